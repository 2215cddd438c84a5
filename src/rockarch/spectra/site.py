"""Site OAS: the block OAS of a set of records and their characteristic curve (paper Sect. 9).

For each record the OAS of a slender rigid block is computed (records scaled to
PGA = ratio·ap,min, as in :mod:`rockarch.spectra.oas`); the site's curves are the **envelope**
(the lowest overturning ratio over all records, at each p) and a chosen **percentile** of
the records' boundaries (a record that does not overturn within the ratio range counts as
+inf). The result is a NetCDF file of kind ``rockarch-site-oas`` with the records' names,
SHA-256 hashes and how they were read (``--units``, ``--dt``), reused by
:mod:`rockarch.design`; :func:`check_records` reads the records again as the file says.
"""

from __future__ import annotations

import hashlib
import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from rockarch import systems
from rockarch.core import __version__, sweep
from rockarch.core.console import on_terminal
from rockarch.core.constants import G_STANDARD, OAS_TOL, g_label
from rockarch.core.sweep.limits import check_simulations
from rockarch.motion.signals import GroundMotion
from rockarch.motion.suite import (
    PGA_RANGE,
    Suite,
    SuiteRecord,
    as_motions,
    check_distinct,
    read_suite,
    record_files,
)
from rockarch.spectra import oas as spectra

if TYPE_CHECKING:  # xarray (half a second to import) where a dataset is made or read
    import xarray as xr

KIND = "rockarch-site-oas"
FORMAT_VERSION = 1
#: Default slenderness of the site's block: slender (the paper's characteristic OAS).
ALPHA = 0.05


#: Site curves a site OAS may hold (``rockarch design --curve``).
CURVES = ("envelope", "characteristic", "normalised", "simplified")

#: Record formats read in the units of ``--units`` (and, single-column, at the step of
#: ``--dt``); the others state their own units and time step.
TEXT_FORMATS = ("two-column", "single-column")


def record_paths(paths) -> list[Path]:
    """Expand files and folders (``.AT2`` and two-column records inside, sorted) into record
    files: :func:`rockarch.motion.suite.record_files` (a ``_SearchResults.csv`` is skipped)."""

    return record_files(paths)[0]


def record_sha256(rec: SuiteRecord) -> str:
    """The SHA-256 a site file holds for a record: that of its file, as read from disk (of
    its samples, :meth:`~rockarch.motion.signals.GroundMotion.fingerprint`, where it has no
    file, e.g. a motion built in Python).

    Parameters
    ----------
    rec : SuiteRecord
        A record of a :class:`~rockarch.motion.suite.Suite`.

    Returns
    -------
    str
        64 hexadecimal digits.
    """
    if rec.path:
        return hashlib.sha256(Path(rec.path).read_bytes()).hexdigest()
    return rec.motion.fingerprint()


def load_records(paths, units: str | None = None, log: Callable[[str], None] | None = None,
                 *, dt: float | None = None) -> tuple[list[GroundMotion], list[str]]:
    """Read the records as a suite (:func:`rockarch.motion.suite.read_suite`: the same folders and
    vertical components left out as every ``--records``; ``dt``: the time step [s] of
    single-column files) and their file hashes; reject implausible PGAs (wrong units) and a
    record given twice (the same samples under two names: it would count twice in the
    percentile). ``log`` receives the suite's notes (a record left out, ...)."""

    motions, hashes = [], []
    suite = read_suite(paths, units=units, dt=dt)
    if log is not None:
        for note in suite.notes:
            log(note)
    check_distinct(suite)
    for rec in suite:
        path, m = Path(rec.path), rec.motion
        lo, hi = PGA_RANGE
        if not lo <= m.pga <= hi:
            raise ValueError(f"{path}: PGA = {m.pga:.4g} m/s² ({m.pga / G_STANDARD:.3g} g, "
                             f"{g_label(G_STANDARD)}) is not plausible: wrong units? (text "
                             "files: --units g, m/s2 or cm/s2)")
        motions.append(m)
        hashes.append(record_sha256(rec))
    return motions, hashes


