"""A site's seismic hazard curve and the mean annual frequency of collapse.

Theory: docs/theory.md §11.5, Eqs. (11.36)–(11.42).

- A hazard curve H(x) is the annual frequency of exceedance of an intensity measure (IM)
  level x [1/yr], read from a two-column CSV whose header names the IM and its units
  (``PGA [g]``, ``Sa(0.5) [m/s2]``, ``PGV [m/s]``) or from OpenQuake's hazard-curve CSV
  (probabilities of exceedance in the investigation time T, converted to rates
  λ = −ln(1 − poe)/T, Eq. (11.38)); IM levels are kept in SI units (m/s², m/s).
- Between its points the curve is a power law (linear in log-log, Eq. (11.38)); beyond its
  ends it is extrapolated as the power law of its end segments, and the share of λ_c that
  comes from there is reported (:func:`collapse_rate` refuses more than
  :data:`OUTSIDE_TOL` unless told to extrapolate, and gives the lower bound of
  Eq. (11.40)).
- λ_c = ∫ P(collapse | x) |dH(x)| (Eq. (11.36)), the probability of collapse in N years
  1 − exp(−λ_c N) (Eq. (11.37)), the deaggregation of λ_c by IM (Eq. (11.41)) and the
  inverse: the largest scale of the hazard for a target probability (Eq. (11.42)).

Pure functions over small frozen dataclasses; the fragility is a lognormal (median θ,
dispersion β) such as :class:`rockarch.risk.fragility.LognormalFit`.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from rockarch.core.constants import G_STANDARD, standard_g

#: Intensity measures a hazard curve may be given in (those of the IDA's :data:`IMS` that
#: hazard models compute): PGA and Sa(T) [m/s²], PGV [m/s].
HAZARD_IMS = ("pga", "pgv", "sa")
#: Units a hazard curve's IM may be written in, as the factor to SI (m/s², m/s).
ACCELERATION_UNITS = {"g": G_STANDARD, "m/s2": 1.0, "m/s^2": 1.0, "m/s²": 1.0,
                      "cm/s2": 0.01, "cm/s^2": 0.01, "cm/s²": 0.01, "gal": 0.01}
VELOCITY_UNITS = {"m/s": 1.0, "cm/s": 0.01}
#: Largest share of λ_c that may rest on the extrapolation of the hazard curve beyond its
#: ends (λ_c minus the lower bound of Eq. (11.40)) before :func:`collapse_rate` refuses
#: the curve.
OUTSIDE_TOL = 0.01
#: The fragility is integrated over θ·exp(±Z_SPAN·β) (P < 1e-15 below), in steps of
#: β/STEPS_PER_BETA of ln x: the midpoint rule's error is below 1e-6 of λ_c.
Z_SPAN = 8.0
STEPS_PER_BETA = 200
#: Steps per unit of ln x outside θ·exp(±Z_SPAN·β) (for the plotted density only).
COARSE_PER_LN = 100
#: OpenQuake's units (hazardlib): PGA and SA in g, PGV in cm/s.
OPENQUAKE_UNITS = {"pga": "g", "sa": "g", "pgv": "cm/s"}


# --------------------------------------------------------------------------- the curve


@dataclass(frozen=True)
class HazardCurve:
    """Annual frequency of exceedance ``rate`` [1/yr] of the IM levels ``x`` (SI units:
    m/s² for PGA and Sa, m/s for PGV), ``x`` increasing, ``rate`` non-increasing and > 0
    (docs/theory.md §11.5).

    ``units`` is how the file wrote the IM (for display), ``source`` where it came from,
    ``investigation_time`` [yr] the time of OpenQuake's probabilities (None: rates given),
    ``site`` the (lon, lat) of an OpenQuake row, ``notes`` what the reader dropped.
    """

    im: str
    x: np.ndarray
    rate: np.ndarray
    period: float | None = None
    units: str = "m/s2"
    source: str = ""
    investigation_time: float | None = None
    site: tuple | None = None
    notes: tuple = field(default_factory=tuple)

    @property
    def label(self) -> str:
        """The IM as a header writes it: ``PGA``, ``PGV`` or ``Sa(0.5)``."""
        return im_label(self.im, self.period)

    @property
    def factor(self) -> float:
        """SI units per unit of :attr:`units` (g → 9.80665 m/s²)."""
        return _unit_factor(self.im, self.units)

    def rate_at(self, x) -> np.ndarray:
        """H(x) [1/yr] at IM levels ``x`` [SI]: a power law between the points, the end
        segments' power laws beyond them (Eq. (11.38))."""
        with np.errstate(divide="ignore"):
            return np.exp(_loglog(self)(np.log(np.asarray(x, dtype=float))))

    def scaled(self, s: float) -> HazardCurve:
        """The hazard of a site whose ground motions are ``s`` times stronger:
        H_s(x) = H(x/s), Eq. (11.42)."""
        return replace(self, x=self.x * float(s))


