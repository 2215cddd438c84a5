"""Paper Figs. 2 and 3: the block and column claims the design method rests on.

Fig. 2: OAS of a slender rigid block for a sine pulse and El Centro 1940; Fig. 3a: the slender
block against less slender ones; Fig. 3b: columns of equal blocks (MDOF engine) against the
monolith of the same size. Prints the rows docs/validation.md quotes (share of p where each
claim holds) and writes fig2.png, fig3a.png, fig3b.png.

Run:  .venv/bin/python examples/background.py --out docs/img [--figs 2,3a,3b]
      (Fig. 3b, MDOF columns under a record, takes several minutes)
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from rockarch.paper import background


def _cells(ps: list[float]) -> str:
    return ", ".join(f"{x:g}" for x in ps) if ps else "–"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("docs/img"))
    ap.add_argument("--figs", default="2,3a,3b", help="which figures (comma-separated)")
    args = ap.parse_args()
    figs = set(args.figs.split(","))
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    if "2" in figs:
        _fig2(args.out)
    if "3a" in figs:
        _fig3a(args.out)
    if "3b" in figs:
        _fig3b(args.out)
    print(f"\nwrote Figs. {args.figs} in {args.out} ({time.perf_counter() - t0:.0f} s)")


def _table(title: str, rows: list[dict], cells: str) -> None:
    """Print a markdown-ish table: ``cells`` is a format string over each row's keys."""
    print(title)
    for r in rows:
        print("| " + cells.format(**r) + " |")


def _fig2(out: Path) -> None:
    rows = [dict(r, pct=100 * r["overturned_share"]) for r in background.fig2(out / "fig2.png")]
    _table("Fig. 2 | signal | alpha | share of the map overturned | p with a safe island", rows,
           "{signal} | {alpha} | {pct:.0f} % | {p_with_safe_islands} of {n_p}")


def _fig3a(out: Path) -> None:
    rows = [dict(r, pct=100 * r["slender_safe"], cells=_cells(r["p_not"]))
            for r in background.fig3a(out / "fig3a.png")]
    _table("\nFig. 3a | signal | less slender alpha | p where the slender block is lower/equal "
           "| p where not", rows, "{signal} | {alpha} | {pct:.0f} % | {cells}")


def _fig3b(out: Path) -> None:
    rows = [dict(r, safer=100 * r["column_safer"], weaker=100 * r["column_weaker"],
                 cells=_cells(r["p_weaker"])) for r in background.fig3b(out / "fig3b.png")]
    _table("\nFig. 3b | signal | blocks | column at least as safe | column weaker | mean rel. "
           "| p where weaker", rows,
           "{signal} | {blocks} | {safer:.0f} % | {weaker:.0f} % | {mean_rel:+.3f} | {cells}")


if __name__ == "__main__":
    main()
