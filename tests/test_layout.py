"""The package tree is its module map (docs/architecture.md): top-level entries, one-line
package docstrings, imports that only go down the stages, and no import circles."""

from __future__ import annotations

import ast
from pathlib import Path

import rockarch

PKG = Path(rockarch.__file__).resolve().parent

#: The stages, lowest first (docs/architecture.md): a module may import its own stage and
#: the ones before it, never a later one, not even inside a function.
STAGES = ["core", "motion", "arch", "rocking", "mdof", "systems", "spectra", "risk", "design",
          "output", "paper", "cli"]


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG).with_suffix("")
        parts = ["rockarch", *rel.parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _stage(module: str) -> int | None:
    parts = module.split(".")
    if len(parts) < 2:
        return None  # the front door itself
    return STAGES.index(parts[1])


def _imports(module: str, path: Path) -> list[tuple[str, bool]]:
    """(imported rockarch module, at module level?) of every import statement."""
    tree = ast.parse(path.read_text())
    top = {id(n) for n in tree.body}
    found = []
    for node in ast.walk(tree):
        names = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            base = node.module
            names = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base
                     for a in node.names]
        for name in names:
            if name.split(".")[0] == "rockarch" and name != "rockarch":
                found.append((name, id(node) in top))
    return found


def test_at_most_twelve_top_level_entries_each_package_says_what_lives_there():
    entries = sorted(p.name for p in PKG.iterdir()
                     if p.name not in {"__init__.py", "__pycache__"})
    assert len(entries) <= 12, entries
    assert {e.removesuffix(".py") for e in entries} == set(STAGES)
    for init in PKG.rglob("__init__.py"):
        doc = ast.get_docstring(ast.parse(init.read_text()))
        assert doc and doc.strip(), f"{init.relative_to(PKG)} has no docstring"


def test_imports_only_go_down_the_stages():
    upward = []
    for module, path in MODULES.items():
        own = _stage(module)
        if own is None:
            continue
        for name, _ in _imports(module, path):
            if _stage(name) > own:
                upward.append(f"{module} imports {name}")
    assert upward == []


def test_no_import_circles():
    graph = {m: {n for n, top in _imports(m, p) if top and n in MODULES}
             for m, p in MODULES.items()}
    state: dict[str, int] = {}
    cycles = []

    def visit(m: str, stack: list[str]) -> None:
        state[m] = 1
        for n in graph.get(m, ()):
            if state.get(n) == 1:
                cycles.append(" -> ".join([*stack[stack.index(n):], n]))
            elif n not in state:
                visit(n, [*stack, n])
        state[m] = 2

    for m in graph:
        if m not in state:
            visit(m, [m])
    assert sorted(set(cycles)) == []