def im_label(im: str, period: float | None = None) -> str:
    """``PGA``, ``PGV`` or ``Sa(T)`` as hazard files write them."""
    return f"Sa({period:g})" if im == "sa" else im.upper()


def _unit_factor(im: str, units: str) -> float:
    table = VELOCITY_UNITS if im == "pgv" else ACCELERATION_UNITS
    key = units.strip().lower().replace(" ", "")
    if key not in table:
        kind = "a velocity" if im == "pgv" else "an acceleration"
        raise ValueError(f"{im_label(im)} is {kind}: its units must be one of "
                         f"{', '.join(sorted(set(table)))}, got {units!r}")
    return table[key]


def hazard_curve(x, rate, im: str = "pga", period: float | None = None, *,
                 units: str = "m/s2", source: str = "hazard curve", **kw) -> HazardCurve:
    """A :class:`HazardCurve` from IM levels ``x`` (in ``units``) and annual frequencies
    of exceedance ``rate`` [1/yr], checked: at least two points, finite, x > 0 strictly
    increasing, rate > 0 and never increasing (trailing zero rates are dropped: the curve
    ends at its last positive rate)."""
    if im not in HAZARD_IMS:
        raise ValueError(f"{source}: a hazard curve's IM must be PGA, PGV or Sa(T), got "
                         f"{im!r}")
    if im == "sa" and not (period is not None and math.isfinite(period) and period > 0):
        raise ValueError(f"{source}: Sa needs its period T > 0 [s], got {period}")
    try:
        f = _unit_factor(im, units)
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    x = np.atleast_1d(np.asarray(x, dtype=float))
    rate = np.atleast_1d(np.asarray(rate, dtype=float))
    if x.ndim != 1 or x.shape != rate.shape:
        raise ValueError(f"{source}: give one rate per IM level")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(rate))):
        raise ValueError(f"{source}: IM levels and rates must be finite numbers")
    if np.any(x <= 0) or np.any(rate < 0):
        raise ValueError(f"{source}: IM levels must be > 0 and rates >= 0")
    notes = list(kw.pop("notes", ()))
    zero = np.flatnonzero(rate == 0)
    if zero.size:
        first = zero[0]
        if np.any(rate[first:] > 0):
            k = first + int(np.argmax(rate[first:] > 0))
            raise ValueError(f"{source}: the curve is not monotonic: the rate rises from 0 "
                             f"at {label_value(x[k - 1], units)} to {rate[k]:.3g}/yr at "
                             f"{label_value(x[k], units)}")
        notes.append(f"{zero.size} IM level(s) from {label_value(x[first], units)} up with "
                     "rate 0 left out: the curve ends at its last positive rate")
        x, rate = x[:first], rate[:first]
    if x.size < 2:
        raise ValueError(f"{source}: a hazard curve needs at least two IM levels with a "
                         "positive rate")
    bad = np.flatnonzero(np.diff(x) <= 0)
    if bad.size:
        k = bad[0]
        raise ValueError(f"{source}: IM levels must increase: {label_value(x[k], units)} is "
                         f"followed by {label_value(x[k + 1], units)}")
    up = np.flatnonzero(np.diff(rate) > 0)
    if up.size:
        k = up[0]
        raise ValueError(f"{source}: the curve is not monotonic: the annual rate of "
                         f"exceedance rises from {rate[k]:.4g} at {label_value(x[k], units)} "
                         f"to {rate[k + 1]:.4g} at {label_value(x[k + 1], units)}")
    return HazardCurve(im=im, x=x * f, rate=rate, period=period, units=units, source=source,
                       notes=tuple(notes), **kw)


