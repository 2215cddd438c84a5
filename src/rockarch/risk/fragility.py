"""Incremental dynamic analysis (IDA) and lognormal fragility of any rocking system.

For one structure (any :func:`rockarch.systems.system` kind) at one frequency parameter p,
every record of a suite is scaled up until the structure collapses (docs/theory.md
Sect. 11.3):

- the scan is the OAS scan of :mod:`rockarch.spectra.oas` on one p: a grid of ratios
  ap/ap,min, then bisection between the last safe grid value below the first collapse and
  that collapse, with the same code (so without a search the IDA collapse point of a
  record *is* its OAS boundary at p times ap,min, Eq. (11.30));
- below the grid's first collapse, collapse islands narrower than the grid are searched
  for on a finer step (by default 0.0025 for every system but MDOF assemblies,
  Eq. (11.30a)): the collapse point is the *first* collapse found;
- safe grid values above the first collapse ("resurrections", safe islands of the record)
  are counted and reported, never filled in;
- a record that never collapses up to the scan limit is a right-censored datum;
- the collapse intensities are fitted by a lognormal distribution by maximum likelihood,
  censored records included (Eq. (11.31)), with a bootstrap confidence band over records.

Every record is one task of the sweep executor (in-process, local processes or Dask): its
whole scan and bisection, with no barrier between records; each finished record may be
kept in the resumable store under its own key (:mod:`rockarch.core.sweep`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from tqdm.auto import tqdm

from rockarch.core import sweep
from rockarch.core.console import bar_rows
from rockarch.core.constants import OAS_TOL, G
from rockarch.core.validate import in_range, show, tolerance
from rockarch.motion.intensity import im_value
from rockarch.motion.signals import GroundMotion
from rockarch.motion.suite import as_motions
from rockarch.risk.record_scan import (
    RecordScan,
    TaskBar,
    check_island_step,
    check_search_step,
    default_scan,
    default_search_step,
)
from rockarch.spectra import site
from rockarch.spectra.oas import _grid
from rockarch.systems import BlockSystem

#: Intensity measures of the IDA (the x axis of the fragility curve): PGA, PGV, Sa(T)
#: (5 % damping) and the dimensionless rocking IMs PGA/(g tan α) and PGV·p/(g tan α)
#: (docs/theory.md Eq. (11.30b); g tan α is the block's ap,min, any system's ap,min
#: takes its place).
IMS = ("pga", "pgv", "sa", "pga_norm", "pgv_norm")
#: Units of each intensity measure ("-": dimensionless).
IM_UNITS = {"pga": "m/s2", "pgv": "m/s", "sa": "m/s2", "pga_norm": "-", "pgv_norm": "-"}
#: How each intensity measure is written in tables.
IM_LABELS = {"pga": "PGA", "pgv": "PGV", "sa": "Sa(T)", "pga_norm": "PGA/(g tan a)",
             "pgv_norm": "PGV*p/(g tan a)"}
#: Bootstrap resamples of the confidence band unless told otherwise.
N_BOOTSTRAP = 500
#: Fewest records of a bootstrap band: of two records' resamples only the pair itself has
#: two different collapse points to fit, and every fitted resample is the sample (a band of
#: zero width).
MIN_BOOTSTRAP_RECORDS = 3
#: Most bootstrap resamples (each refits the lognormal: ~1 ms).
MAX_BOOTSTRAP = 10_000


# --------------------------------------------------------------------------- the scan


def im_per_unit_pga(motion: GroundMotion, im: str, period: float | None = None, *,
                    p: float | None = None, ap_min: float | None = None) -> float:
    """The record's intensity measure over its PGA (IM scales linearly with the record,
    docs/theory.md Eq. (11.30b)): 1 for ``pga``; PGV/PGA [s] for ``pgv``; Sa(period)/PGA
    for ``sa`` (5 % damping); 1/ap_min for ``pga_norm`` and PGV·p/(PGA·ap_min) for
    ``pgv_norm`` (the structure's ``p`` [1/s] and ``ap_min`` [m/s²] = g tan α for a
    block)."""
    if im not in IMS:
        raise ValueError(f"unknown intensity measure {im!r}: choose one of {', '.join(IMS)}")
    if im != "sa" and period is not None:
        raise ValueError("--period is for --im sa only")
    if im == "pga":
        return 1.0
    if im == "sa" and period is None:
        raise ValueError("--im sa needs --period T (seconds)")
    if im == "sa" and not (math.isfinite(period) and period > 0):
        raise ValueError(f"--period must be a finite number > 0, got {period}")
    if im == "sa":
        return im_value(motion, im, period=period) / motion.pga
    if im.endswith("_norm") and (p is None or ap_min is None):
        raise ValueError(f"the intensity measure {im} needs the structure's p and ap_min")
    if im == "pga_norm":
        return 1.0 / ap_min
    pgv = im_value(motion, "pgv") / motion.pga
    return pgv if im == "pgv" else pgv * p / ap_min


@dataclass(frozen=True)
class IDAResult:
    """Collapse points of the records of a suite (docs/theory.md Eq. (11.30)).

    Attributes
    ----------
    system, p, ap_min : the structure's name, frequency parameter [1/s] and ap,min [m/s²].
    im : intensity measure (one of :data:`IMS`).
    records : record names (file names).
    ratio : the scan grid of ap/ap,min.
    overturned : (record, ratio) bool, the scan.
    ratio_collapse : lowest collapse ratio per record (bisected; NaN: censored).
    im_scale : the IM of each record scaled to ratio 1, i.e. to PGA = ap,min (IM units).
    resurrections : per record, collapse → safe transitions on the grid above its first
        collapse (safe islands; a lower bound of those of a finer scan).
    tol : bisection tolerance (ratio units).
    island_step : 1, every grid value run; s > 1, the adaptive scan of
        :class:`RecordScan` (``overturned`` is True where a value was not run).
    evaluated : (record, ratio) bool, the values run (None: every one).
    search_step : step of the search below the grid's first collapse (0: none).
    p_structure : the p of the structure as given in metres where it was scaled to ``p``
        (size ∝ 1/p², :attr:`scale`); None: analysed as given, or it has no size.
    """

    system: str
    p: float
    ap_min: float
    im: str
    records: tuple[str, ...]
    ratio: np.ndarray
    overturned: np.ndarray
    ratio_collapse: np.ndarray
    im_scale: np.ndarray
    resurrections: np.ndarray
    tol: float
    period: float | None = None
    island_step: int = 1
    evaluated: np.ndarray | None = None
    search_step: float = 0.0
    p_structure: float | None = None

    @property
    def scale(self) -> float | None:
        """The analysed structure's size over its size as given, (p_structure/p)² (None:
        not scaled)."""
        return None if self.p_structure is None else (self.p_structure / self.p) ** 2

    @property
    def censored(self) -> np.ndarray:
        """Records that did not collapse up to the scan limit."""
        return ~np.isfinite(self.ratio_collapse)

    @property
    def im_collapse(self) -> np.ndarray:
        """Lowest collapse intensity per record (NaN where censored); PGA is
        ratio·ap,min exactly."""
        return self.ratio_collapse * self.ap_min * self.im_scale

    @property
    def im_limit(self) -> np.ndarray:
        """Intensity of each record at the scan limit (the censoring value)."""
        return self.ratio[-1] * self.ap_min * self.im_scale


def count_resurrections(over: np.ndarray, ratio=None, collapse=None) -> np.ndarray:
    """Safe islands above the first collapse of each row of a (record, ratio) scan: the
    number of collapse → safe transitions along the ratio axis. Given the grid ``ratio``
    and each record's first collapse ``collapse`` (NaN: none), the transitions of the
    sequence (collapse, the grid values above it): a safe grid value above a collapse
    found below the grid's first one counts too."""
    over = np.asarray(over, dtype=bool)
    if collapse is None:
        return np.count_nonzero(over[:, :-1] & ~over[:, 1:], axis=1)
    out = np.zeros(over.shape[0], dtype=int)
    for k, c in enumerate(np.asarray(collapse, dtype=float)):
        if np.isfinite(c):
            row = np.concatenate([[True], over[k][np.asarray(ratio) > c]])
            out[k] = np.count_nonzero(row[:-1] & ~row[1:])
    return out


