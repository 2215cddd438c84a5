"""One record's incremental dynamic analysis (IDA) as one sweep task: the scan of
ap/ap,min on a grid, full or adaptive, then the bisection of the collapse point
(docs/theory.md Sect. 11.3, Eq. (11.30)).

:func:`rockarch.risk.fragility.ida` runs one :class:`RecordScan` task per record on the sweep
executor (:mod:`rockarch.core.sweep`), so records run side by side with no barrier between
bisection rounds, and each finished record is stored under its own key.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rockarch.core.validate import show
from rockarch.motion.signals import GroundMotion
from rockarch.spectra.oas import refine_boundary


def check_island_step(step) -> int:
    """The adaptive scan's step (:class:`RecordScan`, Eq. (11.30)): an integer >= 1."""
    if isinstance(step, bool) or not isinstance(step, (int, np.integer)) or step < 1:
        raise ValueError(f"the island step must be an integer >= 1, got {show(step)}")
    return int(step)


class TaskBar:
    """A progress bar that advances by one per finished task (sweep.run_chunks counts
    the simulations of a task) or, with None, shows nothing (a record's own bisection)."""

    n = total = 0

    def __init__(self, bar=None) -> None:
        self.bar = bar

    def update(self, n: int = 1) -> None:
        if self.bar is not None:
            self.bar.update(1)

    def refresh(self) -> None:
        pass


@dataclass(frozen=True)
class RecordScan:
    """The whole IDA of one record (scan and bisection, Eq. (11.30)) as one sweep task.

    ``run(records, rows, ratio)``: ``rows`` holds one record index k (every entry),
    ``ratio`` the scan grid followed by one NaN. Record k runs on the grid (below), then its
    collapse point is bisected between the last safe grid value below the first collapse
    and that collapse, by the code of the OAS boundary
    (:func:`rockarch.spectra.oas.refine_boundary`), so the collapse point is that of an OAS
    of the record at this p, bit for bit. Returns the grid's verdicts and responses (NaN:
    not run), and in the last slot whether the record collapses and its collapse ratio
    (NaN: censored). A task holds no barrier: the records of a suite run side by side on
    the executor's workers, each at its own pace.

    The grid: ``island_step`` 1 runs every value (one ``system.run`` call). With
    ``island_step`` s > 1 (the adaptive scan) every value up to the first collapse still
    runs (in batches of the numba threads, from the bottom), so the first collapse and the
    collapse point are those of the full scan; above it, every s-th value and the last
    run, and each safe value found there is widened to its whole safe island on the grid
    (its neighbours run until a collapse). Values not run lie between two collapses at
    most s values apart and are taken as collapse: an island narrower than s grid values
    that falls between them is missed.
    """

    system: object
    p: float
    tol: float
    island_step: int = 1

    @property
    def name(self) -> str:
        return f"IDA {self.system.name} p={self.p:g}"

    def run(self, records: Sequence[GroundMotion], rows, ratio):
        rows = np.ravel(np.asarray(rows, dtype=float))
        ks = np.unique(rows)
        if ks.size != 1:
            raise ValueError("a record scan runs one record")
        motion = records[int(ks[0])]
        grid = np.ravel(np.asarray(ratio, dtype=float))[:-1]
        over, resp = self._scan(motion, grid)

        def run(tasks):
            return [self.system.run(motion, np.full(np.size(r), self.p), np.ravel(r))
                    for _, r in tasks]

        collapse = refine_boundary(run, np.array([self.p]), grid, over[None], self.tol,
                                    TaskBar(), 1)[0]
        return np.append(over, bool(np.isfinite(collapse))), np.append(resp, collapse)

    def _scan(self, motion: GroundMotion, grid: np.ndarray):
        """(verdicts, responses) on the grid; responses NaN where not run."""
        n, s = grid.size, int(self.island_step)
        over = np.zeros(n, dtype=bool)
        resp = np.full(n, np.nan)

        def evaluate(idx):
            if idx.size:
                o, r = self.system.run(motion, np.full(idx.size, self.p), grid[idx])
                over[idx], resp[idx] = o, r

        if s == 1:
            evaluate(np.arange(n))
            return over, resp
        import numba

        batch, i = max(numba.get_num_threads(), 1), 0
        while i < n and not over.any():  # bottom up to the first collapse
            evaluate(np.arange(i, min(i + batch, n)))
            i += batch
        if not over.any():
            return over, resp
        first = int(over.argmax())
        evaluate(np.setdiff1d(np.append(np.arange(first + s, n, s), n - 1),
                              np.flatnonzero(~np.isnan(resp))))
        while True:  # widen every safe value above the first collapse to its island
            done = ~np.isnan(resp)
            safe = np.flatnonzero(done & ~over)
            near = np.union1d(safe - 1, safe + 1)
            near = near[(near > first) & (near < n)]
            near = near[~done[near]]
            if not near.size:
                break
            evaluate(near)
        over[np.isnan(resp)] = True
        return over, resp

    def attrs(self) -> dict:
        return {"p": self.p, "tol": self.tol, "island_step": self.island_step,
                **self.system.attrs()}
