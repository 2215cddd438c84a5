"""One record's incremental dynamic analysis (IDA) as one sweep task: the scan of
ap/ap,min on a grid, full or adaptive, the search for collapse islands below the grid's
first collapse on a finer step, then the bisection of the collapse point
(docs/theory.md Sect. 11.3, Eqs. (11.30) and (11.30a)).

:func:`rockarch.risk.fragility.ida` runs one :class:`RecordScan` task per record on the sweep
executor (:mod:`rockarch.core.sweep`), so records run side by side with no barrier between
bisection rounds, and each finished record is stored under its own key.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from rockarch.core.constants import OAS_TOL
from rockarch.core.validate import show
from rockarch.motion.signals import GroundMotion
from rockarch.spectra.oas import refine_boundary

#: The search step of ap/ap,min below the grid's first collapse for systems whose
#: simulation is cheap (every kind but ``mdof``): the step of the fine scan that the
#: collapse islands of rocking IDA curves need (docs/sites.md, "Collapse islands").
SEARCH_STEP = 0.0025
#: Values of the search per ``system.run`` call and numba thread (a call costs about one
#: block simulation; the values run above the first collapse are the overshoot).
SEARCH_BATCH = 16


#: The IDA scan grid (Eq. (11.30)) of systems simulated by an SDOF kernel: this many values
#: of ap/ap,min from 1 to the scan limit, the lowest collapse bisected to ``OAS_TOL``: the
#: grid of ``rockarch oas``.
SCAN_STEPS = 81
#: The IDA scan of MDOF assemblies: values and bisection tolerance. A simulation of an
#: assembly costs seconds, and a record that never collapses runs every value to its end
#: (docs/mdof.md, "The IDA scan of assemblies").
MDOF_SCAN = (17, 0.01)
#: The largest search step of MDOF assemblies: that of the block's grid (0.05), run below
#: a collapse of their coarser grid only (Eq. (11.30a)), so that their collapse points are
#: at least those of the 81-value scan (docs/mdof.md measures it). A single block in the
#: contact engine (~40 ms a simulation of a 30 s record) is searched every SEARCH_STEP, as
#: the block's own IDA is; two blocks with friction already cost ~0.3 s a simulation, and
#: a search every 0.005 took 2 min on the two bundled records.
MDOF_SEARCH_STEP = 0.05


def costly(system) -> bool:
    """Whether a simulation of ``system`` costs seconds (MDOF assemblies) rather than
    ~0.2 ms (the SDOF kernels: block, frame, sdof, fourhinge)."""
    from rockarch.systems import MDOFSystem

    return isinstance(system, MDOFSystem)


def default_scan(system) -> tuple[int, float]:
    """(values, bisection tolerance) of the IDA scan of ``system`` when none is given:
    :data:`SCAN_STEPS` and ``OAS_TOL`` for the SDOF kinds, :data:`MDOF_SCAN` for MDOF
    assemblies (Eq. (11.30))."""
    return MDOF_SCAN if costly(system) else (SCAN_STEPS, OAS_TOL)


def check_search_step(step) -> float:
    """The search step of :class:`RecordScan` (ratio units): a finite number >= 0 (0: off)."""
    if isinstance(step, bool):
        raise ValueError(f"the search step must be a number >= 0, got {step!r}")
    try:
        value = float(step)
    except (TypeError, ValueError):
        raise ValueError(f"the search step must be a number >= 0, got {step!r}") from None
    if not (math.isfinite(value) and value >= 0):
        raise ValueError(f"the search step must be a finite number >= 0, got {step!r}")
    return value


def default_search_step(system) -> float:
    """:data:`SEARCH_STEP` for systems simulated by an SDOF kernel (block, frame, sdof,
    fourhinge: ~0.2 ms a simulation) and for a single block in the contact engine;
    :data:`MDOF_SEARCH_STEP` for MDOF assemblies of several blocks (~0.1–5 s a simulation;
    searched below a collapse only, :class:`RecordScan`)."""
    if costly(system) and len(system.assembly.mass) > 1:
        return MDOF_SEARCH_STEP
    return SEARCH_STEP


def check_island_step(step) -> int:
    """The adaptive scan's step (:class:`RecordScan`, Eq. (11.30)): an integer >= 1."""
    if isinstance(step, bool) or not isinstance(step, (int, np.integer)) or step < 1:
        raise ValueError(f"the island step must be an integer >= 1, got {show(step)}")
    return int(step)