def scan_text(ratio: np.ndarray, tol: float, search_step: float) -> str:
    """The IDA scan in words (the CLI's output): grid, bisection, search."""
    text = (f"ap/ap,min = {ratio[0]:g} … {ratio[-1]:g} in {ratio.size} values, collapse "
            f"points bisected to {tol:g}")
    return text + (f", searched every {search_step:g} below" if search_step > 0 else "")


def ida(system, motions: Sequence[GroundMotion], p: float, *, names=None,
        im: str = "pga", period: float | None = None, ratio=None,
        tol: float | None = None, progress: bool = False, executor=None, store=None,
        island_step: int = 1, search_step: float | None = None,
        log: Callable[[str], None] | None = None, name: str | None = None) -> IDAResult:
    """Incremental dynamic analysis of ``system`` at frequency parameter ``p``.

    Parameters
    ----------
    system : a system of :func:`rockarch.systems.system` (any kind).
    motions : the records, a :class:`rockarch.motion.suite.Suite` (named by its file names)
        or GroundMotions (their shapes are scaled to PGA = ratio·ap,min).
    p : frequency parameter [1/s] (the structure's size).
    names : record names (default the motions' names).
    im, period : intensity measure (:data:`IMS`; ``sa`` at ``period`` [s]).
    ratio : scan grid of ap/ap,min; its last value is the scan limit (censoring). Default
        1 … 5 in 81 values (that of ``rockarch oas``), 17 values for MDOF assemblies
        (:func:`rockarch.risk.record_scan.default_scan`).
    tol : bisection tolerance of the collapse point (ratio units); default 0.001, 0.01 for
        MDOF assemblies.
    progress, executor, store : as in :func:`rockarch.spectra.oas.compute_oas`; every
        record is one task (:class:`RecordScan`), run in this process, on local processes
        or on Dask, and stored as it finishes (the progress bar counts records).
    island_step : 1 (default) runs every grid value; s > 1 the adaptive scan of
        :class:`RecordScan`: the same collapse points, safe islands above the first
        collapse found from every s-th grid value, fewer simulations.
    search_step : step h of the search for collapse islands below the grid's first
        collapse (Eq. (11.30a), :class:`RecordScan`); None (default): 0.0025 for every
        system but MDOF assemblies, 0.05 for those (below a collapse of the grid only);
        0: no search.
    log : called with a line per stage (the structure and the scan, when the IDA starts;
        each record, when it is done), e.g. ``print`` where no progress bar is shown.
    name : the structure's name in the log and the result (default ``system.name``).
    """
    motions, names = as_motions(motions, names, "motions")
    name = system.name if name is None else name
    if not motions:
        raise ValueError("an IDA needs at least one record")
    p = float(p)
    if not (math.isfinite(p) and p > 0):
        raise ValueError(f"p must be a finite number > 0, got {p}")
    steps, tol_default = default_scan(system)
    ratio = _grid("ratio", np.round(np.linspace(1.0, 5.0, steps), 12) if ratio is None
                  else ratio)
    if ratio[0] < 0:
        raise ValueError("ratio values must be >= 0")
    tol = tolerance("tol", tol_default if tol is None else tol)
    names = tuple(m.name for m in motions) if names is None else tuple(names)
    if len(names) != len(motions):
        raise ValueError("give one name per record")
    scale = np.array([im_per_unit_pga(m, im, period, p=p, ap_min=float(system.ap_min))
                      for m in motions])
    search_step = (default_search_step(system) if search_step is None
                   else check_search_step(search_step))
    scan = RecordScan(system, p, tol, check_island_step(island_step), search_step)
    if log is not None:
        log(f"structure {name}: p = {p:.4g} 1/s, ap,min = "
            f"{float(system.ap_min):.4g} m/s²")
        log(f"IDA: {len(motions)} record(s), {scan_text(ratio, tol, search_step)}")
    task_ratio = np.append(ratio, np.nan)
    # one task per record, the longest records first (they finish last otherwise); each
    # record is stored under its own key as it finishes (resumable, and reused by any
    # suite that holds the record)
    order = sorted(range(len(motions)), key=lambda k: -motions[k].duration)
    tasks = [(np.full(task_ratio.size, float(k)), task_ratio) for k in order]
    store = sweep.as_store(store)
    keys = None if store is None else [
        sweep.chunk_key(scan, motions[k], np.array([p]), task_ratio) for k in order]
    executor, owned = sweep.as_executor(executor)
    over = np.zeros((len(motions), ratio.size), dtype=bool)
    evaluated = np.zeros_like(over)
    collapse = np.full(len(motions), np.nan)
    try:
        with tqdm(total=len(motions), desc=scan.name, unit="record",
                  disable=not progress, leave=False, nrows=bar_rows()) as bar:
            res = sweep.run_chunks(scan, motions, tasks, executor=executor, store=store,
                                   bar=TaskBar(bar, log, scan.name, len(motions)), keys=keys)
    finally:
        if owned:
            executor.close()
    for k, (o, r) in zip(order, res, strict=True):
        over[k], evaluated[k], collapse[k] = o[:-1], ~np.isnan(r[:-1]), r[-1]
    return IDAResult(system=name, p=p, ap_min=float(system.ap_min), im=im,
                     records=names, ratio=ratio, overturned=over, ratio_collapse=collapse,
                     im_scale=scale, resurrections=count_resurrections(over, ratio, collapse),
                     tol=tol, period=period, island_step=scan.island_step,
                     evaluated=evaluated, search_step=search_step)


