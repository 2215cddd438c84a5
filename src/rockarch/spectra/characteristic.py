"""Characteristic site OAS: a normalised OAS over p·Tm and a simplified two-duration OAS.

Two ways to turn the OAS boundaries of a suite into one site curve, and to predict a
record's boundary without simulating it (docs/theory.md Sect. 11.2):

- **normalised**: each record's boundary b_k(p) is read as a function of x = p·Tm_k (its
  mean period, Rathje et al.), over which the boundaries of different records collapse
  (the similarity of Dimitrakopoulos & DeJong 2012); the site curve is a percentile over
  the records, Eq. (11.26), read at p·Tm of the site (the geometric mean of the records').
- **simplified**: two durations of the record's strongest impulse, t_I (impulse) and t_M
  (first moment of the impulse), Eqs. (11.20)–(11.22), give three branches of ap/ap,min
  over p, Eq. (11.25): 1 (no uplift), the rectangular-pulse closed form
  1/(1 − e^(−p t_I)) ~ 1/(p t_I) (overturning without impact, Eq. (11.23)) and
  C (cos α)/(p t_M)² (overturning after impact, Eq. (11.24)).

The same two durations and three branches (a constant, one ∝ 1/p, one ≈ ∝ 1/p²) are
proposed in the preprint "Towards physically justified, site-specific overturning
acceleration response spectra" (SSRN 6181908, posted February 2026). The forms here are
our own derivations, not taken from it: the exact no-impact curve 1/(1 − e^(−p t_I)) of
the linearised block under a rectangular pulse, the constant C = 1.5 of the after-impact
branch (a fixed-centre-of-mass argument, :data:`IMPACT_COEFF`), the definitions of t_I
and t_M from the strongest one-signed velocity change, and the percentile over records;
we have not compared our constants with the preprint's.

:func:`characteristic` adds both to a site OAS (:func:`rockarch.spectra.site.site_oas`) and
:func:`skill` measures how well each predicts the computed boundaries.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rockarch.motion.intensity import mean_period
from rockarch.motion.signals import GroundMotion
from rockarch.motion.suite import as_motions
from rockarch.spectra import oas as spectra
from rockarch.spectra import site

if TYPE_CHECKING:  # xarray (half a second to import) where a dataset is made or read
    import xarray as xr

#: Constant C of the after-impact branch, Eq. (11.24), our own (derived, not fitted, not
#: from a paper): the base moves by the half-width R·sin(alpha) under a centre of mass at
#: rest, R = 3g/(4p²) (Housner 1963; docs/theory.md Eq. (1.2)): (3/4)(ap,min/p²)cos(alpha)
#: = A t_M²/2 with A = ratio·ap,min.
IMPACT_COEFF = 1.5


@dataclass(frozen=True)
class PulseDurations:
    """The strongest impulse of a record and its equivalent rectangular pulse (Sect. 11.2).

    ``impulse`` I = |v(t_end) − v(t_start)| [m/s], the largest one-signed change of ground
    velocity; ``moment`` M = |∫ (v − v(t_start)) dt| over it [m], the first moment of the
    impulse about its end; ``pga`` [m/s²].
    """

    impulse: float
    moment: float
    t_start: float
    t_end: float
    pga: float

    @property
    def t_impulse(self) -> float:
        """t_I = I / PGA [s]: a rectangle of height PGA with the same impulse, Eq. (11.21)."""
        return self.impulse / self.pga

    @property
    def t_moment(self) -> float:
        """t_M = sqrt(2 M / PGA) [s]: a rectangle of height PGA with the same first
        moment, Eq. (11.22)."""
        return math.sqrt(2.0 * self.moment / self.pga)


def pulse_durations(motion: GroundMotion) -> PulseDurations:
    """t_I and t_M of a record (docs/theory.md Eqs. (11.20)–(11.22)).

    The ground velocity from rest is integrated exactly at the knots (a_g is linear between
    them); the strongest impulse is the pair t_start < t_end with the largest |Δv| (a
    running minimum, O(n)); its moment is the trapezoidal integral of v − v(t_start).
    For a rectangular pulse of duration T, t_I = t_M = T.
    """
    t = np.asarray(motion.t, dtype=float)
    a = np.asarray(motion.a, dtype=float)
    v = np.concatenate([[0.0], np.cumsum(0.5 * np.diff(t) * (a[1:] + a[:-1]))])
    best = None
    for sign in (1.0, -1.0):
        w = sign * v
        gain = w - np.minimum.accumulate(w)
        j = int(np.argmax(gain))
        if best is None or gain[j] > best[0]:
            best = (float(gain[j]), int(np.argmin(w[:j + 1])), j, sign)
    impulse, i, j, sign = best
    seg = v[i:j + 1] - v[i]
    moment = abs(float(np.sum(0.5 * np.diff(t[i:j + 1]) * (seg[1:] + seg[:-1]))))
    return PulseDurations(impulse=impulse, moment=moment, t_start=float(t[i]),
                          t_end=float(t[j]), pga=motion.pga)


def rectangular_pulse_boundary(p, duration) -> np.ndarray:
    """Lowest ap/ap,min that overturns a slender block without impact under a rectangular
    pulse of that duration: 1/(1 − e^(−p·t)) (linearised rocking, docs/theory.md Eq. (11.23),
    our derivation; its limit 1/(p t) is the 1/p branch of SSRN 6181908)."""
    x = np.asarray(p, dtype=float) * duration
    with np.errstate(divide="ignore"):
        return 1.0 / -np.expm1(-x)


def simplified_boundary(p, t_impulse: float, t_moment: float, alpha: float = 0.0
                        ) -> np.ndarray:
    """The simplified OAS of a record, Eq. (11.25): max(1, min(1/(1 − e^(−p t_I)),
    C cos(alpha)/(p t_M)²)); the easier of the two overturning modes, never below 1."""
    p = np.asarray(p, dtype=float)
    no_impact = rectangular_pulse_boundary(p, t_impulse)
    after_impact = IMPACT_COEFF * math.cos(alpha) / (p * t_moment) ** 2
    return np.maximum(1.0, np.minimum(no_impact, after_impact))


def _log_interp(x_new, x, y) -> np.ndarray:
    """y(x) interpolated linearly in (ln x, ln y) at x_new; NaN outside [x0, x_end];
    +inf entries of y (no overturning within range) stay +inf where a neighbour is."""
    out = np.full(np.shape(x_new), np.nan)
    inside = (x_new >= x[0]) & (x_new <= x[-1])
    finite = np.isfinite(y)
    ly = np.log(np.where(finite, y, 1.0))
    out[inside] = np.exp(np.interp(np.log(x_new[inside]), np.log(x), ly))
    k = np.clip(np.searchsorted(x, x_new[inside]), 1, x.size - 1)
    blocked = ~finite[k] | ~finite[k - 1]
    vals = out[inside]
    vals[blocked] = np.inf
    out[inside] = vals
    return out


def normalised_curve(boundary, p, scale, percentile: float = 50.0, n: int = 120):
    """The site's normalised OAS, Eq. (11.26): on a geometric grid of x = p·scale, the
    ``percentile`` over records of b_k(x/scale_k) (records whose p range does not reach x
    are left out there; a record without overturning counts as +inf).

    Returns (x, curve)."""
    b = np.where(np.isfinite(boundary), boundary, np.inf)
    scale = np.asarray(scale, dtype=float)
    x = np.geomspace(p[0] * scale.min(), p[-1] * scale.max(), n)
    rows = np.stack([_log_interp(x / s, p, bk) for bk, s in zip(b, scale, strict=True)])
    have = np.isfinite(rows) | np.isinf(rows)
    curve = np.full(x.size, np.nan)
    for j in range(x.size):
        col = rows[have[:, j], j]
        if col.size:
            curve[j] = np.percentile(col, percentile, method="lower")
    return x, np.where(np.isfinite(curve), curve, np.nan)


def _mean_period_or_nan(motion: GroundMotion, mean_period) -> float:
    """Tm of the record, NaN where it is undefined (no Fourier amplitude in the band)."""
    try:
        return float(mean_period(motion))
    except ValueError:
        return float("nan")


def characteristic(ds: xr.Dataset, motions, *, percentile: float | None = None
                   ) -> xr.Dataset:
    """A site OAS (:func:`rockarch.spectra.site.site_oas`) with the normalised and simplified
    curves added: per record ``tm``, ``t_impulse``, ``t_moment``, ``simplified_record``
    (record, p); the site curves ``normalised`` and ``simplified`` (p) (the site's
    percentile, default the file's), and ``normalised_x`` / ``normalised_curve`` over x =
    p·Tm."""
    motions, _ = as_motions(motions, what="motions")
    if len(motions) != ds.sizes["record"]:
        raise ValueError(f"the site OAS has {ds.sizes['record']} records, got "
                         f"{len(motions)} motions")
    q = float(ds.attrs.get("percentile", 50.0) if percentile is None else percentile)
    p = ds["p"].values
    alpha = float(ds.attrs.get("alpha", 0.0))
    tm = np.array([_mean_period_or_nan(m, mean_period) for m in motions])
    durs = [pulse_durations(m) for m in motions]
    t_i = np.array([d.t_impulse for d in durs])
    t_m = np.array([d.t_moment for d in durs])
    simple = np.stack([simplified_boundary(p, a, b, alpha) for a, b in zip(t_i, t_m,
                                                                            strict=True)])
    has_tm = np.isfinite(tm)
    if has_tm.any():
        x, curve = normalised_curve(ds["boundary"].values[has_tm], p, tm[has_tm], q)
        tm_site = float(np.exp(np.mean(np.log(tm[has_tm]))))
        site_norm = _log_interp(p * tm_site, x, np.where(np.isfinite(curve), curve, np.inf))
    else:  # no record long enough for a mean period: no normalised curve
        x, curve, tm_site = p.copy(), np.full(p.size, np.nan), float("nan")
        site_norm = np.full(p.size, np.nan)
    out = ds.copy()
    out["tm"] = (("record",), tm)
    out["t_impulse"] = (("record",), t_i)
    out["t_moment"] = (("record",), t_m)
    out["simplified_record"] = (("record", "p"), simple)
    out["simplified"] = (("p",), np.percentile(simple, q, axis=0, method="lower"))
    out["normalised"] = (("p",), np.where(np.isfinite(site_norm), site_norm, np.nan))
    out = out.assign_coords(x=x)
    out["normalised_curve"] = (("x",), curve)
    out["x"].attrs.update(units="1", long_name="p·Tm")
    for name in ("tm", "t_impulse", "t_moment"):
        out[name].attrs.update(units="s")
    out["simplified_record"].attrs.update(units="1", long_name="simplified overturning "
                                          "ap/ap,min of each record")
    for name, what in (("simplified", "simplified overturning ap/ap,min"),
                       ("normalised", "normalised overturning ap/ap,min at p·Tm_site"),
                       ("normalised_curve", "overturning ap/ap,min over x = p·Tm")):
        out[name].attrs.update(units="1", long_name=f"{q:g} percentile of the records' "
                               f"{what}")
    out.attrs.update(tm_site=tm_site, percentile_characteristic=q,
                     impact_coeff=IMPACT_COEFF)
    return spectra.note_units(out)


def skill(ds: xr.Dataset) -> dict:
    """How well each curve predicts the computed boundaries of :func:`characteristic`'s
    dataset (pairs (record, p) whose boundary lies within the ratio range):

    ``raw``: ln(b / median over records at the same p); ``normalised``: ln(b / the
    normalised median curve at p·Tm_k); ``simplified``: ln(b / the record's simplified
    boundary). For each: the standard deviation ``dispersion`` and mean ``bias`` of the
    log ratio, and ``safe`` = the fraction of pairs where the prediction is <= b (safe
    side).
    """
    b = ds["boundary"].values
    p = ds["p"].values
    ok = np.isfinite(b)
    b_inf = np.where(ok, b, np.inf)
    raw = np.percentile(b_inf, 50, axis=0, method="lower")[None, :] * np.ones_like(b)
    tm = ds["tm"].values
    norm = np.full(b.shape, np.nan)
    if np.isfinite(tm).any():
        x, med = normalised_curve(b[np.isfinite(tm)], p, tm[np.isfinite(tm)], 50.0)
        med = np.where(np.isfinite(med), med, np.inf)
        norm = np.stack([_log_interp(p * s, x, med) if np.isfinite(s)
                         else np.full(p.size, np.nan) for s in tm])
    out = {"pairs": int(ok.sum()), "censored_pairs": int((~ok).sum())}
    for name, pred in (("raw", raw), ("normalised", norm),
                       ("simplified", ds["simplified_record"].values)):
        out[name] = log_skill(b, pred)
    return out


def log_skill(boundary, predicted) -> dict:
    """Dispersion (std), bias (mean) of ln(boundary/predicted) and the safe fraction
    (predicted <= boundary) over the pairs where both are finite."""
    b = np.asarray(boundary, dtype=float)
    pred = np.asarray(predicted, dtype=float)
    use = np.isfinite(b) & np.isfinite(pred)
    if not use.any():
        return {"dispersion": float("nan"), "bias": float("nan"), "safe": float("nan"),
                "pairs": 0}
    lr = np.log(b[use] / pred[use])
    return {"dispersion": float(lr.std()), "bias": float(lr.mean()),
            "safe": float(np.mean(lr >= 0)), "pairs": int(use.sum())}


#: p grid and ratio grid of a site OAS computed on the fly (``rockarch design --records``;
#: our choice).
DESIGN_P = np.round(np.geomspace(0.5, 10.0, 40), 6)
DESIGN_RATIO = np.round(np.linspace(1.0, 5.0, 81), 12)


def site_from_records(suite, *, percentile: float = 50.0, executor=None, store=None,
                      progress: bool = False, log=None) -> xr.Dataset:
    """The slender-block site OAS of a suite (:func:`rockarch.motion.suite.read_suite`) on
    :data:`DESIGN_P` × :data:`DESIGN_RATIO`, with the characteristic curves added (``log``:
    a line per record done, as in :func:`rockarch.spectra.site.site_oas`)."""
    ds = site.site_oas(suite, DESIGN_P, DESIGN_RATIO, percentile=percentile,
                       progress=progress, executor=executor, store=store, log=log)
    ds["record_name"] = (("record",), np.array(suite.names, dtype=str),
                         ds["record_name"].attrs)
    return characteristic(ds, suite.motions)
