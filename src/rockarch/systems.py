"""Rocking systems by kind: the one place where a structure is built from its options.

Theory: docs/theory.md §2 (the ratio and p axes, Eq. 2.1), §3 (SDOF mechanisms), §11.4
(a structure scaled to p, Eq. 11.33).

Every kind of structure (:data:`KINDS`) becomes a *system*: a small frozen object with a
name, the limit acceleration ``ap_min`` that the ratio ap/ap,min multiplies, a reference
frequency parameter ``p_ref``, and three calls that take the ground motion's *shape*:

- ``simulate(motion, ratio=, p=None)`` -> :class:`~rockarch.core.response.Response`: one time
  history, the motion scaled to PGA = ratio·ap_min, the structure scaled to frequency
  parameter p (p ∝ 1/sqrt(size) at fixed shape; None: its own size);
- ``batch(motion, p, ratio)`` -> :class:`~rockarch.core.response.Batch`: many verdicts in
  parallel (the OAS axes, docs/theory.md Eq. 2.1);
- ``run(motion, p, ratio)`` -> (overturned, max_rotation_ratio): what a sweep stores.

:func:`system` builds one from the keywords of ``rockarch oas`` / ``rockarch simulate``
(the CLI calls it; so can a Python user). Sign conventions: docs/theory.md Sect. 0.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import asdict, dataclass, replace

import numpy as np

from rockarch import mdof
from rockarch.arch.geometry import make_arch
from rockarch.core.constants import EPS_REST, GAP_TOL, MDOF_H_FACTOR, SDOF_H_FACTOR, T_FREE, G
from rockarch.core.response import Batch, Response
from rockarch.core.validate import (
    in_range,
    integer,
    number,
    numbers,
    positive,
    ratio_value,
    show,
)
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.simulate import check_h_factor, checks_step_by_default
from rockarch.motion.signals import GroundMotion
from rockarch.rocking import mechanism as mc
from rockarch.rocking.block import RigidBlock
from rockarch.rocking.block import simulate as block_simulate
from rockarch.rocking.block import simulate_batch as block_batch
from rockarch.rocking.fourhinge_motion import fourhinge_mechanism

#: The system kinds, with one line each (the CLI's --system choices and help).
KINDS = {
    "block": "rigid rectangular block (Housner), given alpha (and p or width/height)",
    "fourhinge": "the four-hinge mechanism of an arch (exact linkage kinematics)",
    "frame": "rocking frame: two rigid columns and a rigid lintel",
    "sdof": "any SDOF rocking mechanism given by p, delta and ap,min",
    "mdof": "multi-block structure (arch, arch on piers or bridge, column, wall, colonnade, "
            "assembly file) whose joints open, close and (with friction) slide",
}

#: Fewest voussoirs of a four-hinge mechanism.
MIN_FOURHINGE_BLOCKS = 4


def check_motion(motion, name: str = "motion") -> GroundMotion:
    """``motion`` if it is a :class:`GroundMotion`, else a TypeError naming ``name`` and
    how to make one (a path is read by ``ra.read_record``; a system first: swapped?)."""
    if isinstance(motion, GroundMotion):
        return motion
    if isinstance(motion, (str, os.PathLike)):
        hint = f": read the file first, ra.read_record({str(motion)!r})"
    elif isinstance(motion, _Sweepable):
        hint = " (a system: the system comes first, ra.simulate(system, motion, ratio=...))"
    else:
        hint = " (ra.pulse, ra.read_record or ra.el_centro make one)"
    raise TypeError(f"{name} must be a GroundMotion, got {type(motion).__name__}{hint}"[:300])


def check_system(sys_, name: str = "sys_"):
    """``sys_`` if it is a system of :func:`system`, else a TypeError naming ``name``."""
    if isinstance(sys_, _Sweepable):
        return sys_
    if isinstance(sys_, GroundMotion):
        hint = " (a ground motion: the system comes first, ra.simulate(system, motion, ...))"
    elif isinstance(sys_, str) and sys_ in KINDS:
        hint = f": build it first, ra.system({sys_!r}, ...)"
    else:
        hint = " (ra.system(kind, ...) builds one)"
    raise TypeError(f"{name} must be a system, got {type(sys_).__name__}{hint}"[:300])


def scale_to_ratio(motion: GroundMotion, ratio: float, ap_min: float) -> GroundMotion:
    """The motion scaled so that its peak |a_g| is ratio·ap_min (docs/theory.md Eq. 2.1)."""
    motion = check_motion(motion)
    if isinstance(ratio, (list, tuple, np.ndarray)) and np.ndim(ratio) > 0:
        raise TypeError(f"ratio must be one number, got {type(ratio).__name__} of "
                        f"{np.size(ratio)} (many ratios: ra.batch or ra.oas)")
    ratio = ratio_value("ratio", ratio)
    return motion.scaled(ratio * ap_min / motion.pga)


class _Sweepable:
    """What a sweep asks of every system: :meth:`run` on top of its ``batch``."""

    def batch(self, motion: GroundMotion, p, ratio) -> Batch:
        raise NotImplementedError

    def run(self, motion: GroundMotion, p, ratio):
        """(overturned, max_rotation_ratio) over the broadcast p × ratio (Eq. 2.1)."""
        res = self.batch(motion, p, ratio)
        return res.overturned, res.max_rotation_ratio


class _Scaled(_Sweepable):
    """A structure of fixed shape whose p varies by scaling its size, simulated by one
    engine module (``simulate``/``simulate_batch`` over the model of :meth:`_engine`)."""

    def _engine(self) -> tuple:
        """(engine module, model, settings keywords, extra keywords of the batch)."""
        raise NotImplementedError

    def simulate(self, motion: GroundMotion, *, ratio: float, p: float | None = None
                 ) -> Response:
        engine, model, kw, _ = self._engine()
        return engine.simulate(model, scale_to_ratio(motion, ratio, self.ap_min), p=p, **kw)

    def batch(self, motion: GroundMotion, p, ratio) -> Batch:
        engine, model, kw, batch_kw = self._engine()
        return engine.simulate_batch(model, motion, p, ratio, **batch_kw, **kw)


@dataclass(frozen=True)
class BlockSystem(_Sweepable):
    """Rigid blocks of slenderness ``alpha`` (p varies across an OAS; ``p`` is the
    default of :meth:`simulate`)."""

    alpha: float
    g: float = G
    restitution: float | None = None
    t_free: float = T_FREE
    h_factor: float = SDOF_H_FACTOR
    eps_rest: float = EPS_REST
    name: str = "block"
    p: float | None = None

    def __repr__(self) -> str:
        """One line: the name, alpha, p (or that an OAS varies it) and ap_min."""
        p = "p varies" if self.p is None else f"p {self.p:.4g} 1/s"
        r = "" if self.restitution is None else f", restitution {self.restitution:.4g}"
        return (f"BlockSystem({self.name!r}, alpha {self.alpha:.4g} rad, {p}, "
                f"ap_min {self.ap_min:.4g} m/s²{r})")

    def __post_init__(self) -> None:
        RigidBlock(1.0 if self.p is None else self.p, self.alpha, self.g,
                   self.restitution)  # validate

    def block(self, p: float | None = None) -> RigidBlock:
        """The rigid block of frequency parameter p (default: the system's own)."""
        p = self.p if p is None else p
        if p is None:
            raise ValueError("a block needs its frequency parameter: give p (or width and "
                             "height)")
        return RigidBlock(p, self.alpha, self.g, self.restitution)

    @property
    def ap_min(self) -> float:
        """g·tan(alpha) [m/s²] (paper Eq. 2)."""
        return RigidBlock(1.0, self.alpha, self.g, self.restitution).ap_min

    @property
    def p_ref(self) -> float | None:
        return self.p

    def simulate(self, motion: GroundMotion, *, ratio: float, p: float | None = None
                 ) -> Response:
        blk = self.block(p)
        return block_simulate(blk, scale_to_ratio(motion, ratio, blk.ap_min),
                              t_free=self.t_free, h_factor=self.h_factor,
                              eps_rest=self.eps_rest)

    def batch(self, motion: GroundMotion, p, ratio) -> Batch:
        return block_batch(RigidBlock(1.0, self.alpha, self.g, self.restitution), motion, p,
                           ratio, t_free=self.t_free, h_factor=self.h_factor,
                           eps_rest=self.eps_rest)

    def attrs(self) -> dict:
        d = {k: v for k, v in asdict(self).items() if v is not None}
        d["restitution"] = RigidBlock(1.0, self.alpha, self.g, self.restitution).r
        d["ap_min"] = self.ap_min
        return d


@dataclass(frozen=True)
class MechanismSystem(_Scaled):
    """An SDOF mechanism of fixed shape: p varies by scaling its size (p ∝ 1/sqrt(size));
    ratio scales the motion to a peak of ratio·ap_min."""

    mechanism: mc.SDOFMechanism
    t_free: float = T_FREE
    h_factor: float = SDOF_H_FACTOR
    eps_rest: float = EPS_REST

    def __repr__(self) -> str:
        """One line: the mechanism's (name, kind, p, delta, ap_min), not its tables."""
        return f"MechanismSystem({self.mechanism!r})"

    @property
    def name(self) -> str:
        return self.mechanism.name

    @property
    def ap_min(self) -> float:
        return self.mechanism.ap_min

    @property
    def p_ref(self) -> float:
        return self.mechanism.p

    def _engine(self) -> tuple:
        return mc, self.mechanism, {"t_free": self.t_free, "h_factor": self.h_factor,
                                    "eps_rest": self.eps_rest}, {}

    def attrs(self) -> dict:
        m = self.mechanism
        d = {"kind": "mechanism", "ap_min": m.ap_min, "delta": m.delta, "p_ref": m.p,
             "size_ref": m.size, "g": m.g, "t_free": self.t_free, "h_factor": self.h_factor,
             "eps_rest": self.eps_rest,
             "restitution": -1.0 if m.restitution is None else m.restitution,
             "e_plus": m.plus.e_close, "e_minus": m.minus.e_close}
        d.update({k: v for k, v in m.info.items() if isinstance(v, (int, float, str))})
        return d


@dataclass(frozen=True)
class MDOFSystem(_Scaled):
    """An MDOF assembly of fixed shape: p varies by scaling its size (p ∝ 1/sqrt(size)),
    ratio scales the motion's peak to ratio·ap_min.

    ``ap_min_override``/``p_override`` put the map on another structure's axes (e.g. the
    critical optimal four-hinge mechanism's, for the paper's Hypotheses 2 and 3); by
    default the assembly's own (arch: N-voussoir LP and four-hinge mechanism).
    """

    assembly: Assembly
    ap_min_override: float | None = None
    p_override: float | None = None
    t_free: float = T_FREE
    h_factor: float = MDOF_H_FACTOR
    gap_tol: float = GAP_TOL

    def __repr__(self) -> str:
        """One line: the assembly's (name, kind, block and joint counts, ap_min, p, delta),
        and the axes of the map where another structure's are put on it."""
        axes = "".join(f", {k} {v:.4g}{u}" for k, v, u in
                       (("ap_min", self.ap_min_override, " m/s²"),
                        ("p", self.p_override, " 1/s")) if v is not None)
        return f"MDOFSystem({self.assembly!r}{axes and ', axes:' + axes[1:]})"

    def __post_init__(self) -> None:
        mdof.check_settings(self.t_free, self.h_factor, self.gap_tol)

    @property
    def name(self) -> str:
        return self.assembly.name

    @property
    def ap_min(self) -> float:
        a = self.ap_min_override
        return self.assembly.ap_min if a is None else a

    @property
    def p_ref(self) -> float:
        p = self.p_override
        return self.assembly.p_ref if p is None else p

    def _engine(self) -> tuple:
        return mdof, self.assembly, {"t_free": self.t_free, "h_factor": self.h_factor,
                                     "gap_tol": self.gap_tol}, \
            {"ap_min": self.ap_min_override, "p_ref": self.p_override}

    def simulate(self, motion: GroundMotion, *, ratio: float, p: float | None = None,
                 check_step: bool | None = None) -> Response:
        """One time history (:func:`rockarch.mdof.simulate`); ``check_step``: rerun it at
        h/2 and say whether it is sensitive to the step (``h_half``, ``step_sensitive``);
        None (default): on the chain stepper and up to
        :data:`rockarch.mdof.simulate.STEP_CHECK_MAX_BLOCKS` blocks."""
        if check_step is None:
            check_step = checks_step_by_default(self.assembly)
        return mdof.simulate(self.assembly, scale_to_ratio(motion, ratio, self.ap_min), p=p,
                             t_free=self.t_free, h_factor=self.h_factor,
                             gap_tol=self.gap_tol, check_step=check_step)

    def attrs(self) -> dict:
        a = self.assembly
        d = {"kind": "mdof", "assembly": a.kind, "blocks": a.n_blocks, "joints": a.n_joints,
             "ap_min": self.ap_min, "p_ref": self.p_ref,
             "ap_min_assembly": a.ap_min, "p_assembly": a.p_ref, "delta_ref": a.delta_ref,
             "size_ref": a.size, "g": a.g, "t_free": self.t_free, "h_factor": self.h_factor,
             "gap_tol": self.gap_tol}
        if not a.frictionless:
            d["friction_min"] = float(np.min(a.mu))
        d.update({k: v for k, v in a.info.items() if isinstance(v, (int, float, str))})
        return d


#: Largest acceleration of gravity accepted [m/s²] (the Sun's surface has 274).
G_MAX = 1000.0

_ARCH = ("shape", "span", "rise", "thickness", "rise_over_span", "thickness_over_span",
         "blocks")
_MDOF_ONLY = ("column", "friction", "spans", "pier_height", "pier_width", "pier_blocks",
              "abutments", "wall", "block", "colonnade", "drums", "bay", "lintel", "assembly")
#: The keywords of :func:`system` that each kind takes (g, t_free and gap_tol: every kind).
_APPLIES = {
    "block": {"alpha", "p", "width", "height", "restitution", "h_factor"},
    "frame": {"alpha", "p", "mass_ratio", "restitution", "h_factor"},
    "sdof": {"p", "delta", "ap_min", "restitution", "h_factor"},
    "fourhinge": {*_ARCH, "restitution", "h_factor"},
    "mdof": {*_ARCH, *_MDOF_ONLY, "h_factor", "restitution"},  # restitution: its own message
}
_NUMBERS = ("alpha", "p", "width", "height", "span", "rise", "thickness", "rise_over_span",
            "thickness_over_span", "mass_ratio", "delta", "ap_min", "restitution", "g",
            "t_free", "h_factor", "gap_tol", "friction", "pier_height", "pier_width", "bay",
            "lintel")
_INTEGERS = ("blocks", "spans", "pier_blocks", "colonnade", "drums")
_EVERY_KIND = ("g", "t_free", "gap_tol")
_ALL_KEYWORDS = {*_NUMBERS, *_INTEGERS, "shape", "column", "abutments", "wall", "block",
                 "assembly"}


def _check_types(given: dict) -> None:
    """TypeError naming the keyword of :func:`system` whose value has the wrong type
    (``alpha=True`` is not 1 rad, ``blocks=20.9`` is not 20 voussoirs)."""
    for k, v in given.items():
        if k in _NUMBERS:
            number(k, v)
        elif k in _INTEGERS:
            integer(k, v)
        elif k == "shape" and not isinstance(v, str):
            raise TypeError(f"shape must be a string (one of catenary, circular, pointed, "
                            f"elliptical), got {type(v).__name__}")
        elif k == "abutments" and not isinstance(v, (bool, np.bool_)):
            raise TypeError(f"abutments must be True or False, got {type(v).__name__}")
        elif k == "column" and isinstance(v, str):
            raise TypeError("column must be a sequence of (width, height[, x_centre]) rows, "
                            f"got str {v!r} (the CLI's --column text is parsed by it)")
        elif k in ("column", "wall", "block") and isinstance(v, (int, float, bool)):
            raise TypeError(f"{k} must be a sequence (or the CLI's comma-separated text), "
                            f"got {type(v).__name__} {v!r}")
        elif k == "assembly" and not isinstance(v, (str, dict, os.PathLike)):
            raise TypeError(f"assembly must be a JSON file's path or its dict, got "
                            f"{type(v).__name__}")


def _need(by: str | list[str], **given) -> None:
    """Raise a ValueError naming the options of ``given`` that are None.

    Parameters
    ----------
    by : str or list of str
        What needs them: a system kind ("mdof": "--system mdof needs ...") or the flags of
        the options given that need them (["--spans", "--pier-height"]: "--spans,
        --pier-height need ..."), for commands without --system (simulate KIND, animate).
    **given
        The options needed, by keyword.
    """
    missing = [k for k, v in given.items() if v is None]
    if missing:
        flags = ", ".join("--" + k.replace("_", "-") for k in missing)
        subject = f"--system {by}" if isinstance(by, str) else ", ".join(by)
        verb = "need" if isinstance(by, list) and len(by) > 1 else "needs"
        raise ValueError(f"{subject} {verb} {flags} (keywords: {', '.join(missing)})")


def check_blocks(blocks: int | None) -> int | None:
    """Voussoirs of a four-hinge mechanism: None (continuous) or at least 4."""
    if blocks is not None and blocks < MIN_FOURHINGE_BLOCKS:
        raise ValueError(f"at least {MIN_FOURHINGE_BLOCKS} voussoirs are needed for a "
                         f"four-hinge mechanism, got {blocks}")
    return blocks


def _arch(shape, span, rise, thickness, rise_over_span, thickness_over_span, kind):
    """The arch of a fourhinge/mdof system: real size (span, rise, thickness) or the
    shape at span 1 (rise_over_span, thickness_over_span)."""
    if span is not None or rise is not None or thickness is not None:
        if rise_over_span is not None or thickness_over_span is not None:
            raise ValueError("give either span/rise/thickness or rise_over_span/"
                             "thickness_over_span, not both")
        _need(kind, shape=shape, span=span, rise=rise, thickness=thickness)
        return make_arch(shape, positive("span", span), positive("rise", rise),
                         positive("thickness", thickness))
    _need(kind, shape=shape, rise_over_span=rise_over_span,
          thickness_over_span=thickness_over_span)
    return make_arch(shape, 1.0, positive("rise_over_span", rise_over_span),
                     positive("thickness_over_span", thickness_over_span))


def system(kind: str, *, alpha: float | None = None, p: float | None = None,
           width: float | None = None, height: float | None = None,
           shape: str | None = None, span: float | None = None, rise: float | None = None,
           thickness: float | None = None, rise_over_span: float | None = None,
           thickness_over_span: float | None = None, blocks: int | None = None,
           column: Sequence[Sequence[float]] | None = None, mass_ratio: float | None = None,
           delta: float | None = None, ap_min: float | None = None,
           restitution: float | None = None, g: float = G, t_free: float = T_FREE,
           h_factor: float | None = None, gap_tol: float = GAP_TOL,
           friction: float | None = None, spans: int | None = None,
           pier_height: float | None = None, pier_width: float | None = None,
           pier_blocks: int | None = None, abutments: bool | None = None,
           wall: Sequence[int] | None = None, block: Sequence[float] | None = None,
           colonnade: int | None = None, drums: int | None = None,
           bay: float | None = None, lintel: float | None = None, assembly=None):
    """Build a rocking structure of one kind: a block, a mechanism or a multi-block assembly.

    The same options as ``rockarch simulate/oas --system KIND``; each kind takes its own
    (another kind's option is a ValueError that says so). The result is what
    :func:`simulate`, :func:`batch`, :func:`rockarch.oas` and the site, fragility and design
    functions take. Theory: docs/theory.md §1 (block), §3 and §5 (mechanisms), §6, §9, §10
    (assemblies).

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`: ``"block"``, ``"fourhinge"``, ``"frame"``, ``"sdof"``,
        ``"mdof"``.
    alpha : float, optional
        block: slenderness atan(B/H) [rad]; frame: slenderness of the columns [rad].
    p : float, optional
        block: frequency parameter sqrt(3g/(4R)) [1/s] (optional: an OAS varies it);
        frame: p of one column [1/s] (default 1); sdof: p [1/s] (default 1).
    width, height : float, optional
        block: full width B and height H [m], instead of alpha and p.
    shape : str, optional
        fourhinge/mdof: arch shape, ``"catenary"``, ``"circular"``, ``"pointed"`` or
        ``"elliptical"``.
    span, rise, thickness : float, optional
        fourhinge/mdof: the arch's axis span and rise and its thickness [m].
    rise_over_span, thickness_over_span : float, optional
        fourhinge/mdof: the arch at span 1, by ratios [-] (instead of span, rise,
        thickness).
    blocks : int, optional
        fourhinge: voussoirs (default: the continuous arch); mdof: voussoirs of the arch
        (required for an arch).
    column : sequence of (B, H) or (B, H, x), optional
        mdof: a column instead of an arch, blocks bottom to top (x: the block's
        horizontal centre, default 0) [m].
    mass_ratio : float, optional
        frame: lintel mass over the mass of both columns [-].
    delta, ap_min : float, optional
        sdof: neutral angle [rad] and limit acceleration ap,min [m/s²] (with ``p``).
    restitution : float, optional
        Coefficient of restitution in [0, 1] (default: the structure's own impact law; not
        for mdof, whose impacts follow from the geometry).
    g : float
        Acceleration of gravity [m/s²] (default 9.81).
    t_free : float
        Free motion simulated after the record ends before "safe" is declared [s]
        (default 10).
    h_factor : float, optional
        Time step × p [-] (default per model, :mod:`rockarch.core.constants`).
    gap_tol : float
        mdof: contact tolerance as a fraction of the thinnest joint [-].
    friction : float, optional
        mdof: Coulomb friction coefficient of every joint [-] (None: no sliding, the chain
        model bit for bit); ``ap_min`` is then the friction-aware collapse acceleration
        (non-associative, docs/theory.md Eqs. (10.4)–(10.9); one block: min(mu, B/H)·g).
    spans, pier_height, pier_width, pier_blocks, abutments : optional
        mdof: the arch on piers (``spans`` 1) or a bridge of ``spans`` equal arches; pier
        height and width [m], blocks per pier, abutments instead of end piers
        (:func:`rockarch.mdof.builders.bridge`).
    wall : (int, int), optional
        mdof: a wall in running bond of (rows, columns) blocks of size ``block``.
    block : (float, float), optional
        mdof: the (B, H) of a wall's or a colonnade's blocks [m].
    colonnade : int, optional
        mdof: that many columns of size ``block``, ``bay`` [m] apart, under a lintel of
        depth ``lintel`` [m] (2 columns: a trilithon).
    drums : int, optional
        mdof: each column of ``colonnade`` made of that many equal drums stacked with dry
        joints (default 1: monolithic columns); only with ``colonnade``.
    bay, lintel : float, optional
        mdof: column spacing and lintel depth of a colonnade [m].
    assembly : path or dict, optional
        mdof: a JSON file (or its dict) of convex blocks
        (:mod:`rockarch.mdof.assembly_file`).

    Returns
    -------
    BlockSystem, MechanismSystem or MDOFSystem
        ``BlockSystem`` for ``"block"``, ``MechanismSystem`` for ``"fourhinge"``,
        ``"frame"`` and ``"sdof"``, ``MDOFSystem`` for ``"mdof"``; each has ``name``,
        ``ap_min`` [m/s²] and ``p_ref`` [1/s] (None for a block given by alpha alone).

    Raises
    ------
    TypeError
        If ``kind`` is not a string or an option has the wrong type.
    ValueError
        If ``kind`` is unknown, a required option is missing, an option does not apply to
        ``kind``, a value is out of range, or the arch has no four-hinge mechanism.

    Examples
    --------
    >>> import rockarch as ra
    >>> blk = ra.system("block", width=0.4, height=2.0)
    >>> round(blk.alpha, 4), round(blk.p, 3), round(blk.ap_min, 3)
    (0.1974, 2.686, 1.962)
    >>> arch = ra.system("fourhinge", shape="circular", span=10, rise=2.89, thickness=0.35)
    >>> arch.name
    'four-hinge circular arch l=10 f=2.89 d=0.35'
    """
    if not isinstance(kind, str) or kind not in KINDS:
        raise (ValueError if isinstance(kind, str) else TypeError)(
            f"unknown system kind {kind!r}: choose one of {', '.join(KINDS)}"[:200])
    given = {k: v for k, v in locals().items() if k in _ALL_KEYWORDS and v is not None}
    _check_types(given)
    g = in_range("g", g, 0.0, G_MAX, lo_open=True)
    t_free = in_range("t_free", t_free, 0.0, math.inf, hi_open=True)
    if h_factor is not None:
        h_factor = check_h_factor(h_factor)
    sdof_h = SDOF_H_FACTOR if h_factor is None else h_factor
    mdof_only = [k for k in _MDOF_ONLY if k in given]
    if kind != "mdof" and mdof_only:
        raise ValueError(f"--{mdof_only[0].replace('_', '-')} belongs to --system mdof, not "
                         f"{kind}")
    extra = [k for k in given if k not in _APPLIES[kind] and k not in _EVERY_KIND]
    if extra:
        raise ValueError(f"--{extra[0].replace('_', '-')} does not apply to --system {kind} "
                         f"({KINDS[kind]}): leave it out")
    if kind == "block":
        if width is not None or height is not None:
            if p is not None or alpha is not None:
                raise ValueError("give either width/height or p/alpha, not both")
            _need([f for f, v in (("--width", width), ("--height", height))
                   if v is not None], width=width, height=height)
            blk = RigidBlock.from_dimensions(width, height, g, restitution)
            p, alpha = blk.p, blk.alpha
        _need(kind, alpha=alpha)
        return BlockSystem(alpha=alpha, g=g, restitution=restitution, t_free=t_free,
                           h_factor=sdof_h, p=p)
    if kind == "mdof":
        check_drums(drums, colonnade)  # before an arch is asked for
        if restitution is not None:
            raise ValueError("an mdof system has no restitution: joints close with "
                             "inelastic impacts (the restitution follows from the geometry)")
        arch = None
        if column is None and wall is None and colonnade is None and assembly is None:
            arch = _arch(shape, span, rise, thickness, rise_over_span, thickness_over_span,
                         kind)
            _need(kind, blocks=blocks)
            if span is None and (pier_height is not None or pier_width is not None):
                raise ValueError("--pier-height and --pier-width are in metres: give the "
                                 "arch in metres too (--span --rise --thickness), not as "
                                 "ratios of a span of 1")
        else:
            other = next(k for k, v in (("column", column), ("wall", wall),
                                        ("colonnade", colonnade), ("assembly", assembly))
                         if v is not None)
            arch_opts = [k for k in _ARCH if k in given]
            if arch_opts:
                raise ValueError(f"--{arch_opts[0].replace('_', '-')} describes an arch: it "
                                 f"does not apply to --{other} (give one structure)")
        assembly = mdof_assembly(
            arch=arch, blocks=blocks, column=column, friction=friction, spans=spans,
            pier_height=pier_height, pier_width=pier_width, pier_blocks=pier_blocks,
            abutments=abutments, wall=wall, block=block, colonnade=colonnade, drums=drums,
            bay=bay, lintel=lintel, assembly=assembly, g=g)
        return MDOFSystem(assembly, t_free=t_free,
                          h_factor=MDOF_H_FACTOR if h_factor is None else h_factor,
                          gap_tol=gap_tol)
    if kind == "fourhinge":
        arch = _arch(shape, span, rise, thickness, rise_over_span, thickness_over_span,
                     kind)
        label = None
        if span is None:
            label = f"{shape} f/l={rise_over_span:g} d/l={thickness_over_span:g}"
        mech = fourhinge_mechanism(arch, check_blocks(blocks), g=g, restitution=restitution,
                                   name=label)
    elif kind == "frame":
        _need(kind, alpha=alpha, mass_ratio=mass_ratio)
        mech = mc.rocking_frame(alpha, 1.0 if p is None else p, mass_ratio, g, restitution)
    else:
        _need(kind, delta=delta, ap_min=ap_min)
        mech = mc.generic(1.0 if p is None else p, delta, ap_min, g, restitution)
        if p is None:  # p is the axis of its maps: its reference 1 1/s is not named
            mech = replace(mech, name=f"SDOF delta={delta:g} rad, ap,min={ap_min:g} m/s²")
    return MechanismSystem(mech, t_free=t_free, h_factor=sdof_h)


def _pair(name: str, form: str, values) -> tuple:
    """``values`` as a pair: a sequence, or the CLI's comma-separated text ("0.4,0.2")."""
    if isinstance(values, str):
        try:
            values = [float(v) for v in values.split(",")]
        except ValueError:
            raise ValueError(f"{name} needs 2 comma-separated numbers ({form}), got "
                             f"{values!r}") from None
    vals = tuple(values)
    if len(vals) != 2:
        raise ValueError(f"{name} needs 2 values ({form}), got {len(vals)}")
    return vals


def check_drums(drums, colonnade) -> None:
    """Drums per column (``--drums``): None, or an integer >= 1 beside a colonnade.

    Parameters
    ----------
    drums : int or None
        Drums per column of the colonnade.
    colonnade : int or None
        Columns of the colonnade (None: no colonnade).

    Raises
    ------
    TypeError
        If ``drums`` is not a whole number.
    ValueError
        If ``drums`` is below 1, or given without a colonnade.
    """
    if drums is None:
        return
    if colonnade is None:
        raise ValueError("--drums divides the columns of a colonnade: give --colonnade N "
                         "(with --block B,H --bay S --lintel D) or leave --drums out")
    if integer("drums", drums) < 1:
        raise ValueError(f"--drums must be an integer >= 1 (drums per column), got "
                         f"{show(drums)}")


def mdof_assembly(*, arch=None, blocks=None, column=None, friction=None, spans=None,
                  pier_height=None, pier_width=None, pier_blocks=None, abutments=None,
                  wall=None, block=None, colonnade=None, drums=None, bay=None, lintel=None,
                  assembly=None, g: float = G) -> Assembly:
    """The MDOF assembly of :func:`system`'s keywords: exactly one of an arch (alone or on
    piers), a column, a wall, a colonnade or an assembly file, with ``friction``."""
    from rockarch.mdof import assembly_file, builders

    given = [k for k, v in (("arch", arch), ("column", column), ("wall", wall),
                            ("colonnade", colonnade), ("assembly", assembly)) if v is not None]
    if len(given) != 1:
        raise ValueError(f"give one mdof structure, got {', '.join(given) or 'none'}")
    piers = {"spans": spans, "pier_height": pier_height, "pier_width": pier_width,
             "pier_blocks": pier_blocks, "abutments": abutments}
    if any(v is not None for v in piers.values()) and arch is None:
        raise ValueError("--spans/--pier-height/--pier-width/--pier-blocks/--abutments "
                         "build piers under an arch: give the arch too")
    if block is not None and wall is None and colonnade is None:
        raise ValueError("--block sizes the blocks of a wall or a colonnade")
    if (bay is not None or lintel is not None) and colonnade is None:
        raise ValueError("--bay and --lintel belong to a colonnade")
    check_drums(drums, colonnade)
    mu = None if friction is None else builders.friction_value(friction)
    if assembly is not None:
        if isinstance(assembly, dict):
            return assembly_file.assembly_from_dict(assembly, mu=mu, g=g)
        return assembly_file.read_assembly(assembly, mu=mu, g=g)
    if wall is not None or colonnade is not None:
        if block is None:
            raise ValueError(f"--{'wall' if wall is not None else 'colonnade'} needs --block "
                             "B,H: the size of its blocks [m] (keyword: block)")
        bw, bh = _pair("--block", "B,H", block)
        if wall is not None:
            rows, cols = _pair("--wall", "ROWS,COLUMNS", wall)
            if not all(float(v).is_integer() for v in (rows, cols)):
                raise ValueError(f"--wall needs whole numbers of rows and columns, got "
                                 f"{show(wall)}")
            rows, cols = int(rows), int(cols)
            a = builders.wall(rows, cols, bw, bh, mu=mu, g=g)
            assembly_file.warn_implausible_size(a, a.name)
            return a
        _need(["--colonnade"], bay=bay, lintel=lintel)
        a = builders.colonnade(colonnade, bw, bh, bay, lintel,
                               drums=1 if drums is None else drums, mu=mu, g=g)
        assembly_file.warn_implausible_size(a, a.name)
        return a
    if arch is not None and any(v is not None for v in piers.values()):
        by = [("--end-piers" if k == "abutments" and v is False else
               "--" + k.replace("_", "-")) for k, v in piers.items() if v is not None]
        _need(by, pier_height=pier_height, pier_width=pier_width)
        return builders.bridge(arch, blocks, spans=1 if spans is None else spans,
                               pier_height=pier_height, pier_width=pier_width,
                               pier_blocks=pier_blocks, abutments=abutments, mu=mu, g=g)
    if column is not None:
        a = mdof.column(column, g=g)
        assembly_file.warn_implausible_size(a, a.name)
    else:
        a = mdof.arch_assembly(arch, blocks, g=g)
    return a if mu is None else builders.with_friction(a, mu)


def simulate(sys_, motion: GroundMotion, *, ratio: float, p: float | None = None,
             check_step: bool | None = None) -> Response:
    """One time history of a system on a ground motion scaled to PGA = ratio·ap,min.

    The motion's shape is scaled so that its peak |a_g| is ratio·ap,min (docs/theory.md
    Eq. (2.1)); the structure rocks until it overturns (Eqs. (1.5), (3.5)) or comes to rest
    after the motion and a free motion of ``t_free`` (a setting of :func:`system`).

    Parameters
    ----------
    sys_ : BlockSystem, MechanismSystem or MDOFSystem
        The structure, from :func:`system`.
    motion : GroundMotion
        The ground motion (:func:`rockarch.pulse`, :func:`rockarch.read_record`,
        :func:`rockarch.el_centro`); its amplitude is replaced by ratio·ap,min [m/s²].
    ratio : float
        Peak ground acceleration over the structure's ap,min [-], >= 0 (one number; for
        many, :func:`batch` or :func:`rockarch.oas`).
    p : float, optional
        Frequency parameter [1/s] to simulate at: a block of that p, any other structure
        scaled to it (same shape, same ap,min). None: the structure as built (a block built
        from ``alpha`` alone has no p: give one).
    check_step : bool, optional
        MDOF systems only: rerun the history at half the time step and report in
        ``step_sensitive`` whether the verdict depends on it (:meth:`MDOFSystem.simulate`;
        None: its default, docs/mdof.md).

    Returns
    -------
    Response
        ``overturned``, ``t_overturn`` [s] (None if safe), ``max_rotation_ratio`` [-],
        ``impacts``, ``t`` [s] and the kind's own histories (``BlockResponse``: ``theta``
        [rad]; ``MechanismResponse``: ``u`` [rad]; ``MDOFResponse``: ``q``, ``joints``):
        see :class:`rockarch.Response`.

    Raises
    ------
    TypeError
        If ``sys_`` is not a system, ``motion`` not a GroundMotion, or ``ratio`` not one
        number.
    ValueError
        If ``ratio`` or ``p`` is out of range, a block has no p, ``check_step`` is given
        for a system that is not MDOF, or the history exceeds the work limits
        (docs/limits.md).

    Examples
    --------
    >>> import rockarch as ra
    >>> r = ra.simulate(ra.system("block", alpha=0.1), ra.pulse("sine", period=0.5),
    ...                 p=2.0, ratio=6.0)
    >>> r.overturned, round(r.t_overturn, 2)
    (True, 1.6)
    """
    check_system(sys_)
    check_motion(motion)
    kw = {}
    if isinstance(sys_, MDOFSystem):
        kw["check_step"] = check_step
    elif check_step:
        raise ValueError(f"check_step applies to mdof systems (their time-stepping engine), "
                         f"not to {sys_.name}")
    return sys_.simulate(motion, ratio=ratio, p=None if p is None else number("p", p), **kw)


def batch(sys_, motion: GroundMotion, p, ratio) -> Batch:
    """Verdicts of many simulations of one system on one motion, (p, ratio) broadcast.

    Each pair is one run as :func:`simulate` would do it (the motion scaled to
    ratio·ap,min, the structure at p), without the time histories; the runs go in
    parallel on numba threads.

    Parameters
    ----------
    sys_ : BlockSystem, MechanismSystem or MDOFSystem
        The structure, from :func:`system`.
    motion : GroundMotion
        The ground motion; only its shape matters.
    p : float or array-like
        Frequency parameters [1/s], each within [1e-3, 1e4].
    ratio : float or array-like
        Peak ground acceleration over ap,min [-], each in [0, 1e6]; broadcast with ``p`` by
        numpy's rules (e.g. ``p[:, None]`` and ``ratio`` for a grid).

    Returns
    -------
    Batch
        Arrays shaped like the broadcast (p, ratio): ``overturned`` (bool),
        ``t_overturn`` [s] (NaN where safe), ``max_rotation_ratio`` [-], ``impacts``, and
        ``extras`` (MDOF: ``open_joints_max``, ``lcp_failures``).

    Raises
    ------
    TypeError
        If ``sys_`` is not a system or ``motion`` not a GroundMotion.
    ValueError
        If p and ratio do not broadcast together, or a value is out of range.

    Examples
    --------
    >>> import numpy as np
    >>> import rockarch as ra
    >>> b = ra.batch(ra.system("block", alpha=0.1), ra.pulse("sine", period=0.5),
    ...              p=np.array([1.0, 2.0])[:, None], ratio=[1.0, 3.0, 6.0])
    >>> b.overturned.tolist()
    [[False, False, False], [False, False, True]]
    """
    check_system(sys_)
    check_motion(motion)
    return sys_.batch(motion, numbers("p", p), numbers("ratio", ratio))



__all__ = ["KINDS", "BlockSystem", "MDOFSystem", "MechanismSystem", "batch", "check_blocks",
           "check_motion", "check_system", "numbers", "scale_to_ratio", "simulate", "system"]