def with_im(result: IDAResult, motions: Sequence[GroundMotion], im: str,
            period: float | None = None) -> IDAResult:
    """The same IDA (same collapse ratios, Eq. (11.30)) in another intensity measure:
    every IM of :data:`IMS` is linear in the record's scale, Eq. (11.30b)."""
    motions, _ = as_motions(motions, what="motions")
    if len(motions) != len(result.records):
        raise ValueError("give the motions of the IDA, one per record")
    scale = np.array([im_per_unit_pga(m, im, period, p=result.p, ap_min=result.ap_min)
                      for m in motions])
    return replace(result, im=im, period=period, im_scale=scale)


def ims_of(result: IDAResult, period: float | None = None) -> list[tuple[str, float | None]]:
    """Every intensity measure that :func:`compare_ims` reports: (im, period) with Sa at
    ``period`` [s], default T = 2π/p (the structure's p read as a circular frequency)."""
    t = 2 * math.pi / result.p if period is None else float(period)
    return [(im, t if im == "sa" else None) for im in IMS]


def compare_ims(result: IDAResult, motions: Sequence[GroundMotion], *,
                period: float | None = None, n_bootstrap: int = N_BOOTSTRAP,
                level: float = 0.95, seed: int = 0) -> list[dict]:
    """The lognormal fit (Eq. (11.31)) of one IDA in every intensity measure of
    :data:`IMS`, to pick the most efficient one (lowest β, Luco & Cornell 2007). On one
    structure PGA/(g tan α) and PGV·p/(g tan α) are PGA and PGV times constants: the same
    β (they differ when structures of other sizes or slenderness are pooled).

    Returns one dict per IM: ``im``, ``label``, ``units``, ``period`` (Sa only),
    ``median``, ``beta`` and ``ci`` (bootstrap intervals of θ and β; empty for
    ``n_bootstrap`` 0).
    """
    out = []
    for im, t in ims_of(result, period):
        frag = fit_ida(with_im(result, motions, im, t), n_bootstrap=n_bootstrap,
                       level=level, seed=seed)
        row = {"im": im, "label": IM_LABELS[im], "units": IM_UNITS[im],
               "median": frag.fit.median, "beta": frag.fit.beta,
               "ci": {k: frag.ci[k] for k in ("level", "median", "beta") if k in frag.ci}}
        if t is not None:
            row["period"] = t
        out.append(row)
    return out


