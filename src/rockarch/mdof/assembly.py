"""Planar assemblies of rigid blocks for the MDOF model: arch, column, single block.

An :class:`Assembly` is a chain of nb rigid bodies and nj joints; joint k lies between body
k−1 and body k (body −1 and body nb are the ground). Each joint has two corner points
(corner 0, corner 1) and a normal pointing from body k−1 into body k. For an arch, corner 0
is the intrados and corner 1 the extrados; for a column, corner 0 is the left end.

Reference dynamic parameters travel with the assembly (the OAS axes):

* ``ap_min`` — the limit acceleration (arch: thrust-line LP of the N-voussoir arch;
  column: the smallest over its joints of g·(lever of the part above)/(its height));
* ``p_ref`` — frequency parameter at the assembly's size (arch: the N-voussoir four-hinge
  mechanism; column: the critical part rocking as one block about its corner);
* ``delta_ref`` — the neutral angle of that mechanism (normalises the reported rotation:
  for one block it is alpha, so ``max_theta_over_alpha`` means what it means for blocks).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from rockarch.arch import analyse, voussoirs
from rockarch.arch.fourhinge import NoFourHingeMechanism
from rockarch.core import limits
from rockarch.core.constants import G
from rockarch.core.validate import integer, positive, show
from rockarch.mdof.statics import collapse


@dataclass(frozen=True)
class Assembly:
    """A chain of rigid blocks between rigid supports (see the module docstring)."""

    name: str
    kind: str  # "arch" | "column" | "block"
    mass: np.ndarray  # (nb,)
    inertia: np.ndarray  # (nb,) polar moment about the centroid
    centroid: np.ndarray  # (nb, 2)
    corners: np.ndarray  # (nj, 2, 2) reference corner points of every joint
    normal: np.ndarray  # (nj, 2) unit normal, from body k-1 into body k
    polygons: tuple  # outlines of the original blocks (for plots)
    ap_min: float
    p_ref: float
    delta_ref: float
    size: float  # characteristic length (span or height) at which p_ref holds
    g: float = G
    info: dict = field(default_factory=dict)
    poly_body: tuple = ()  # body index of every polygon (default: one polygon per body)
    # The contact graph (docs/theory.md §10). Joint k joins body_a[k] (on the tail side of
    # normal[k]) to body_b[k] (the side the normal points into); -1 is the ground, or a
    # support moving with it. mu[k] is the joint's Coulomb friction coefficient (inf: no
    # sliding). None: the chain ground-0-1-...-(nb-1)[-ground] with no sliding.
    body_a: np.ndarray | None = None
    body_b: np.ndarray | None = None
    mu: np.ndarray | None = None

    def __repr__(self) -> str:
        """One line: the name, kind, block and joint counts, ap_min, the reference p and
        delta (and the least friction coefficient where joints slide), not the arrays the
        attributes hold."""
        nb_, nj = self.n_blocks, self.n_joints
        friction = "" if self.frictionless else f", friction {float(np.min(self.mu)):.4g}"
        return (f"Assembly({self.name!r}, {self.kind}: {nb_} block{'s' * (nb_ != 1)}, "
                f"{nj} joint{'s' * (nj != 1)}, ap_min {self.ap_min:.4g} m/s², "
                f"p {self.p_ref:.4g} 1/s, delta {self.delta_ref:.4g} rad{friction})")

    def __post_init__(self) -> None:
        nb_, nj = self.n_blocks, self.n_joints
        if self.body_a is None:
            object.__setattr__(self, "body_a", np.arange(nj) - 1)
        if self.body_b is None:
            object.__setattr__(self, "body_b", np.where(np.arange(nj) < nb_, np.arange(nj), -1))
        if self.mu is None:
            object.__setattr__(self, "mu", np.full(nj, np.inf))
        for name in ("body_a", "body_b"):
            object.__setattr__(self, name, np.asarray(getattr(self, name), dtype=np.int64))
        object.__setattr__(self, "mu", np.asarray(self.mu, dtype=float))

    @property
    def is_chain(self) -> bool:
        """True if joint k joins body k-1 to body k (the ends on the ground)."""
        k = np.arange(self.n_joints)
        return bool(np.array_equal(self.body_a, k - 1) and np.array_equal(
            self.body_b, np.where(k < self.n_blocks, k, -1)))

    @property
    def frictionless(self) -> bool:
        """True if no joint can slide (every mu is infinite)."""
        return bool(np.all(np.isinf(self.mu)))

    @property
    def slides(self) -> bool:
        """True if friction lowers ap_min below rocking's (``info["ap_min_no_sliding"]``):
        the collapse mechanism slides; p_ref and delta_ref stay rocking's."""
        return bool(self.ap_min < self.info.get("ap_min_no_sliding", self.ap_min) * (1 - 1e-9))

    def body_of_polygon(self, i: int) -> int:
        return int(self.poly_body[i]) if self.poly_body else i

    @property
    def n_blocks(self) -> int:
        return int(self.mass.shape[0])

    @property
    def n_joints(self) -> int:
        return int(self.normal.shape[0])

    @property
    def thickness(self) -> np.ndarray:
        """(nj,) joint lengths."""
        return np.hypot(*(self.corners[:, 1] - self.corners[:, 0]).T)

    def merged(self, keep, *, name: str | None = None) -> Assembly:
        """The same structure with only the joints ``keep`` able to open: the blocks between
        consecutive kept joints are glued into one rigid body (e.g. an arch whose only weak
        joints are its four hinges). Reference values (ap_min, p_ref, delta_ref) are kept."""
        keep = sorted({int(k) for k in keep})
        nb_, nj = self.n_blocks, self.n_joints
        if not keep or keep[0] != 0 or any(k < 0 or k >= nj for k in keep):
            raise ValueError(f"joints to keep must include joint 0 and lie in 0..{nj - 1}")
        if nj == nb_ + 1 and keep[-1] != nj - 1:
            raise ValueError(f"an arch must keep its last springing joint {nj - 1}")
        bounds = keep + [nb_] if nj == nb_ else keep  # column: the top block ends the chain
        mass, cen, ine, owner = [], [], [], np.zeros(nb_, dtype=int)
        for b, (k0, k1) in enumerate(zip(bounds[:-1], bounds[1:], strict=True)):
            idx = np.arange(k0, k1)
            m = self.mass[idx]
            mt = m.sum()
            c = (m[:, None] * self.centroid[idx]).sum(axis=0) / mt
            mass.append(mt)
            cen.append(c)
            ine.append(float(np.sum(self.inertia[idx] + m * np.sum((self.centroid[idx] - c) ** 2,
                                                                  axis=1))))
            owner[idx] = b
        pb = tuple(int(owner[self.body_of_polygon(i)]) for i in range(len(self.polygons)))
        return Assembly(name=name or f"{self.name} (joints {keep} only)", kind=self.kind,
                        mass=np.array(mass), inertia=np.array(ine), centroid=np.array(cen),
                        corners=self.corners[keep], normal=self.normal[keep],
                        polygons=self.polygons, ap_min=self.ap_min, p_ref=self.p_ref,
                        delta_ref=self.delta_ref, size=self.size, g=self.g,
                        info=dict(self.info, merged_joints=keep), poly_body=pb)

    def size_for(self, p: float) -> float:
        """Size (same shape) whose frequency parameter is p (p ∝ 1/sqrt(size))."""
        return self.size * (self.p_ref / p) ** 2