def read_with(motion: GroundMotion) -> tuple[str, float]:
    """How a record was read: the units (``--units``) and time step (``--dt``) given to the
    reader, as a site file records them.

    Parameters
    ----------
    motion : GroundMotion
        A record read by :func:`rockarch.motion.records.read_record` (or any motion).

    Returns
    -------
    units : str
        The units of a text file's accelerations (two-column or single-column; "m/s2" where
        none were given, the reader's default); "" where the file states its own (.AT2,
        ESM, K-NET, COSMOS) or the motion is not a file's.
    dt : float
        The time step [s] given for a single-column file; NaN where the file gives its own.
    """
    meta = motion.meta or {}
    fmt = meta.get("format")
    if fmt not in TEXT_FORMATS:
        return "", math.nan
    dt = float(meta["dt"]) if fmt == "single-column" else math.nan
    return str(meta.get("units_in_file") or "m/s2"), dt


def curves(boundary, percentile: float) -> tuple[np.ndarray, np.ndarray]:
    """The site's envelope and percentile curves of the records' boundaries (record, ...)
    (docs/theory.md Eq. (2.2), a record that does not overturn within range counting as
    +inf): (min over records, ``percentile`` over records, lower value), +inf left in."""
    inf = np.where(np.isfinite(boundary), boundary, np.inf)
    return inf.min(axis=0), np.percentile(inf, percentile, axis=0, method="lower")