# --------------------------------------------------------------------------- the fit


@dataclass(frozen=True)
class LognormalFit:
    """A lognormal fragility P(collapse | IM = x) = Φ(ln(x/θ)/β) (Eq. (11.31)).

    ``median`` θ and ``beta`` β maximise the likelihood of the collapse points and of the
    censored records (survivors up to their scan limit).
    """

    median: float
    beta: float
    n_collapsed: int
    n_censored: int
    loglik: float

    def probability(self, x) -> np.ndarray:
        """P(collapse) at intensity ``x``."""
        from scipy.stats import norm

        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return norm.cdf(np.log(x / self.median) / self.beta)

    def intensity(self, probability) -> np.ndarray:
        """The intensity at which P(collapse) equals ``probability`` (in (0, 1))."""
        from scipy.stats import norm

        q = np.asarray(probability, dtype=float)
        if np.any((q <= 0) | (q >= 1)):
            raise ValueError("a probability of collapse must lie in (0, 1)")
        return self.median * np.exp(self.beta * norm.ppf(q))


_LOG_SQRT_2PI = 0.5 * math.log(2 * math.pi)


def _neg_loglik(params, lx, lc):
    """−ln L of Eq. (11.31) without the constant Σ ln x_i, and its gradient in
    (μ = ln θ, s = ln β): with z = (ln x − μ)/β and the hazard h(z) = φ(z)/(1 − Φ(z)),
    ∂/∂μ = −(Σ z_i + Σ h(z_j))/β and ∂/∂s = n − Σ z_i² − Σ z_j h(z_j)."""
    from scipy.special import log_ndtr

    mu, log_beta = float(params[0]), float(params[1])
    beta = math.exp(log_beta)
    z = (lx - mu) / beta
    zc = (lc - mu) / beta
    log_sf = log_ndtr(-zc)
    value = float(0.5 * z @ z + lx.size * (_LOG_SQRT_2PI + log_beta) - log_sf.sum())
    hazard = np.exp(-0.5 * zc * zc - _LOG_SQRT_2PI - log_sf)
    grad = np.array([-(z.sum() + hazard.sum()) / beta,
                     lx.size - z @ z - zc @ hazard])
    return value, grad


