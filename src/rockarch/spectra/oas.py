"""Overturning acceleration spectra (OAS): the safe/unsafe map over p × ap/ap,min.

For one ground-motion *shape* (a pulse of fixed period, or one record), a structure with
frequency parameter p is excited with peak ground acceleration ap = ratio·ap,min
(docs/theory.md §2, Eq. (2.1); paper Fig. 2). The OAS is the boolean map
``overturned(p, ratio)``; its boundary is the lowest overturning ratio per p (Eq. (2.2)),
refined by bisection below the first overturning grid cell. The map is kept whole: safe
islands above the boundary (real for records) are never filled in.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Protocol

import numpy as np
from tqdm.auto import tqdm

from rockarch.core import __version__, sweep
from rockarch.core.console import bar_rows, on_terminal
from rockarch.core.constants import OAS_TOL as TOL
from rockarch.core.paths import atomic_write
from rockarch.core.validate import tolerance
from rockarch.motion.signals import GroundMotion

if TYPE_CHECKING:  # xarray (half a second to import) where a dataset is made or read
    import xarray as xr


class OASSystem(Protocol):
    """What an OAS needs from a structure (:mod:`rockarch.systems` builds them)."""

    name: str

    def run(self, motion: GroundMotion, p: np.ndarray, ratio: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
        """Return (overturned, max response / its overturning limit) for each pair."""

    def attrs(self) -> dict:
        """Parameters to store with the result (plain numbers and strings)."""


#: Units of the numeric dataset attributes rockarch writes, by name without a ``system_``
#: prefix ("1": dimensionless). A file lists those it holds in its ``attribute_units``.
ATTR_UNITS = {
    "alpha": "rad", "delta": "rad", "delta_ref": "rad",
    "g": "m/s2", "ap_min": "m/s2", "ap_min_assembly": "m/s2", "ap_min_lp": "m/s2",
    "p": "1/s", "p_ref": "1/s", "p_assembly": "1/s", "p_column": "1/s",
    "t_free": "s", "tm_site": "s",
    "size_ref": "m", "span": "m", "rise": "m", "thickness": "m", "pier_height": "m",
    "pier_width": "m",
    "restitution": "1", "e_plus": "1", "e_minus": "1", "h_factor": "1", "eps_rest": "1",
    "gap_tol": "1", "friction_min": "1", "tolerance": "1", "c1": "1", "c2": "1",
    "impact_coeff": "1", "percentile": "%", "percentile_characteristic": "%",
}


def note_units(ds: xr.Dataset) -> xr.Dataset:
    """Set ``ds.attrs["attribute_units"]``: ``"name: unit; ..."`` for every numeric attribute
    of :data:`ATTR_UNITS` that ``ds`` holds (SI; "1" dimensionless), so that a file says the
    units of ``system_alpha``, ``system_g``, ``alpha``, ... itself. Returns ``ds``."""
    units = [f"{k}: {ATTR_UNITS[k.removeprefix('system_')]}" for k, v in ds.attrs.items()
             if k.removeprefix("system_") in ATTR_UNITS and not isinstance(v, str)]
    ds.attrs["attribute_units"] = "; ".join(units)
    return ds


def _grid(name: str, values) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values, dtype=float))
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D list of numbers")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} values must be finite")
    if name == "p" and np.any(arr <= 0):
        raise ValueError(f"p values must be > 0 [1/s], got {arr[arr <= 0][0]:g}")
    if np.any(np.diff(arr) <= 0):
        raise ValueError(f"{name} values must be strictly increasing")
    return arr


def compute_oas(system: OASSystem, motion: GroundMotion, p, ratio, *, tol: float = TOL,
                progress: bool | None = None, chunks: int = 32, executor=None,
                store=None) -> xr.Dataset:
    """OAS of ``system`` for the motion's shape on the grid ``p`` × ``ratio``.

    The map of docs/theory.md §2: Eq. (2.1) scales the motion, Eq. (2.2) defines the
    boundary.

    Parameters
    ----------
    system : OASSystem
        E.g. :func:`rockarch.systems.system`'s result.
    motion : GroundMotion
        Its shape is used; each run scales it to a peak of ratio·ap,min.
    p, ratio : array-like
        Strictly increasing grids [1/s] and [-].
    tol : float
        Bisection tolerance of the boundary (ratio units); 0 disables the refinement and
        the boundary is the first overturning grid value.
    progress : bool or None
        Show a progress bar on stderr (None: only if stderr is a terminal, so that a log
        file gets no bar).
    chunks : int
        The grid is run in this many chunks of rows (p values); the bisection rounds are
        split the same way.
    executor : None, str or rockarch.core.sweep.Executor
        Where the chunks run: None (default) in this process with numba threads on every
        core; ``"serial"`` (the same, chunk after chunk) or ``"processes"`` (a pool of local
        processes, one per core; started and closed here); or an
        :class:`~rockarch.core.sweep.Executor` to reuse (it is not closed here). Dask needs
        an Executor object, not the string ``"dask"`` (a ValueError):
        ``Executor(dask_workers=n)`` starts a ``LocalCluster`` of n worker processes,
        ``Executor(scheduler="tcp://HOST:PORT")`` connects to a running scheduler; use it
        as a context manager (``with Executor(dask_workers=4) as ex: compute_oas(...,
        executor=ex)``) so that the cluster is stopped. See docs/sweeps.md.
    store : None, bool, path or rockarch.core.sweep.Store
        Resumable store of finished chunks (None/False: none; True: the default cache
        directory). A rerun reuses every stored chunk; results are bit-identical.

    Returns
    -------
    xarray.Dataset
        ``overturned`` (p, ratio) bool, ``max_response`` (p, ratio) = max |u|/u_limit,
        ``boundary`` (p) = lowest overturning ratio (NaN if none in range).
    """
    p = _grid("p", p)
    ratio = _grid("ratio", ratio)
    if np.any(ratio < 0):
        raise ValueError("ratio values must be >= 0")
    tol = tolerance("tol", tol)
    n_p, n_r = p.size, ratio.size
    sweep.check_simulations(n_p * n_r, f"{n_p} p × {n_r} ratio values")
    over = np.zeros((n_p, n_r), dtype=bool)
    resp = np.zeros((n_p, n_r))
    rows = np.array_split(np.arange(n_p), min(max(chunks, 1), n_p))
    n_bisect = 0
    if tol > 0:
        width = np.diff(np.concatenate([[min(1.0, ratio[0])], ratio])).max()
        n_bisect = max(int(math.ceil(math.log2(max(width, tol) / tol))), 0)
    store = sweep.as_store(store)
    executor, owned = sweep.as_executor(executor)

    def run(tasks):
        return sweep.run_chunks(system, motion, tasks, executor=executor, store=store,
                                bar=bar)

    try:
        with tqdm(total=n_p * n_r + n_bisect * n_p, desc=f"OAS {system.name}", unit="sim",
                  disable=not on_terminal(progress), leave=False, nrows=bar_rows()) as bar:
            grid = [np.meshgrid(p[idx], ratio, indexing="ij") for idx in rows]
            for idx, (o, m) in zip(rows, run(grid), strict=True):
                over[idx], resp[idx] = o, m
            boundary = refine_boundary(run, p, ratio, over, tol, bar, len(rows))
    finally:
        if owned:
            executor.close()
    import xarray as xr

    ds = xr.Dataset(
        {
            "overturned": (("p", "ratio"), over),
            "max_response": (("p", "ratio"), resp),
            "boundary": (("p",), boundary),
        },
        coords={"p": p, "ratio": ratio},
    )
    ds["p"].attrs.update(units="1/s", long_name="frequency parameter p")
    ds["ratio"].attrs.update(units="1", long_name="ap / ap,min")
    ds["boundary"].attrs.update(units="1", long_name="lowest overturning ap/ap,min",
                                tolerance=tol)
    ds["max_response"].attrs.update(units="1", long_name="max |theta| / alpha (or u/delta)")
    attrs = {f"system_{k}": (v if not isinstance(v, bool) else int(v))
             for k, v in system.attrs().items()}
    ds.attrs.update(attrs)
    ds.attrs.update(system=system.name, motion=motion.name,
                    motion_sha256=motion.fingerprint(), rockarch_version=__version__,
                    title=f"OAS of {system.name} for {motion.name}")
    return note_units(ds)


def refine_boundary(run, p, ratio, over, tol, bar, chunks) -> np.ndarray:
    """Lowest overturning ratio per p: bisection between the last safe value below the
    first overturning grid cell and that cell (ratio ≤ 1 never moves, so 1 brackets it).

    ``run(chunks of (p, ratio) pairs)`` gives, per chunk, a tuple whose first item is the
    overturned flags; ``over`` is the grid's (p, ratio) map; bisection to ``tol`` (0: the
    grid cell); ``bar`` a progress bar (tqdm-like), ``chunks`` how many tasks per round.
    Used by the OAS here and by the per-record IDA scan (:mod:`rockarch.risk.record_scan`)."""
    first = np.where(over.any(axis=1), over.argmax(axis=1), -1)
    has = first >= 0
    hi = np.where(has, ratio[np.maximum(first, 0)], np.nan)
    lo = np.where(first > 0, ratio[np.maximum(first - 1, 0)], min(1.0, ratio[0]))
    lo = np.where(has, lo, np.nan)
    if tol <= 0 or not has.any():
        return hi
    active = has & (hi - lo > tol)
    while active.any():
        mid = 0.5 * (lo[active] + hi[active])
        idx = np.flatnonzero(active)
        # chunks of >= 16 values (one simulation each), as many as the grid's chunks
        parts = np.array_split(np.arange(idx.size), max(min(chunks, idx.size // 16), 1))
        res = run([(p[idx[k]], mid[k]) for k in parts])
        o = np.concatenate([np.asarray(r[0], dtype=bool) for r in res])
        hi[idx[o]] = mid[o]
        lo[idx[~o]] = mid[~o]
        active = has & (hi - lo > tol)
    bar.total = bar.n
    bar.refresh()
    return hi


def boundary_of(ds: xr.Dataset) -> np.ndarray:
    """The boundary (lowest overturning ratio per p) of an OAS dataset."""
    return ds["boundary"].values


def save(ds: xr.Dataset, path) -> None:
    """Write an OAS dataset to NetCDF atomically (a temporary file renamed on success)."""
    atomic_write(path, ds.to_netcdf)


def read_netcdf(path) -> xr.Dataset:
    """Read a NetCDF file into memory; a missing or unreadable file is a ValueError. A
    boolean ``overturned`` map (stored as bytes) comes back as bool."""
    from pathlib import Path

    path = Path(path)
    if not path.exists():
        raise ValueError(f"{path}: no such file")
    if path.is_file():
        with path.open("rb") as f:
            head = f.read(8)
        if not (head.startswith(b"CDF") or head == b"\x89HDF\r\n\x1a\n"):
            raise ValueError(f"{path}: not a NetCDF file (rockarch writes them with --out "
                             "FILE.nc or --save-site FILE.nc)")
    import xarray as xr

    try:
        ds = xr.load_dataset(path)
    except Exception as exc:  # noqa: BLE001 - any reader failure is a bad file for the user
        why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise ValueError(f"{path}: not a readable NetCDF file ({why[:160]})") from None
    if "overturned" in ds:
        ds["overturned"] = ds["overturned"].astype(bool)
    return ds


def load(path) -> xr.Dataset:
    """Read an OAS dataset written by :func:`save` (``rockarch oas --out``).

    Parameters
    ----------
    path : str or path
        The NetCDF file.

    Returns
    -------
    xarray.Dataset
        The dataset of :func:`compute_oas`, read into memory.

    Raises
    ------
    ValueError
        If the file is missing or not NetCDF, has no ``overturned``/``boundary`` over
        (p, ratio), or is a rockarch file of another kind (a site OAS, with its ``record``
        axis: read it with :func:`rockarch.spectra.site.load`).
    """
    ds = read_netcdf(path)
    kind = ds.attrs.get("kind")
    if kind is not None or "record" in ds.dims:
        what = ("a rockarch site OAS file: read it with rockarch.spectra.site.load"
                if kind == "rockarch-site-oas" or kind is None
                else f"a file of kind {kind!r}")
        raise ValueError(f"{path}: not an OAS file but {what} (an OAS file is written by "
                         "`rockarch oas --out` or rockarch.spectra.oas.save)")
    if "overturned" not in ds or "boundary" not in ds:
        raise ValueError(f"{path}: not an OAS file (no 'overturned'/'boundary' variables)")
    if ds["overturned"].dims != ("p", "ratio") or ds["boundary"].dims != ("p",):
        raise ValueError(f"{path}: not an OAS file ('overturned' is over "
                         f"{ds['overturned'].dims}, an OAS's over ('p', 'ratio'))")
    return ds