def label_value(value: float, units: str) -> str:
    """``0.3 g``: a value with its units, for messages."""
    return f"{value:.4g} {units}"


# --------------------------------------------------------------------------- files

_IM_HEADER = re.compile(r"^\s*(PGA|PGV|S[Aa]\s*\(\s*(?:T\s*=\s*)?([0-9.eE+-]+)\s*s?\s*\))\s*"
                        r"\[\s*([^\]]+?)\s*\]\s*$", re.IGNORECASE)
_RATE_UNITS = {"1/yr", "1/year", "/yr", "1/a", "per year", "yr^-1", "1/y"}


def _parse_im(text: str, where: str) -> tuple[str, float | None, str]:
    m = _IM_HEADER.match(text)
    if not m:
        raise ValueError(f"{where}: the first column's header must name the IM and its "
                         f"units, e.g. 'PGA [g]', 'Sa(0.5) [m/s2]' or 'PGV [m/s]'; got "
                         f"{text.strip()!r}")
    name = m.group(1).upper()
    im = "sa" if name.startswith("S") else name.lower()
    period = float(m.group(2)) if im == "sa" else None
    return im, period, m.group(3)


def read_hazard(path, *, site_row: int | None = None) -> HazardCurve:
    """Read a hazard curve: OpenQuake's hazard-curve CSV (a first line ``#...``
    holding ``investigation_time=``, then ``lon,lat[,depth],poe-IML,...``; one row per
    site, chosen by ``site_row``) or a two-column CSV: header ``IM [units]``, ``annual
    frequency of exceedance [1/yr]``, then one IM level and its rate per line (``#``
    lines are comments; ``,``, ``;`` or tab separate)."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such file")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: not a readable text file ({exc})") from None
    lines = text.splitlines()
    first = next((ln for ln in lines if ln.strip()), "")
    if first.startswith("#") and "investigation_time" in first:
        return _read_openquake(path, lines, site_row)
    if site_row is not None:
        raise ValueError(f"{path}: --site-row is for OpenQuake files (a two-column curve "
                         "holds one site)")
    return _read_two_column(path, lines)


def _split(line: str) -> list[str]:
    for sep in (",", ";", "\t"):
        if sep in line:
            return next(csv.reader(io.StringIO(line), delimiter=sep))
    return [line]


def _read_two_column(path: Path, lines: list[str]) -> HazardCurve:
    rows = [(k + 1, ln) for k, ln in enumerate(lines)
            if ln.strip() and not ln.lstrip().startswith("#")]
    if not rows:
        raise ValueError(f"{path}: empty: a hazard curve needs a header 'IM [units], annual "
                         "frequency of exceedance [1/yr]' and its rows")
    n, header = rows[0]
    cols = _split(header)
    if len(cols) != 2:
        raise ValueError(f"{path}: line {n}: a two-column hazard curve has a header of two "
                         f"columns (IM [units], annual frequency of exceedance [1/yr]), got "
                         f"{len(cols)}")
    im, period, units = _parse_im(cols[0], f"{path}: line {n}")
    second = cols[1].lower()
    if "poe" in second or "probab" in second:
        raise ValueError(f"{path}: line {n}: the second column must be the annual frequency "
                         "of exceedance [1/yr]; probabilities of exceedance in T years come "
                         "in OpenQuake's format (a first line '# ... investigation_time=T')")
    unit = re.search(r"\[([^\]]*)\]", cols[1])
    if unit and unit.group(1).strip().lower() not in _RATE_UNITS:
        raise ValueError(f"{path}: line {n}: the annual frequency of exceedance is in 1/yr, "
                         f"got [{unit.group(1)}]")
    x, rate = [], []
    for n, ln in rows[1:]:
        vals = _split(ln)
        try:
            if len(vals) != 2:
                raise ValueError
            x.append(float(vals[0]))
            rate.append(float(vals[1]))
        except ValueError:
            raise ValueError(f"{path}: line {n}: expected two numbers (IM level, annual "
                             f"rate), got {ln.strip()!r}") from None
    return hazard_curve(x, rate, im, period, units=units, source=str(path))


def _read_openquake(path: Path, lines: list[str], site_row: int | None) -> HazardCurve:
    head = lines[0]
    t = re.search(r"investigation_time\s*=\s*([0-9.eE+-]+)", head)
    try:
        time = float(t.group(1)) if t else float("nan")
    except ValueError:
        time = float("nan")
    if not (math.isfinite(time) and time > 0):
        raise ValueError(f"{path}: line 1: no investigation_time > 0 [yr] in OpenQuake's "
                         "header line")
    imt = re.search(r"imt\s*=\s*['\"]?\s*(PGA|PGV|SA\s*\(\s*[0-9.eE+-]+\s*\))", head,
                    re.IGNORECASE)
    imt = imt or re.search(r"-(PGA|PGV|SA\([0-9.eE+-]+\))(?:[-_.]|$)", path.name,
                           re.IGNORECASE)
    if imt is None:
        raise ValueError(f"{path}: OpenQuake file without its IM: no imt= in line 1 and no "
                         "-PGA, -PGV or -SA(T) in the file name")
    name = imt.group(1).replace(" ", "").upper()
    im = "sa" if name.startswith("SA") else name.lower()
    period = float(name[3:-1]) if im == "sa" else None
    if len(lines) < 3:
        raise ValueError(f"{path}: OpenQuake file without its header row and a site row")
    cols = [c.strip() for c in _split(lines[1])]
    poe_cols = [k for k, c in enumerate(cols) if c.lower().startswith("poe-")]
    if not poe_cols or cols[:2] != ["lon", "lat"]:
        raise ValueError(f"{path}: line 2: expected OpenQuake's header lon,lat[,depth],"
                         f"poe-IML,...; got {lines[1][:60]!r}")
    try:
        iml = [float(cols[k][4:]) for k in poe_cols]
    except ValueError:
        raise ValueError(f"{path}: line 2: a poe- column without its IM level") from None
    rows = [(k + 3, _split(ln)) for k, ln in enumerate(lines[2:]) if ln.strip()]
    if not rows:
        raise ValueError(f"{path}: no site row after the header")
    if site_row is None:
        if len(rows) > 1:
            raise ValueError(f"{path}: the file holds {len(rows)} sites: choose one with "
                             f"--site-row K (0 … {len(rows) - 1})")
        site_row = 0
    if not 0 <= site_row < len(rows):
        raise ValueError(f"{path}: --site-row must lie in 0 … {len(rows) - 1}, got {site_row}")
    n, vals = rows[site_row]
    try:
        if len(vals) != len(cols):
            raise ValueError
        poe = np.array([float(vals[k]) for k in poe_cols])
        lon, lat = float(vals[0]), float(vals[1])
    except ValueError:
        raise ValueError(f"{path}: line {n}: expected {len(cols)} numbers") from None
    if np.any((poe < 0) | (poe >= 1)) or not np.all(np.isfinite(poe)):
        raise ValueError(f"{path}: line {n}: probabilities of exceedance must lie in [0, 1) "
                         "(a poe of 1 is an infinite rate)")
    return hazard_curve(iml, poe_to_rate(poe, time), im, period,
                        units=OPENQUAKE_UNITS[im], source=str(path),
                        investigation_time=time, site=(lon, lat))


def poe_to_rate(poe, investigation_time: float) -> np.ndarray:
    """Annual rate of exceedance of a probability of exceedance in T years (Poisson):
    λ = −ln(1 − poe)/T, Eq. (11.38)."""
    return -np.log1p(-np.asarray(poe, dtype=float)) / float(investigation_time)


# --------------------------------------------------------------------------- fragility


@dataclass(frozen=True)
class FragilityCurve:
    """A lognormal fragility Φ(ln(x/θ)/β) in an IM (SI units): what :func:`collapse_rate`
    integrates, read from ``rockarch fragility --json`` or made from a fit."""

    im: str
    median: float
    beta: float
    period: float | None = None
    name: str = "fragility"

    def probability(self, x) -> np.ndarray:
        """P(collapse | IM = x), Eq. (11.31)'s curve."""
        from scipy.special import ndtr

        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return ndtr(np.log(x / self.median) / self.beta)