def fit_lognormal(collapse, censored_at=()) -> LognormalFit:
    """Maximum-likelihood lognormal fit of collapse intensities with right-censoring.

    Parameters
    ----------
    collapse : array_like
        Collapse intensities of the records that collapsed (> 0).
    censored_at : array_like
        Intensities up to which the other records survived (> 0).

    Notes
    -----
    Without censored records the estimate is closed form (mean and standard deviation,
    ddof 0, of ln x); with them the likelihood Eq. (11.31) is maximised numerically
    (scipy.optimize BFGS with the analytic gradient, from the closed-form start).
    """
    lx = np.log(_positive_values("collapse intensities", collapse))
    lc = np.log(_positive_values("censoring intensities", censored_at))
    if lx.size < 2 or np.ptp(lx) == 0:
        raise ValueError(f"a lognormal fit needs at least two different collapse "
                         f"intensities, got {lx.size} record(s) that collapse"
                         + (f" and {lc.size} censored" if lc.size else ""))
    mu0, beta0 = float(lx.mean()), float(lx.std())
    if lc.size == 0:
        mu, beta = mu0, beta0
    else:
        from scipy.optimize import minimize

        res = minimize(_neg_loglik, [mu0, math.log(beta0)], args=(lx, lc), jac=True,
                       method="BFGS", options={"gtol": 1e-10, "maxiter": 500})
        mu, beta = float(res.x[0]), math.exp(float(res.x[1]))
    return LognormalFit(median=math.exp(mu), beta=beta, n_collapsed=int(lx.size),
                        n_censored=int(lc.size),
                        loglik=-_neg_loglik([mu, math.log(beta)], lx, lc)[0]
                        - float(lx.sum()))


def _positive_values(name: str, values) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values, dtype=float)).ravel()
    if arr.size and not (np.all(np.isfinite(arr)) and np.all(arr > 0)):
        raise ValueError(f"{name} must be finite numbers > 0")
    return arr


