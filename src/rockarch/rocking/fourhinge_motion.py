"""The four-hinge arch in motion: an SDOF rocking mechanism with exact linkage kinematics.

Side + is the critical (optimal) four-hinge mechanism for a ground acceleration to the right
(``analyse(arch, direction=+1)``), side − the one for the opposite acceleration. For a
symmetric arch side − is the mirror image of side + with the mirrored coordinate (identical
tables, mirrored response); otherwise it is found by the limit analysis with the opposite
load and its coordinate is the rotation of its own left part (the linkage's own; the
scalars of ``analyse(arch, direction=-1)`` are on its part 3, docs/theory.md Eq. 5.6). On each
side the tables of A(u), A'(u), V'(u) and the driving moment Q(u) come from the exact
kinematics of :mod:`rockarch.arch.fourhinge` (docs/theory.md §3 and §5); the motion
itself is integrated by :mod:`rockarch.rocking.mechanism`.

Impact law (docs/theory.md §5): when u returns to 0 the closing mechanism's velocity
field J_old (every voussoir's velocity and spin per unit rate of u) is projected onto the
opening mechanism's J_new in the kinetic-energy metric: u_new' = e·|u_old'| with
e = −(J_newᵀ M J_old)/(J_newᵀ M J_new), summed over all voussoirs (those outside the hinges
do not move). For a block this is Housner's r; for arches the loss shrinks with
slenderness. ``restitution=`` overrides it.
"""

from __future__ import annotations

import numpy as np

from rockarch.arch.fourhinge import (
    ArchMechanism,
    analyse,
    driving_moment,
    generalized_inertia,
    generalized_inertia_du,
    kinematics,
    potential_du,
)
from rockarch.arch.geometry import Arch
from rockarch.core.constants import G
from rockarch.rocking.mechanism import TABLE_INTERVALS, SDOFMechanism, tabulate


def velocity_field(res: ArchMechanism) -> tuple[np.ndarray, np.ndarray]:
    """Velocity (N, 2) and spin (N,) of every voussoir per unit rate of u at u = 0."""
    mech = res.mechanism
    vs = res.thrust.voussoirs
    k = kinematics(mech, 0.0)
    vel = np.zeros((vs.n, 2))
    spin = np.zeros(vs.n)
    for j in range(3):
        a, b = mech.joints[j], mech.joints[j + 1]
        rel = vs.centroid[a:b] - mech.centroid[j]
        w = float(k.dphi[j, 0])
        vel[a:b, 0] = float(k.dx[j, 0]) - w * rel[:, 1]
        vel[a:b, 1] = float(k.dy[j, 0]) + w * rel[:, 0]
        spin[a:b] = w
    return vel, spin


def impact_coefficient(closing: ArchMechanism, opening: ArchMechanism) -> float:
    """e = −(J_newᵀ M J_old)/(J_newᵀ M J_new) (docs/theory.md Eq. 5.3), at least 0.

    e is expressed in the two sides' own coordinates (the rotation of each mechanism's left
    part), so it may exceed 1 when the new coordinate turns faster for the same motion; the
    kinetic energy ratio (J_newᵀ M J_old)²/(A_old·A_new) never exceeds 1 (Cauchy–Schwarz).
    A negative projection (a squat mechanism whose new side would close at once) stops the
    motion: e = 0 (the closed-form laws of the block, frame and sdof are refused where they
    turn negative, :class:`rockarch.rocking.mechanism.SDOFMechanism`).
    """
    vs = closing.thrust.voussoirs
    if opening.thrust.voussoirs.n != vs.n:
        raise ValueError("the two mechanisms must come from the same voussoirs")
    v1, w1 = velocity_field(closing)
    v2, w2 = velocity_field(opening)
    m, inertia = vs.mass, vs.inertia
    cross = np.sum(m * np.sum(v1 * v2, axis=1) + inertia * w1 * w2)
    norm = np.sum(m * np.sum(v2 * v2, axis=1) + inertia * w2 * w2)
    return max(float(-cross / norm), 0.0)