def fragility_curve(im: str, median: float, beta: float, period: float | None = None,
                    name: str = "fragility") -> FragilityCurve:
    """A checked :class:`FragilityCurve` (θ > 0 in SI units, β > 0)."""
    for what, v in (("median", median), ("beta", beta)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{name}: the fragility's {what} must be a finite number > 0, "
                             f"got {v!r}")
    if im == "sa" and not (isinstance(period, (int, float)) and math.isfinite(period)
                           and period > 0):
        raise ValueError(f"{name}: a fragility in Sa needs its period > 0 [s], got "
                         f"{period!r}")
    return FragilityCurve(im, float(median), float(beta), period, name)


def read_fragility(path) -> FragilityCurve:
    """The lognormal fit of a ``rockarch fragility --json`` file (keys ``im``, ``units``,
    ``median``, ``beta``, ``period`` for Sa)."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such file")
    try:
        d = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ValueError(f"{path}: not a JSON file of rockarch fragility --json ({exc})"
                         ) from None
    if not isinstance(d, dict) or "im" not in d or "median" not in d:
        raise ValueError(f"{path}: not the JSON of rockarch fragility --json (no im, "
                         "median)")
    if "ims" in d:
        raise ValueError(f"{path}: the JSON of --im all: give the JSON of one IM "
                         "(rockarch fragility --im pga ... --json)")
    if d["median"] is None:
        raise ValueError(f"{path}: the fragility has no lognormal fit (fewer than two "
                         "collapse points): raise its scan limit")
    expected = {"pga": "m/s2", "sa": "m/s2", "pgv": "m/s"}.get(d["im"])
    if expected is None:
        raise ValueError(f"{path}: a fragility in {d['im']!r} cannot meet a hazard curve "
                         "(hazard models give PGA, PGV or Sa(T)): rerun it with --im pga, "
                         "pgv or sa")
    if d.get("units") != expected:
        raise ValueError(f"{path}: a fragility in {d['im']} has units {expected}, the file "
                         f"says {d.get('units')!r}")
    return fragility_curve(d["im"], d["median"], d["beta"], d.get("period"), str(path))


def check_match(hazard: HazardCurve, frag: FragilityCurve) -> None:
    """The hazard curve and the fragility must be in the same IM (Sa at the same period,
    to 0.1 %); units are converted (both are held in SI)."""
    if hazard.im != frag.im:
        again = hazard.im + ("" if hazard.period is None else f" --period {hazard.period:g}")
        raise ValueError(f"the hazard curve is in {hazard.label} [{hazard.units}] and the "
                         f"fragility in {im_label(frag.im, frag.period)}: they must be in "
                         f"the same IM (rerun the fragility with --im {again})")
    if hazard.im == "sa" and not math.isclose(hazard.period, frag.period, rel_tol=1e-3):
        raise ValueError(f"the hazard curve is Sa({hazard.period:g}) and the fragility "
                         f"Sa({frag.period:g}): the periods must agree (rerun the fragility "
                         f"with --period {hazard.period:g})")


# --------------------------------------------------------------------------- the rate


@dataclass(frozen=True)
class RiskResult:
    """The mean annual frequency of collapse of one structure at one site
    (docs/theory.md Eqs. (11.36)–(11.41)).

    Attributes
    ----------
    annual_rate : λ_c [1/yr], the curve extrapolated beyond its ends as power laws.
    probability : 1 − exp(−λ_c·years), Eq. (11.37).
    years : N.
    inside : the part of λ_c from IM levels within the curve's range.
    outside_share : the share of λ_c from IM levels outside it (below, above).
    lower_bound : Eq. (11.40): λ_c without extrapolation (nothing below the curve, the
        ground motions above it collapsing with P(collapse | its last level)).
    extrapolated_share : (λ_c − lower bound)/λ_c, the share of λ_c that only the
        extrapolation gives (what the curve leaves undetermined).
    extrapolated : the caller accepted an extrapolated share above :data:`OUTSIDE_TOL`.
    im_bins : edges [SI units] of the deaggregation bins: the curve's levels, with the
        extrapolated ranges below and above as bins of their own.
    shares : share of λ_c in each bin, Eq. (11.41).
    im_grid, density : the deaggregation density P(x)·|dH/d ln x| [1/yr] on a grid of x.
    mode, median_im : the IM of the largest density and the one below which half of λ_c
        falls.
    """

    annual_rate: float
    probability: float
    years: float
    inside: float
    outside_share: tuple[float, float]
    lower_bound: float
    extrapolated_share: float
    extrapolated: bool
    im_bins: np.ndarray
    shares: np.ndarray
    im_grid: np.ndarray
    density: np.ndarray
    mode: float
    median_im: float

    def to_dict(self, factor: float = 1.0, units: str = "SI") -> dict:
        """The JSON of ``rockarch risk``: ``annual_rate`` [1/yr], ``probability``,
        ``years`` and the deaggregation (IM levels divided by ``factor``: in ``units``)."""
        bins = [float(f"{v:.12g}") for v in self.im_bins / factor]  # 0.7, not 0.69999
        return {"annual_rate": self.annual_rate, "probability": self.probability,
                "years": self.years, "lower_bound": self.lower_bound,
                "inside_curve": self.inside,
                "outside_share": {"below": self.outside_share[0],
                                  "above": self.outside_share[1]},
                "extrapolated_share": self.extrapolated_share,
                "extrapolated": self.extrapolated,
                "deaggregation": {"units": units, "mode": self.mode / factor,
                                  "median": self.median_im / factor,
                                  "bins": [{"im_lo": float(a), "im_hi": float(b),
                                            "share": float(s)}
                                           for a, b, s in zip(bins[:-1], bins[1:],
                                                              self.shares, strict=True)]}}


def _loglog(hazard: HazardCurve):
    """ln H as a function of ln x: linear between the points, the end segments'
    power laws beyond them (Eq. (11.38))."""
    lx, lh = np.log(hazard.x), np.log(hazard.rate)
    slope = np.diff(lh) / np.diff(lx)

    def ln_h(lnx):
        lnx = np.asarray(lnx, dtype=float)
        inner = np.interp(lnx, lx, lh)
        below = lh[0] + slope[0] * (lnx - lx[0])
        above = lh[-1] + slope[-1] * (lnx - lx[-1])
        return np.where(lnx < lx[0], below, np.where(lnx > lx[-1], above, inner))

    return ln_h


def collapse_rate(hazard: HazardCurve, frag: FragilityCurve, *, years: float = 50.0,
                  extrapolate: bool = False) -> RiskResult:
    """λ_c = ∫ P(collapse | x) |dH(x)| (Eq. (11.36)), the probability of collapse in
    ``years`` (Eq. (11.37)) and the deaggregation of λ_c by IM (Eq. (11.41)).

    The integral runs on a grid of ln x holding the curve's levels and steps of β/200 over
    θ·exp(±8β) (the midpoint rule for P, the exact increments of the power-law H). Beyond
    the curve's ends H is extrapolated as the power law of its end segment; if more than
    :data:`OUTSIDE_TOL` of λ_c comes from there, a ValueError says how much and gives the
    lower bound of Eq. (11.40), unless ``extrapolate``.
    """
    check_match(hazard, frag)
    years = float(years)
    if not (math.isfinite(years) and years > 0):
        raise ValueError(f"the number of years must be a finite number > 0, got {years}")
    grid, mid, part, tail = _integrand(hazard, frag)
    lx0, lx1 = math.log(hazard.x[0]), math.log(hazard.x[-1])
    below = float(part[mid < lx0].sum())
    above = float(part[mid > lx1].sum()) + tail
    inside = float(part[(mid >= lx0) & (mid <= lx1)].sum())
    total = inside + below + above
    if not total > 0:
        raise ValueError("the annual rate of collapse is 0 to double precision: the "
                         "fragility lies far above the hazard curve")
    p_last = float(frag.probability(hazard.x[-1]))
    lower = min(inside + float(hazard.rate[-1]) * p_last, total)
    share = (below / total, above / total)
    guessed = (total - lower) / total
    if guessed > OUTSIDE_TOL and not extrapolate:
        raise ValueError(_coverage_message(hazard, frag, total, share, guessed, lower))
    # deaggregation: the curve's intervals, and the extrapolated ranges as one bin each
    bins = np.concatenate([grid[:1] if grid[0] < lx0 else [], np.log(hazard.x),
                           grid[-1:] if grid[-1] > lx1 else []])
    idx = np.clip(np.searchsorted(bins, mid, side="right") - 1, 0, bins.size - 2)
    shares = np.bincount(idx, weights=part, minlength=bins.size - 1)
    shares[-1] += tail
    density = part / np.diff(grid)
    cum = np.cumsum(part) / total
    return RiskResult(annual_rate=total, probability=probability_in(total, years),
                      years=years, inside=inside, outside_share=share, lower_bound=lower,
                      extrapolated_share=guessed, extrapolated=guessed > OUTSIDE_TOL,
                      im_bins=np.exp(bins),
                      shares=shares / total, im_grid=np.exp(mid), density=density,
                      mode=float(np.exp(mid[int(np.argmax(density))])),
                      median_im=float(np.exp(np.interp(0.5, cum, grid[1:]))))


def _integrand(hazard: HazardCurve, frag: FragilityCurve):
    """(grid of ln x, its midpoints, P·|ΔH| per step, the rate above the grid): the
    terms of Eq. (11.36) on the grid of :func:`collapse_rate`."""
    lx0, lx1 = math.log(hazard.x[0]), math.log(hazard.x[-1])
    lt, b = math.log(frag.median), frag.beta
    lo, hi = min(lx0, lt - Z_SPAN * b), max(lx1, lt + Z_SPAN * b)
    # steps of β/200 where P varies; outside, P is 0 or 1 to 1e-15 and the exact
    # decrements of H need no fine step (a coarse grid for the density's plot)
    fine = np.linspace(lt - Z_SPAN * b, lt + Z_SPAN * b, 2 * int(Z_SPAN * STEPS_PER_BETA) + 1)
    coarse = np.linspace(lo, hi, int(math.ceil((hi - lo) * COARSE_PER_LN)) + 1)
    grid = np.union1d(np.log(hazard.x), np.union1d(fine, coarse))
    # points of the three grids that nearly coincide are merged: a step of 1e-16 made the
    # density P·ΔH/Δ ln x of that step rounding noise (a spike twice the curve's height)
    grid = grid[np.r_[True, np.diff(grid) > 1e-3 * (fine[1] - fine[0])]]
    h = hazard.rate_at(np.exp(grid))
    mid = 0.5 * (grid[:-1] + grid[1:])
    part = frag.probability(np.exp(mid)) * (h[:-1] - h[1:])  # P |dH| per step
    tail = float(h[-1] * frag.probability(np.exp(grid[-1])))  # above the grid: P ≈ 1
    return grid, mid, part, tail


def _coverage_message(hazard, frag, total, share, guessed, lower) -> str:
    f = hazard.factor
    lo, hi = frag.median * math.exp(-2.326 * frag.beta), frag.median * math.exp(
        2.326 * frag.beta)
    where = " and ".join(w for w, s in (("below", share[0]), ("above", share[1]))
                         if s > 0.0005) or "outside"
    std = standard_g(hazard.units)
    return (f"the hazard curve ({hazard.label} {hazard.x[0] / f:.3g} … "
            f"{hazard.x[-1] / f:.3g} {hazard.units}{', ' + std if std else ''}) does not cover "
            f"the fragility (1–99 % "
            f"between {lo / f:.3g} and {hi / f:.3g} {hazard.units}): "
            f"{100 * guessed:.1f} % of lambda_c = {total:.3g}/yr rests on its extrapolation "
            f"{where} it (its end segments as power laws); without extrapolation "
            f"lambda_c >= {lower:.3g}/yr, a lower bound (Eq. 11.40). Extend the curve, or accept "
            "the extrapolation with --extrapolate")


def probability_in(rate: float, years: float) -> float:
    """1 − exp(−λ N): the probability of at least one collapse in N years (Poisson),
    Eq. (11.37)."""
    return float(-np.expm1(-float(rate) * float(years)))


def rate_for_probability(probability: float, years: float) -> float:
    """The annual rate whose probability in N years is ``probability``:
    −ln(1 − P)/N, Eq. (11.37) inverted."""
    p = float(probability)
    if not 0 < p < 1:
        raise ValueError(f"a probability of collapse in N years must lie in (0, 1), got {p}")
    return float(-np.log1p(-p) / float(years))


def power_law_rate(k0: float, k: float, median: float, beta: float) -> float:
    """The closed form of Eq. (11.39): λ_c = k0 θ^(−k) exp(k²β²/2) for H(x) = k0 x^(−k)
    and a lognormal fragility (Cornell et al. 2002)."""
    return float(k0 * median ** (-k) * math.exp(0.5 * (k * beta) ** 2))


def largest_scale(hazard: HazardCurve, frag: FragilityCurve, probability: float, *,
                  years: float = 50.0, extrapolate: bool = False) -> float:
    """The largest s such that the hazard H_s(x) = H(x/s) (ground motions s times
    stronger) gives P(collapse in ``years``) ≤ ``probability``, Eq. (11.42).

    λ_c(H_s, θ) = λ_c(H, θ/s) increases with s; solved by bisection on ln s to 1e-6.
    """
    from scipy.optimize import brentq

    check_match(hazard, frag)
    target = rate_for_probability(probability, years)

    def excess(ln_s):  # the extrapolated rate: the coverage is checked at the answer
        _, _, part, tail = _integrand(hazard.scaled(math.exp(ln_s)), frag)
        total = float(part.sum()) + tail
        return math.log(total / target) if total > 0 else -745.0

    lo, hi = -1.0, 1.0
    for _ in range(40):  # bracket the root (s within e^±40)
        f_lo, f_hi = excess(lo), excess(hi)
        if f_lo <= 0 <= f_hi:
            break
        lo, hi = (lo - 1.0, hi) if f_lo > 0 else (lo, hi + 1.0)
    else:
        raise ValueError("no scale of the hazard between e^-40 and e^40 reaches the target "
                         "probability")
    s = math.exp(brentq(excess, lo, hi, xtol=1e-6))
    collapse_rate(hazard.scaled(s), frag, years=years, extrapolate=extrapolate)  # coverage
    return s