def bootstrap(collapse, censored_at=(), *, n: int = N_BOOTSTRAP, level: float = 0.95,
              im_grid=None, seed: int = 0) -> dict:
    """Bootstrap confidence intervals of θ, β and of the curve (records resampled with
    replacement, each resample refitted by :func:`fit_lognormal`; resamples with fewer
    than two different collapse intensities are skipped and counted).

    Returns a dict: ``level``, ``n``, ``skipped``, ``seed``, ``median`` [lo, hi],
    ``beta`` [lo, hi] and, given ``im_grid``, ``im`` and the band ``probability_lo`` /
    ``probability_hi`` (pointwise percentiles of the resampled curves).
    """
    from scipy.stats import norm

    if isinstance(n, bool) or int(n) != n or not 1 <= n <= MAX_BOOTSTRAP:
        raise ValueError(f"the number of bootstrap resamples must be an integer in [1, "
                         f"{MAX_BOOTSTRAP}], got {show(n)}")
    if not 0 < level < 1:
        raise ValueError(f"the confidence level must lie in (0, 1), got {level}")
    x = _positive_values("collapse intensities", collapse)
    c = _positive_values("censoring intensities", censored_at)
    values = np.concatenate([x, c])
    is_c = np.arange(values.size) >= x.size
    rng = np.random.default_rng(seed)
    fits = []
    for _ in range(int(n)):
        k = rng.integers(0, values.size, values.size)
        try:
            f = fit_lognormal(values[k][~is_c[k]], values[k][is_c[k]])
        except ValueError:
            continue
        fits.append((f.median, f.beta))
    if not fits:
        raise ValueError("no bootstrap resample could be fitted (too few collapses)")
    th, be = np.array(fits).T
    q = 100 * np.array([(1 - level) / 2, (1 + level) / 2])
    out = {"level": level, "n": int(n), "skipped": int(n) - len(fits), "seed": seed,
           "median": np.percentile(th, q).tolist(), "beta": np.percentile(be, q).tolist()}
    if im_grid is not None:
        grid = _positive_values("im grid", im_grid)
        curves = norm.cdf(np.log(grid[None, :] / th[:, None]) / be[:, None])
        lo, hi = np.percentile(curves, q, axis=0)
        out.update(im=grid.tolist(), probability_lo=lo.tolist(), probability_hi=hi.tolist())
    return out


# --------------------------------------------------------------------------- together


class TooFewCollapses(ValueError):
    """Fewer than two different collapse points: no lognormal can be fitted."""



@dataclass(frozen=True)
class Fragility:
    """IDA, its lognormal fit and the bootstrap band (what ``rockarch fragility`` prints);
    ``fit`` is None when fewer than two records collapse (:class:`TooFewCollapses`)."""

    ida: IDAResult
    fit: LognormalFit | None
    ci: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """The CLI's JSON: ``im``, ``median``, ``beta``, ``points``, ``ci`` and the ``scan``
        of ap/ap,min (its first and last value, number of values, bisection tolerance)."""
        r = self.ida
        points = [{"record": name, "im_collapse": (float(v) if math.isfinite(v) else None),
                   "censored": bool(not math.isfinite(v)),
                   "im_limit": float(lim), "resurrections": int(n)}
                  for name, v, lim, n in zip(r.records, r.im_collapse, r.im_limit,
                                             r.resurrections, strict=True)]
        fit = self.fit
        out = {"im": r.im, "units": IM_UNITS[r.im],
               "median": None if fit is None else fit.median,
               "beta": None if fit is None else fit.beta, "n_records": len(r.records),
               "n_collapsed": int((~r.censored).sum()), "n_censored": int(r.censored.sum()),
               "system": r.system, "p": r.p, "ap_min": r.ap_min, "points": points,
               "ci": self.ci}
        if r.period is not None:
            out["period"] = r.period
        if r.island_step > 1:
            out["island_step"] = r.island_step
        out["search_step"] = r.search_step
        if r.p_structure is not None:
            out["scale"], out["p_structure"] = r.scale, r.p_structure
        out["scan"] = {"ratio_min": float(r.ratio[0]), "ratio_max": float(r.ratio[-1]),
                       "values": int(r.ratio.size), "tol": r.tol}
        return out