def _is_symmetric(res: ArchMechanism, rtol: float = 1e-9) -> bool:
    """True if the voussoirs are mirror-symmetric about the mid-span vertical."""
    vs = res.thrust.voussoirs
    c = vs.centroid
    xm = 0.5 * (vs.points[0, 0] + vs.points[-1, 0])
    scale = float(np.ptp(vs.points[:, 0])) or 1.0
    mirrored = np.column_stack([2 * xm - c[::-1, 0], c[::-1, 1]])
    return bool(np.allclose(mirrored, c, rtol=0, atol=rtol * scale)
                and np.allclose(vs.mass[::-1], vs.mass, rtol=1e-7)
                and np.allclose(vs.inertia[::-1], vs.inertia, rtol=1e-7))


def mirror_impact_coefficient(res: ArchMechanism) -> float:
    """e for a symmetric arch: the opening mechanism is the mirror image of the closing one,
    with the mirrored coordinate: J_new(k) = mirror of J_old(N−1−k) (docs/theory.md §5)."""
    vs = res.thrust.voussoirs
    v1, w1 = velocity_field(res)
    v2 = np.column_stack([-v1[::-1, 0], v1[::-1, 1]])
    w2 = -w1[::-1]
    m, inertia = vs.mass, vs.inertia
    cross = np.sum(m * np.sum(v1 * v2, axis=1) + inertia * w1 * w2)
    norm = np.sum(m * np.sum(v1 * v1, axis=1) + inertia * w1 * w1)
    return max(float(-cross / norm), 0.0)


def _side_tables(res: ArchMechanism, e_close: float, n: int):
    mech = res.mechanism
    # on the linkage's own coordinate, its left part's rotation (side −'s reported delta is
    # on its part 3, the mirror of side +'s coordinate: docs/theory.md Eq. 5.6)
    return tabulate(res.delta_linkage, lambda q: generalized_inertia(mech, q),
                    lambda q: generalized_inertia_du(mech, q),
                    lambda q: potential_du(mech, q), lambda q: driving_moment(mech, q),
                    e_close, n=n)


def fourhinge_mechanism(arch: Arch, blocks: int | None = None, *, g: float = G,
                        restitution: float | None = None, name: str | None = None,
                        n: int = TABLE_INTERVALS) -> SDOFMechanism:
    """The arch's four-hinge mechanism in both directions, ready to simulate (docs/theory.md §5).

    ``blocks=None``: the critical optimal mechanism (hinges at the maximum eccentricities of
    the continuous arch); ``blocks=N``: the critical mechanism of the N-voussoir arch.
    The reference size is the arch's span; p ∝ 1/sqrt(span) at fixed shape.
    """
    label = name or (f"{arch.shape} arch l={arch.span:g} f={arch.rise:g}"
                     + (f" d={arch.uniform_thickness:g}" if arch.uniform_thickness else ""))
    try:
        plus = analyse(arch, blocks, g=g, direction=1)
        symmetric = _is_symmetric(plus)
        if symmetric:  # side − is the mirror image of side +, in the mirrored coordinate
            side_p = _side_tables(plus, mirror_impact_coefficient(plus), n)
            side_m = side_p
        else:  # the LP with the opposite load; each side's coordinate: its left part
            minus = analyse(arch, blocks, g=g, direction=-1)
            side_p = _side_tables(plus, impact_coefficient(plus, minus), n)
            side_m = _side_tables(minus, impact_coefficient(minus, plus), n)
    except ValueError as exc:
        why = str(exc).removeprefix("no four-hinge mechanism: ")
        raise ValueError(f"{label}: no four-hinge mechanism: {why}") from None
    info = {"kind": "fourhinge", "shape": arch.shape, "span": arch.span, "rise": arch.rise,
            "blocks": -1 if blocks is None else int(blocks), "c1": plus.c1, "c2": plus.c2,
            "ap_min_lp": plus.ap_min, "symmetric": int(symmetric)}
    if arch.uniform_thickness:
        info["thickness"] = arch.uniform_thickness
    return SDOFMechanism(f"four-hinge {label}", side_p, side_m, g, arch.span, restitution,
                         info)
