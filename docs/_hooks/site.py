"""MkDocs hooks of rockarch's site (mkdocs.yml, ``make docs``).

After the build, MathJax (the copy shipped by the ``django-static-mathjax`` package, a
dependency of the ``docs`` extra) is copied into ``site/assets/mathjax/``, so the
equations render without a network connection.
"""

from __future__ import annotations

import shutil
from pathlib import Path

#: What the pages load: the TeX-input, CommonHTML-output component, its fonts, the TeX
#: extensions it loads on demand, the menu and the accessibility parts it may load.
MATHJAX_PARTS = ("tex-chtml.js", "output/chtml/fonts/woff-v2", "input/tex/extensions", "ui",
                 "a11y")


def on_post_build(config, **kwargs) -> None:
    import mathjax  # the django-static-mathjax package (MathJax 3, Apache 2.0)

    src = Path(mathjax.__file__).parent / "static" / "mathjax"
    dest = Path(config["site_dir"]) / "assets" / "mathjax"
    for part in MATHJAX_PARTS:
        s, d = src / "es5" / part, dest / part
        d.parent.mkdir(parents=True, exist_ok=True)
        if s.is_dir():
            shutil.copytree(s, d, dirs_exist_ok=True)
        else:
            shutil.copy2(s, d)
    shutil.copy2(src / "LICENSE", dest / "LICENSE")


#: The packages of the API reference, the stages of docs/architecture.md, lowest first.
PACKAGES = ("core", "motion", "arch", "rocking", "mdof", "systems", "spectra", "risk",
            "design", "output", "paper", "cli")
SRC = Path(__file__).resolve().parents[2] / "src" / "rockarch"
TABLE = "<!-- packages: the table is made from the package docstrings (docs/_hooks/site.py) -->"


def package_docstring(name: str) -> str:
    import ast

    path = SRC / name / "__init__.py"
    path = path if path.exists() else SRC / f"{name}.py"
    return ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""


def theory_sections(doc: str) -> list[str]:
    """The § numbers of a docstring's "Theory:" paragraph."""
    import re

    m = re.search(r"^Theory:(.*(?:\n(?!\n).*)*)", doc, flags=re.M)
    return re.findall(r"§(\d+(?:\.\d+)?)", m.group(1)) if m else []


def _package_table() -> str:
    import re

    from markdown.extensions.toc import slugify

    theory = (Path(__file__).resolve().parents[1] / "theory.md").read_text(encoding="utf-8")
    anchors = {m.group(2): slugify(m.group(1).strip(), "-") for m in
               re.finditer(r"^#{2,3} ((\d+(?:\.\d+)?)\.? .*)$", theory, flags=re.M)}
    rows = ["| package | purpose | theory |", "|---|---|---|"]
    for name in PACKAGES:
        doc = package_docstring(name)
        purpose = doc.splitlines()[0].replace("``", "`")
        secs = ", ".join(f"[§{s}](../theory.md#{anchors.get(s) or anchors[s.split('.')[0]]})"
                         for s in theory_sections(doc)) or "–"
        rows.append(f"| [`rockarch.{name}`]({name}.md) | {purpose} | {secs} |")
    return "\n".join(rows)


def on_page_markdown(markdown: str, page, config, files) -> str:
    if page.file.src_uri == "api/index.md":
        return markdown.replace(TABLE, _package_table())
    return markdown