def site_oas(motions: list[GroundMotion], p, ratio, *, alpha: float = ALPHA,
             percentile: float = 50.0, tol: float = OAS_TOL, hashes=None,
             progress: bool | None = None, executor=None, store=None, system=None,
             log: Callable[[str], None] | None = None, **system_kw) -> xr.Dataset:
    """OAS of every record and the site's envelope and percentile curves (Eq. (2.2)).

    The site OAS of the paper's design method (paper Sect. 9).

    ``motions``: the records, a :class:`rockarch.motion.suite.Suite` or GroundMotions.
    ``hashes``: their SHA-256 as the file holds them (default :func:`record_sha256`: a
    Suite's record files, as ``rockarch site-oas`` writes them; a GroundMotion's samples).

    The structure is the slender block of slenderness ``alpha`` (the paper's site OAS), or
    ``system``, any :func:`rockarch.systems.system`: a block gives the same file as by
    ``alpha``; any other structure has the p axis of :func:`rockarch.spectra.oas.compute_oas`
    (docs/theory.md Eq. (11.33): the same shape scaled to each p).

    Returns a Dataset with ``overturned`` (record, p, ratio), ``boundary`` (record, p),
    ``envelope`` (p), ``characteristic`` (p) (the ``percentile`` of the boundaries; a lower
    percentile is more conservative), and the records' names, PGAs, hashes and how each
    was read (``record_units``, ``record_dt``: :func:`read_with`).
    ``executor`` and ``store`` are those of :func:`rockarch.spectra.oas.compute_oas` (one
    executor serves every record: a pool or cluster starts once).
    ``log`` (e.g. ``print`` where no progress bar is shown) gets a line per record done.
    """
    if hashes is None and isinstance(motions, Suite):
        hashes = [record_sha256(rec) for rec in motions]
    motions, _ = as_motions(motions, what="motions")
    if not motions:
        raise ValueError("a site OAS needs at least one record")
    if not 0.0 <= float(percentile) <= 100.0:
        raise ValueError(f"percentile must lie in [0, 100], got {percentile}")
    if system is not None and (alpha != ALPHA or system_kw):
        raise ValueError("give either a system or the block's alpha and settings, not both")
    n_p, n_r = np.size(p), np.size(ratio)
    check_simulations(len(motions) * n_p * n_r,
                      f"{len(motions)} records × {n_p} p × {n_r} ratio values")
    if system is None:
        system = systems.BlockSystem(alpha=alpha, **system_kw)
    block = isinstance(system, systems.BlockSystem)  # the paper's site OAS, as it was
    alpha = system.alpha if block else None

    executor, owned = sweep.as_executor(executor)
    store = sweep.as_store(store)
    progress = on_terminal(progress)
    maps, t0 = [], time.perf_counter()
    try:
        for k, m in enumerate(motions):
            if progress:
                from tqdm.auto import tqdm

                tqdm.write(f"record {k + 1}/{len(motions)}: {m.name}")
            maps.append(spectra.compute_oas(system, m, p, ratio, tol=tol, progress=progress,
                                            executor=executor, store=store))
            if log is not None:
                log(f"site OAS: record {k + 1}/{len(motions)} done: {m.name} "
                    f"({time.perf_counter() - t0:.0f} s)")
    finally:
        if owned:
            executor.close()
    b = np.stack([ds["boundary"].values for ds in maps])
    env, char = curves(b, percentile)
    names = [m.name for m in motions]
    hashes = list(hashes) if hashes is not None else [m.fingerprint() for m in motions]
    read_units, read_dt = zip(*(read_with(m) for m in motions), strict=True)
    import xarray as xr

    ds = xr.Dataset(
        {
            "overturned": (("record", "p", "ratio"),
                           np.stack([d["overturned"].values for d in maps])),
            "boundary": (("record", "p"), b),
            "envelope": (("p",), np.where(np.isfinite(env), env, np.nan)),
            "characteristic": (("p",), np.where(np.isfinite(char), char, np.nan)),
            "record_name": (("record",), np.array(names, dtype=str)),
            "record_sha256": (("record",), np.array(hashes, dtype=str)),
            "record_pga": (("record",), np.array([m.pga for m in motions])),
            "record_units": (("record",), np.array(read_units, dtype=str)),
            "record_dt": (("record",), np.array(read_dt, dtype=float)),
        },
        coords={"record": np.arange(len(motions)), "p": maps[0]["p"].values,
                "ratio": maps[0]["ratio"].values},
    )
    ds["p"].attrs.update(units="1/s", long_name="frequency parameter p")
    ds["ratio"].attrs.update(units="1", long_name="ap / ap,min")
    ds["record"].attrs.update(long_name="record index (its name: record_name)")
    ds["record_name"].attrs.update(long_name="record name (select by name: "
                                             "ds.swap_dims(record='record_name'))")
    ds["record_sha256"].attrs.update(long_name="SHA-256 of the record file (or of its "
                                               "samples)")
    ds["record_pga"].attrs.update(units="m/s2", long_name="peak ground acceleration")
    ds["record_units"].attrs.update(long_name="units the record was read in (--units: text "
                                              "files; empty: the file states its own)")
    ds["record_dt"].attrs.update(units="s", long_name="time step the record was read at "
                                 "(--dt: single-column files; NaN: the file gives its own)")
    ds["overturned"].attrs.update(long_name="overturned at (p, ap/ap,min)")
    ds["boundary"].attrs.update(units="1", long_name="lowest overturning ap/ap,min of each "
                                "record", tolerance=float(tol))
    ds["envelope"].attrs.update(units="1", long_name="lowest overturning ap/ap,min over the "
                                "records")
    ds["characteristic"].attrs.update(units="1", long_name=f"{float(percentile):g} "
                                      "percentile of the records' lowest overturning "
                                      "ap/ap,min")
    ds.attrs.update(kind=KIND, format_version=FORMAT_VERSION, rockarch_version=__version__)
    if not block:  # any structure: its name and parameters, as an OAS file keeps them
        ds.attrs.update({f"system_{k}": (v if not isinstance(v, bool) else int(v))
                         for k, v in system.attrs().items()})
        ds.attrs.update(system=system.name, percentile=float(percentile),
                        tolerance=float(tol), t_free=system.t_free,
                        p_axis="the structure scaled to each p (p ~ 1/sqrt(size), same "
                               f"shape); p of the structure as given: {system.p_ref:.6g} 1/s",
                        title=f"site OAS of {len(motions)} record(s), {system.name}")
        return spectra.note_units(ds)
    ds.attrs.update(alpha=float(alpha), percentile=float(percentile), tolerance=float(tol),
                    t_free=system.t_free, restitution=system.attrs()["restitution"],
                    title=f"site OAS of {len(motions)} record(s), slender block "
                          f"alpha = {alpha:g}")
    return spectra.note_units(ds)