class TaskBar:
    """A progress bar that advances by one per finished task (sweep.run_chunks counts
    the simulations of a task) or, with None, shows nothing (a record's own bisection).
    ``line`` (e.g. a line on stderr where no bar is shown) gets ``"LABEL: record k/n done
    (T s)"`` for each finished task, stored ones included."""

    n = total = 0

    def __init__(self, bar=None, line: Callable[[str], None] | None = None,
                 label: str = "IDA", total: int = 0) -> None:
        self.bar, self.line, self.label, self.n_tasks = bar, line, label, total
        self.done, self.t0 = 0, time.perf_counter()

    def update(self, n: int = 1) -> None:
        if self.bar is not None:
            self.bar.update(1)
        self.done += 1
        if self.line is not None:
            self.line(f"{self.label}: record {self.done}/{self.n_tasks} done "
                      f"({time.perf_counter() - self.t0:.0f} s)")

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

    The search (``search_step`` h > 0, Eq. (11.30a)): after the grid's collapse point
    (the OAS boundary b, bisected), collapse islands narrower than the grid's step are
    looked for on the values grid[0] + k·h below b (the whole grid if none), from the
    bottom up, in batches, until one collapses; the collapse point is then bisected
    between the last safe value of the search and that collapse. So the collapse point is
    never above b, and equals it when the search finds nothing below. An island narrower
    than h that falls between two values of the search is missed. h = 0: the grid alone
    (the collapse point is b, bit for bit). For a :func:`costly` system (MDOF) the search
    runs below a collapse of the grid only (a record safe on the whole grid stays
    censored: its search would run every value to the end of the record), one value per
    numba thread at a time.
    """

    system: object
    p: float
    tol: float
    island_step: int = 1
    search_step: float = 0.0

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

        def bisect(ratios, verdicts):
            return refine_boundary(run, np.array([self.p]), ratios, verdicts[None], self.tol,
                                   TaskBar(), 1)[0]

        collapse = bisect(grid, over)  # the record's OAS boundary at p
        bracket = self._search(motion, grid, over, collapse)
        if bracket is not None:  # a collapse island below it: the first collapse found
            collapse = bisect(*bracket)
        return np.append(over, bool(np.isfinite(collapse))), np.append(resp, collapse)

    def _search(self, motion: GroundMotion, grid: np.ndarray, over: np.ndarray,
                boundary: float):
        """The bracket (ratios, verdicts) of the bisection of a collapse below the grid's
        ``boundary`` (bisected; NaN: censored): the first collapse among the values
        grid[0] + k·h below it and the value before it (safe), or None (no search, or no
        collapse found below the boundary)."""
        h = float(self.search_step)
        expensive = costly(self.system)
        if h <= 0 or grid.size == 0 or (expensive and not np.isfinite(boundary)):
            return None
        c = int(over.argmax()) if over.any() else grid.size
        top = boundary if np.isfinite(boundary) else grid[-1]
        # the search values below the boundary, not on the grid (those ran); rounded as
        # the grid of the CLI is, so that 1.7 is 1.7
        k = np.arange(int(math.floor((top - grid[0]) / h + 1e-9)) + 1)
        values = np.round(grid[0] + h * k, 12)
        values = values[(values < top) if np.isfinite(boundary) else (values <= top)]
        safe = grid[:c]
        values = np.setdiff1d(values, safe)
        import numba

        batch = (1 if expensive else SEARCH_BATCH) * max(numba.get_num_threads(), 1)
        for i in range(0, values.size, batch):
            chunk = values[i:i + batch]
            o, _ = self.system.run(motion, np.full(chunk.size, self.p), chunk)
            o = np.asarray(o, dtype=bool)
            if o.any():
                found = float(chunk[int(o.argmax())])
                ratios = np.union1d(values, safe)  # every value run below it is safe
                below = ratios[ratios < found]
                if below.size == 0:
                    return np.array([found]), np.array([True])
                return np.array([below[-1], found]), np.array([False, True])
        return None

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
        out = {"p": self.p, "tol": self.tol, "island_step": self.island_step,
               **self.system.attrs()}
        if self.search_step > 0:  # keys of stores written without a search stay valid
            out["search_step"] = self.search_step
        return out
