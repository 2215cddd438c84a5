"""Griffe extension: the Sphinx roles of rockarch's docstrings (``:func:`x```, ``:class:`~a.B```,
``:mod:``, ``:data:``, ``:meth:``, ``:attr:``) become cross-references of the API reference, and
their citations of docs/theory.md (``docs/theory.md §8``, ``theory.md Eq. 7.2``) links to the
section of the Theory page.

A name is resolved as Sphinx does, in the scope of the object whose docstring cites it
(module, class, function), or as a full dotted path. A resolved public name becomes a link
to its entry (an optional one: a name that the reference does not render, e.g. a private
helper, stays plain code); a name that resolves nowhere is a warning, so ``mkdocs build
--strict`` (``make docs``) fails on a broken reference.
"""

from __future__ import annotations

import html
import importlib.util
import logging
import re
from pathlib import Path

import griffe

log = logging.getLogger("mkdocs.plugins.rockarch.sphinx_roles")
THEORY = Path(__file__).resolve().parents[1] / "theory.md"
#: A citation of docs/theory.md: "docs/theory.md §8", "theory §11.1", "theory.md, Eq. 7.2",
#: "docs/theory.md Eqs. (4.1)–(4.3)", "docs/theory.md Sect. 0".
CITATION = re.compile(r"(?:docs/)?theory(?:\.md)?,?\s+(?:§\s?|Sects?\.\s*|Eqs?\.\s*\(?)"
                      r"(\d+)(\.\d+)?")
ROLE = re.compile(r":(?:py:)?(func|class|mod|data|meth|attr|obj|exc|const):`(~?)([\w.]+?)(\(\))?`")


def _objects(obj):
    yield obj
    for member in obj.members.values():
        if not member.is_alias:
            yield from _objects(member)


def _resolve(obj, name: str, loader) -> str | None:
    """The full path of ``name`` cited in ``obj``'s docstring, or None."""
    collection = loader.modules_collection
    candidates = [name]
    scope = obj
    while scope is not None:  # the object's own scope, then its parents'
        candidates.append(f"{scope.path}.{name}")
        scope = scope.parent
    head, _, rest = name.partition(".")
    try:
        resolved = obj.resolve(head)
        candidates.append(resolved + ("." + rest if rest else ""))
    except Exception:  # noqa: BLE001 - griffe raises several kinds; unresolved is the answer
        pass
    for path in candidates:
        try:
            target = collection.get_member(path)
        except Exception:  # noqa: BLE001
            continue
        if target is not None:
            return path
    return None


def _sections() -> dict[str, str]:
    """Section number ("8", "11.1") -> the anchor of its heading on the Theory page."""
    from markdown.extensions.toc import slugify

    out = {}
    for m in re.finditer(r"^#{2,3} ((\d+(?:\.\d+)?)\.? .*)$", THEORY.read_text(encoding="utf-8"),
                         flags=re.M):
        out[m.group(2)] = slugify(m.group(1).strip(), "-")
    return out


def _theory_links(text: str, sections: dict[str, str], where: str) -> str:
    """Every citation of docs/theory.md becomes a link to its section (an equation's: the
    section of its number); a "Theory:" line links each of its § numbers."""

    def cite(m):
        whole, sub = m.group(1), m.group(2) or ""
        # "§11.1" is a subsection; "Eq. 7.2" is equation 2 of section 7
        number = whole + sub if m.group(0).find("§") >= 0 or "Sect" in m.group(0) else whole
        anchor = sections.get(number) or sections.get(whole)
        if anchor is None:
            log.warning("%s: docstring cites docs/theory.md section %s, which does not exist",
                        where, number)
            return m.group(0)
        return f"[{m.group(0)}][{anchor}]"

    def theory_line(m):
        def sec(n):
            anchor = sections.get(n.group(1)) or sections.get(n.group(1).split(".")[0])
            return f"[{n.group(0)}][{anchor}]" if anchor else n.group(0)

        line = re.sub(r"(?<!\[)(?:docs/)?theory\.md\s+", "", m.group(0))
        return re.sub(r"§(\d+(?:\.\d+)?)", sec, line)

    text = re.sub(r"^Theory:.*(?:\n(?!\n).*)*", theory_line, text, count=1, flags=re.M)
    return CITATION.sub(cite, text)


class SphinxRoles(griffe.Extension):
    """Rewrite the Sphinx roles of every docstring of the loaded package."""

    def on_package(self, *, pkg, loader, **kwargs) -> None:
        sections = _sections()
        for obj in _objects(pkg):
            if obj.docstring is None:
                continue
            text = obj.docstring.value

            def link(m, obj=obj):
                _, tilde, name, call = m.groups()
                shown = (name.rsplit(".", 1)[-1] if tilde else name) + (call or "")
                path = _resolve(obj, name, loader)
                if path is None and name.split(".")[0] != "rockarch" \
                        and importlib.util.find_spec(name.split(".")[0]) is not None:
                    return f"`{shown}`"  # another library's name (matplotlib, numpy, ...)
                if path is None:
                    log.warning("%s: docstring cites %r, which does not exist",
                                obj.path, m.group(0))
                    return f"`{shown}`"
                return (f'<autoref identifier="{html.escape(path)}" optional>'
                        f"<code>{html.escape(shown)}</code></autoref>")

            obj.docstring.value = _theory_links(ROLE.sub(link, text), sections, obj.path)