def check_block_site(ds: xr.Dataset, path=None, *, structure: str | None = None
                     ) -> xr.Dataset:
    """The site OAS unchanged if it is a slender block's (what the paper's design method
    and the equivalent SDOF read, docs/theory.md Eqs. (7.2), (11.35)).

    Parameters
    ----------
    ds : xarray.Dataset
        A site OAS (:func:`load`).
    path : path, optional
        Its file, named in the error.
    structure : str, optional
        The structure being designed (e.g. ``system.name``), named in the error apart from
        the file's.

    Returns
    -------
    xarray.Dataset
        ``ds`` itself.

    Raises
    ------
    ValueError
        If ``ds`` is the site OAS of another structure (``site-oas --system``): one line
        naming it and the structure designed, and asking for a block's site OAS or the
        records.
    """
    if "system" in ds.attrs:
        where = f"{path}: " if path is not None else ""
        of = "the design check" if structure is None else f"the design of the {structure}"
        raise ValueError(f"{where}this is the site OAS of {ds.attrs['system']}, not of a "
                         f"slender block: {of} reads a block's site OAS (rockarch site-oas "
                         "without --system): give one, or --records")
    return ds


def save(ds: xr.Dataset, path) -> None:
    """Write a site OAS to NetCDF atomically."""
    spectra.save(ds, path)


def load(path) -> xr.Dataset:
    """Read a site OAS file, checking its kind and version."""
    ds = spectra.read_netcdf(path)
    kind = ds.attrs.get("kind")
    if kind != KIND:
        raise ValueError(f"{path}: not a rockarch site OAS file (kind = {kind!r}; make one "
                         "with `rockarch site-oas`)")
    version = int(ds.attrs.get("format_version", -1))
    if version != FORMAT_VERSION:
        raise ValueError(f"{path}: site OAS format version {version}, this rockarch reads "
                         f"version {FORMAT_VERSION}: rebuild it with `rockarch site-oas`")
    return ds


def read_options(ds: xr.Dataset) -> dict:
    """The ``units`` and ``dt`` with which a site file's records were read (``--units``,
    ``--dt``; keywords of :func:`rockarch.motion.suite.read_suite`).

    Parameters
    ----------
    ds : xarray.Dataset
        A site OAS (:func:`load`).

    Returns
    -------
    dict
        ``{"units": str or None, "dt": float or None}`` (None: no record took one); ``{}``
        for a file written before site files recorded them (its records' reading is
        unknown: the caller's options, as then).

    Raises
    ------
    ValueError
        If the records were read with different units or time steps (then read them one
        by one: ``ds["record_units"]``, ``ds["record_dt"]``).
    """
    if "record_units" not in ds or "record_dt" not in ds:
        return {}
    units = sorted({str(u) for u in ds["record_units"].values if str(u)})
    dts = sorted({float(d) for d in ds["record_dt"].values if np.isfinite(d)})
    if len(units) > 1 or len(dts) > 1:
        raise ValueError(f"the site's records were read with different --units ({units}) "
                         f"or --dt ({dts}): read them one by one (record_units, record_dt)")
    return {"units": units[0] if units else None, "dt": dts[0] if dts else None}


def _read_as(opts: dict) -> str:
    """A reading (``units``, ``dt``) as an error names it: 'with --units g --dt 0.01',
    'without --units or --dt'."""
    words = ([f"--units {opts['units']}"] if opts["units"] is not None else []) + (
        [f"--dt {opts['dt']:g}"] if opts["dt"] is not None else [])
    return f"with {' '.join(words)}" if words else "without --units or --dt"


def _same_option(a, b) -> bool:
    """Two values of --units (spelt alike up to case and blanks) or of --dt."""
    if isinstance(a, str) and isinstance(b, str):
        return a.strip().lower().replace(" ", "") == b.strip().lower().replace(" ", "")
    if isinstance(a, str) or isinstance(b, str) or a is None or b is None:
        return a is b
    return math.isclose(float(a), float(b), rel_tol=1e-12)