def _rect_props(x0, y0, w, h):
    m = w * h
    return m, np.array([x0 + w / 2, y0 + h / 2]), m * (w * w + h * h) / 12.0


def _rocking_part(mass, cen, inertia, corner, direction, g):
    """ap_min, p, delta of the rigid part (bodies given) rocking about ``corner``."""
    mt = mass.sum()
    c = (mass[:, None] * cen).sum(axis=0) / mt
    io = float(np.sum(inertia + mass * np.sum((cen - corner) ** 2, axis=1)))
    dx = direction * (c[0] - corner[0])  # lever towards the rocking direction
    dy = c[1] - corner[1]
    if dx <= 0 or dy <= 0:
        return math.inf, math.nan, math.nan
    r = math.hypot(dx, dy)
    return g * dx / dy, math.sqrt(mt * g * r / io), math.atan2(dx, dy)


def stack(rects, *, g: float = G, name: str | None = None) -> Assembly:
    """A column of rectangles (x_left, y_bottom, width, height), bottom to top, the first
    one on the ground (y_bottom = 0), each resting on the one below.

    Raises ValueError if blocks overlap, float, or do not share a contact face.
    """
    g = positive("g", g)
    r = np.asarray(rects, dtype=float)
    if r.ndim != 2 or r.shape[1] != 4 or r.shape[0] < 1:
        raise ValueError("a column needs a list of blocks (x_left, y_bottom, width, height)")
    if not np.all(np.isfinite(r)):
        raise ValueError("column block coordinates must be finite numbers")
    if np.any(r[:, 2] <= 0) or np.any(r[:, 3] <= 0):
        raise ValueError("column blocks need a width and a height > 0")
    if np.abs(r).max() > 1e5 or r[:, 3].sum() > 1e5:
        raise ValueError("column blocks must lie within 1e5 m (sizes in metres)")
    scale = float(r[:, 3].sum())
    tol = 1e-9 * scale
    if abs(r[0, 1]) > tol:
        raise ValueError(f"the first block must stand on the ground (y_bottom = 0), got "
                         f"{r[0, 1]:g}")
    nb_ = limits.check_count("a column", r.shape[0], "blocks", "use fewer blocks")
    mass, cen, ine, corners, polys = [], [], [], [], []
    for k in range(nb_):
        x0, y0, w, h = r[k]
        if k == 0:
            lo, hi, yj = x0, x0 + w, 0.0
        else:
            top = r[k - 1, 1] + r[k - 1, 3]
            if y0 < top - tol:
                raise ValueError(f"blocks {k - 1} and {k} overlap (block {k} starts at y = "
                                 f"{y0:g} below the top of block {k - 1}, y = {top:g})")
            if y0 > top + tol:
                raise ValueError(f"block {k} floats above block {k - 1} (gap {y0 - top:g})")
            lo = max(x0, r[k - 1, 0])
            hi = min(x0 + w, r[k - 1, 0] + r[k - 1, 2])
            yj = top
            if hi - lo <= 1e-6 * scale:
                raise ValueError(f"blocks {k - 1} and {k} do not share a contact face")
        m, c, i = _rect_props(x0, y0, w, h)
        mass.append(m)
        cen.append(c)
        ine.append(i)
        corners.append([[lo, yj], [hi, yj]])
        polys.append(np.array([[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]))
    mass, cen, ine = np.array(mass), np.array(cen), np.array(ine)
    corners = np.array(corners)
    best = (math.inf, math.nan, math.nan, -1)
    for k in range(nb_):
        for d, c in ((1, 0), (-1, 1)):
            am, p, dl = _rocking_part(mass[k:], cen[k:], ine[k:], corners[k, c], d, g)
            if am < best[0]:
                best = (am, p, dl, k)
    if not math.isfinite(best[0]):
        raise ValueError("the column cannot stand: a part's centre of mass lies outside its "
                         "support")
    kind = "block" if nb_ == 1 else "column"
    return Assembly(name=name or (f"{nb_}-block column" if nb_ > 1 else "block"), kind=kind,
                    mass=mass, inertia=ine, centroid=cen, corners=corners,
                    normal=np.tile([0.0, 1.0], (nb_, 1)), polygons=tuple(polys),
                    ap_min=best[0], p_ref=best[1], delta_ref=best[2], size=scale, g=g,
                    info={"critical_joint": best[3]})


def column(blocks, *, g: float = G, name: str | None = None) -> Assembly:
    """A column of blocks (width, height) or (width, height, x_centre), stacked bottom to
    top (x_centre defaults to 0: a centred stack)."""
    rects, y = [], 0.0
    for i, b in enumerate(blocks):
        b = tuple(b)
        if len(b) not in (2, 3):
            raise ValueError(f"column block {i}: give (width, height) or (width, height, "
                             f"x_centre), got {show(b)}")
        w = positive(f"width of block {i}", b[0])
        h = positive(f"height of block {i}", b[1])
        xc = float(b[2]) if len(b) == 3 else 0.0
        rects.append((xc - w / 2, y, w, h))
        y += h
    if not rects:
        raise ValueError("a column needs at least one block")
    return stack(rects, g=g, name=name)


def single_block(width: float, height: float, *, g: float = G) -> Assembly:
    """One rectangular block on the ground (Housner's block, docs/theory.md §1)."""
    return column([(width, height)], g=g, name=f"block B={width:g} H={height:g}")


def block_from_p_alpha(p: float, alpha: float, g: float = G) -> Assembly:
    """The block with frequency parameter p and slenderness alpha (R = 3g/(4p²))."""
    r = 3.0 * positive("g", g) / (4.0 * positive("p", p) ** 2)
    return single_block(2 * r * math.sin(alpha), 2 * r * math.cos(alpha), g=g)


#: Fewest voussoirs of an MDOF arch (four hinges need four parts... and joints to choose from).
MIN_VOUSSOIRS = 5


def arch_assembly(arch, n: int, *, g: float = G) -> Assembly:
    """The arch cut into ``n`` voussoirs (joints normal to the axis) between rigid supports.

    ap_min from the thrust-line LP of the n-voussoir arch; p_ref and delta_ref from its
    four-hinge (critical) mechanism. A ring too thick for a four-hinge mechanism (its
    thrust line at ap,min touches it at 3 or 5 points, or not on alternate faces) takes
    them from the general statics of its contact graph instead (docs/theory.md Eqs.
    (10.4)-(10.5b)), whatever its mechanism. Raises ValueError if n is too small or the
    arch cannot stand.
    """
    n = integer("number of voussoirs (blocks)", n)
    if n < MIN_VOUSSOIRS:
        raise ValueError(f"an MDOF arch needs at least {MIN_VOUSSOIRS} voussoirs, got {n}")
    limits.check_count(f"an MDOF arch of {n} voussoirs", n, "blocks", "use fewer voussoirs")
    v = voussoirs(arch, n)
    try:
        mech = analyse(arch, n, g=g)
    except NoFourHingeMechanism:
        mech = None
    except ValueError as exc:
        raise ValueError(f"{n} voussoirs: {exc}") from None
    if mech is not None and len({h.joint for h in mech.hinges}) < 4:
        raise ValueError(f"{n} voussoirs are too few for this arch: the four-hinge mechanism "
                         "needs four distinct joints")
    corners = np.stack([v.intrados, v.extrados], axis=1)
    label = f"{arch.shape} arch l={arch.span:g} f={arch.rise:g}"
    if arch.uniform_thickness:
        label += f" d={arch.uniform_thickness:g}"
    a = Assembly(
        name=f"MDOF {label} N={n}", kind="arch", mass=np.asarray(v.mass, float),
        inertia=np.asarray(v.inertia, float), centroid=np.asarray(v.centroid, float),
        corners=corners, normal=np.asarray(v.tangent, float), polygons=tuple(v.polygons()),
        ap_min=math.nan, p_ref=math.nan, delta_ref=math.nan, size=float(arch.span), g=g,
        info={"shape": arch.shape, "span": arch.span, "rise": arch.rise, "blocks": n})
    if mech is not None:
        return replace(a, ap_min=float(mech.ap_min), p_ref=float(mech.p),
                       delta_ref=float(mech.delta),
                       info={**a.info, "hinges": [h.joint for h in mech.hinges],
                             "hinge_sides": [h.side for h in mech.hinges]})
    c = collapse(a)
    return replace(a, ap_min=float(c.ap_min), p_ref=float(c.p), delta_ref=float(c.delta),
                   info={**a.info, "mechanism": "general (no four-hinge mechanism)",
                         "opening_joints": np.flatnonzero(c.opening.any(axis=1)).tolist()})