def fit_ida(result: IDAResult, *, n_bootstrap: int = N_BOOTSTRAP, level: float = 0.95,
            im_grid=None, seed: int = 0,
            hint: str = "raise the scan limit, e.g. --ratio-max 10") -> Fragility:
    """Lognormal fit (censored records included) and bootstrap band of an IDA (none with
    fewer than :data:`MIN_BOOTSTRAP_RECORDS` records); ``hint``: what to do when fewer than
    two records collapse (:class:`TooFewCollapses`)."""
    x = result.im_collapse[~result.censored]
    c = result.im_limit[result.censored]
    if np.unique(x).size < 2:
        if len(result.records) < 2:
            hint = "give at least two records"
        raise TooFewCollapses(f"only {x.size} of {len(result.records)} records collapse up to "
                              f"ap/ap,min = {result.ratio[-1]:g}: a fragility needs at least "
                              f"two different collapse points ({hint})")
    fit = fit_lognormal(x, c)
    few = len(result.records) < MIN_BOOTSTRAP_RECORDS
    ci = {} if n_bootstrap == 0 or few else bootstrap(x, c, n=n_bootstrap, level=level,
                                               im_grid=im_grid, seed=seed)
    return Fragility(result, fit, ci)


def fragility(system, motions: Sequence[GroundMotion], p: float, *,
              im_grid: Callable | Sequence | None = None, n_bootstrap: int = N_BOOTSTRAP,
              level: float = 0.95, seed: int = 0, **ida_kw) -> Fragility:
    """IDA of ``system`` at ``p`` over ``motions`` and its lognormal fragility (Sect. 11.3);
    keywords as :func:`ida` (im, period, ratio, tol, executor, store, ...)."""
    return fit_ida(ida(system, motions, p, **ida_kw), n_bootstrap=n_bootstrap, level=level,
                   im_grid=im_grid, seed=seed)


def site_ida(motions: Sequence[GroundMotion], p: float, ap_min: float, *,
             alpha: float | None = None, names=None, ratio=None, tol: float = OAS_TOL,
             t_free: float | None = None, executor=None, store=None,
             progress: bool = False) -> IDAResult:
    """IDA of a structure replaced by the site's slender block (the design method of
    docs/theory.md Sect. 7): the block of slenderness ``alpha`` (default the site's) at the
    structure's ``p``, collapse islands searched below the grid (Eq. (11.30a)), collapse
    points in units of the structure's ``ap_min`` (PGA = ratio·ap_min, Eq. (11.30))."""
    kw = {} if t_free is None else {"t_free": t_free}
    block = BlockSystem(alpha=site.ALPHA if alpha is None else alpha, **kw)
    res = ida(block, motions, p, names=names, ratio=ratio, tol=tol, executor=executor,
              store=store, progress=progress)
    return replace(res, ap_min=float(ap_min), system=f"block alpha={block.alpha:g} "
                   f"(replacement, ap,min = {ap_min:.4g} m/s²)")


#: What to do when too few of a site's records collapse the replacement's block.
SITE_HINT = "give more records, or records that collapse at different levels"


def site_fragility(motions: Sequence[GroundMotion], p: float, ap_min: float, *,
                   n_bootstrap: int = N_BOOTSTRAP, seed: int = 0, **kw) -> Fragility:
    """Fragility in PGA [m/s²] of a structure replaced by the site's slender block: the
    lognormal fit of :func:`site_ida` (keywords as there)."""
    return fit_ida(site_ida(motions, p, ap_min, **kw), n_bootstrap=n_bootstrap, seed=seed,
                   hint=SITE_HINT)


def design_summary(frag: Fragility, *, pga: float | None = None,
                   probability: float | None = 0.1, g: float | None = None) -> dict:
    """What ``rockarch design --records`` reports of the replacement's fragility: θ, β,
    the probability of collapse at ``pga`` [m/s²] and the PGA at ``probability``."""
    g = G if g is None else g
    fit = frag.fit
    out = {"median": fit.median, "beta": fit.beta, "n_records": len(frag.ida.records),
           "n_censored": fit.n_censored, "ci": {k: frag.ci[k] for k in ("level", "median",
                                                                       "beta")
                                               if k in frag.ci}}
    if pga is not None:
        if not (math.isfinite(pga) and pga > 0):
            raise ValueError(f"--pga must be a finite number > 0 [m/s²], got {pga}")
        out["probability_at_pga"] = {"pga": pga, "probability": float(fit.probability(pga))}
    if probability is not None:
        probability = in_range("probability", probability, 0.0, 1.0, lo_open=True,
                               hi_open=True)
        x = float(fit.intensity(probability))
        out["pga_at_probability"] = {"probability": probability, "pga": x, "pga_g": x / g}
    return out