def check_records(ds: xr.Dataset, sources, *, units: str | None = None,
                  dt: float | None = None) -> Suite:
    """Read a site file's records again as the file says they were read, and check that
    they are the ones it was computed from.

    Each record of ``ds`` is found among ``sources`` by its SHA-256 (of the file, as
    ``rockarch site-oas`` and ``rockarch design --save-site`` write it, :func:`record_sha256`;
    or of its samples, as files of ``design --save-site`` held before) and must have the PGA
    the file holds.

    Parameters
    ----------
    ds : xarray.Dataset
        A site OAS (:func:`load`).
    sources : path or list of paths
        Record files and folders (:func:`rockarch.motion.suite.read_suite`).
    units : str, optional
        Units of text records (``--units``): needed only for a file that does not record
        them (written before site files did); otherwise it must agree with the file's.
    dt : float, optional
        Time step [s] of single-column records (``--dt``), as ``units``.

    Returns
    -------
    Suite
        The site's records in the file's order, read as the file says (``units`` and
        ``dt`` of :func:`read_options`).

    Raises
    ------
    ValueError
        If ``units`` or ``dt`` contradict the file's, a record of the file is not among
        ``sources``, or one reads to another PGA than the file's (other units or time
        step).
    """
    recorded = read_options(ds)
    given = {"units": units, "dt": dt}
    for key, value in given.items():
        if recorded and value is not None and not _same_option(recorded[key], value):
            raise ValueError(f"--{key} {value}: the site file's records were read "
                             f"{_read_as(recorded)} (leave --{key} out: the file says how)")
    opts = recorded or given
    suite = read_suite(sources, **opts)
    found = [(record_sha256(r), r.motion.fingerprint(), r) for r in suite]
    out = []
    for name, digest, pga in zip(ds["record_name"].values, ds["record_sha256"].values,
                                 ds["record_pga"].values, strict=True):
        same = [r for f, m, r in found if digest in (f, m)]
        if not same:
            raise ValueError(f"{name}: not among the records given (SHA-256 {digest[:12]}...): "
                             "give the files the site OAS was computed from")
        match = [r for r in same if math.isclose(r.motion.pga, pga, rel_tol=1e-9)]
        if not match:
            raise ValueError(f"{name}: read {_read_as(opts)} its PGA is "
                             f"{same[0].motion.pga:.6g} m/s², the site file's "
                             f"{float(pga):.6g} m/s²" + ("" if recorded else
                             ": give the --units and --dt it was read with (this file does "
                             "not record them)"))
        out.append(match[0])
    return Suite(tuple(out), csv=suite.csv, notes=suite.notes)


def curve_at(ds: xr.Dataset, p: float, curve: str = "envelope") -> tuple[float, bool]:
    """The site curve's ratio at p: the smaller of the two grid values around p.

    Record boundaries are jagged, so no interpolation: the lower neighbour is the safe side.
    Returns (ratio, is_lower_bound): where no record overturns within the ratio range the
    largest ratio of the range is used, a safe lower bound of the true value.
    """

    if curve not in CURVES:
        raise ValueError(f"curve must be one of {', '.join(CURVES)}, got {curve!r}")
    if curve not in ds:
        raise ValueError(f"the site OAS has no {curve!r} curve: compute it from the records "
                         "(rockarch design --records DIR)")
    ps = ds["p"].values
    if not ps[0] <= p <= ps[-1]:
        raise ValueError(f"the site OAS covers p = {ps[0]:g}…{ps[-1]:g} 1/s, the structure "
                         f"has p = {p:.4g} 1/s: recompute the site OAS over a wider p range")
    vals = ds[curve].values
    rmax = float(ds["ratio"].values[-1])
    filled = np.where(np.isfinite(vals), vals, rmax)
    sel = _around(ps, p)
    i = sel.start + int(np.argmin(filled[sel]))
    return float(filled[i]), bool(not np.isfinite(vals[i]))


def _around(ps: np.ndarray, p: float) -> slice:
    """The grid values of p read at p: p itself if on the grid, else its two neighbours."""
    k = int(np.searchsorted(ps, p))
    return slice(k, k + 1) if ps[min(k, ps.size - 1)] == p else slice(max(k - 1, 0), k + 1)


def records_at(ds: xr.Dataset, p: float) -> np.ndarray:
    """Each record's boundary (first collapse ratio) at p, read as :func:`curve_at` reads a
    curve (the lower of the neighbouring grid values); +inf where it does not collapse."""
    b = ds["boundary"].values[:, _around(ds["p"].values, p)]
    return np.where(np.isfinite(b), b, np.inf).min(axis=1)
