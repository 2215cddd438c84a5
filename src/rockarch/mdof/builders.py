"""General assemblies: blocks on any contact graph (docs/theory.md §10).

Builders of :class:`~rockarch.mdof.assembly.Assembly` objects whose joints form any graph
(``body_a``/``body_b``, -1 = the ground or a support moving with it) with a Coulomb friction
coefficient per joint:

- :func:`from_polygons` — convex polygon blocks, contacts found from coincident faces
  (Eq. 10.1) or given as pairs;
- :func:`wall` — a wall in running bond;
- :func:`colonnade` — columns under a continuous lintel (two columns: a trilithon, the
  rocking frame of the SDOF model as blocks);
- :func:`bridge` — an arch (or K equal spans) on piers made of stacked blocks;
- :func:`with_friction` — any assembly (chain or general) with one friction coefficient.

Reference values of a general assembly (Eqs. 10.4–10.5): ``ap_min`` is the limit-analysis
collapse acceleration with friction (:mod:`rockarch.mdof.statics`); ``p_ref`` and
``delta_ref`` are the equivalent block of the no-sliding collapse mechanism (they set the time
step, the OAS p axis and the rotation ratio; sliding does not change them).
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import numpy as np

from rockarch.arch import Arch, voussoirs
from rockarch.core import limits
from rockarch.core.constants import G
from rockarch.core.validate import integer, positive
from rockarch.mdof import polygons as pg
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.statics import LAMBDA_CAP, collapse, limit_analysis

#: Largest friction coefficient accepted: above it the limit-analysis LP loses its accuracy
#: (μ = 1e10 gave an ap,min 6000 times too low), and no real joint comes near it.
MU_MAX = 1e6
#: Smallest friction coefficient accepted (ice on ice is ~0.02; below 1e-3 the collapse
#: acceleration μ·g underflows the motions scaled to it).
MU_MIN = 1e-3


def check_block_count(n: int, what: str = "the structure") -> int:
    """``n`` blocks if at most :func:`rockarch.core.limits.max_blocks`, else ValueError
    before anything is built (the limit analysis and the contact dynamics grow with the
    joints: a 400-block wall takes minutes to build)."""
    return limits.check_count(what, n, "blocks", "use fewer or larger blocks")


def friction_value(mu, name: str = "friction coefficient") -> float:
    """A friction coefficient: a finite number in [``MU_MIN``, ``MU_MAX``] (ValueError
    otherwise)."""
    mu = positive(name, mu)
    if mu < MU_MIN:
        raise ValueError(f"{name} must be at least {MU_MIN:g}, got {mu:g}")
    if mu > MU_MAX:
        raise ValueError(f"{name} must be at most {MU_MAX:g}, got {mu:g} (for joints that "
                         "never slide, give no friction)")
    return mu


def _graph_checks(nb_: int, body_a, body_b, names) -> None:
    """Every block touches something, and everything is connected to the ground."""
    touched = np.zeros(nb_, dtype=bool)
    adj = [[] for _ in range(nb_ + 1)]  # node nb_ = the ground
    for a, b in zip(body_a, body_b, strict=True):
        ia, ib = (nb_ if a < 0 else a), (nb_ if b < 0 else b)
        touched[[i for i in (a, b) if i >= 0]] = True
        adj[ia].append(ib)
        adj[ib].append(ia)
    if not touched.all():
        raise ValueError(f"{names[int(np.flatnonzero(~touched)[0])]} touches nothing (no "
                         "coincident face with another block, a support or the ground)")
    seen, todo = {nb_}, [nb_]
    while todo:
        for j in adj[todo.pop()]:
            if j not in seen:
                seen.add(j)
                todo.append(j)
    lost = [i for i in range(nb_) if i not in seen]
    if lost:
        raise ValueError(f"{names[lost[0]]} rests on nothing connected to the ground")


def assemble(*, name: str, kind: str, mass, inertia, centroid, polygons, joints, poly_body=(),
             mu=None, g: float = G, names=None, info=None) -> Assembly:
    """An :class:`Assembly` from bodies and joints, with its statics (Eqs. 10.2–10.5).

    ``joints``: list of (body_a, body_b, end0, end1, normal, mu_or_None); a joint's own
    friction wins over ``mu`` (one value for the structure; None: no sliding).
    """
    g = positive("g", g)
    mass = np.asarray(mass, float)
    nb_ = check_block_count(len(mass), name)
    names = list(names) if names is not None else [f"block {i}" for i in range(nb_)]
    body_a = np.array([j[0] for j in joints], dtype=np.int64)
    body_b = np.array([j[1] for j in joints], dtype=np.int64)
    _graph_checks(nb_, body_a, body_b, names)
    corners = np.array([[j[2], j[3]] for j in joints], dtype=float)
    normal = np.array([j[4] for j in joints], dtype=float)
    default = math.inf if mu is None else friction_value(mu)
    mus = np.array([default if j[5] is None else friction_value(j[5]) for j in joints])
    centroid = np.asarray(centroid, float)
    inertia = np.asarray(inertia, float)
    args = (mass, inertia, centroid, corners, normal, body_a, body_b)
    if np.all(np.isinf(mus)):
        fric = rock = limit_analysis(*args, mus, g=g, names=names)
    else:  # with and without sliding at once (HiGHS releases the GIL: two cores busy)
        with ThreadPoolExecutor(max_workers=2) as pool:
            fric, rock = pool.map(lambda m: limit_analysis(*args, m, g=g, names=names),
                                  (mus, None))
    # the reference mechanism (p_ref, delta_ref): the no-sliding one; if nothing can rock
    # without sliding (a block against a support), the friction one
    ref = rock if math.isfinite(rock.ap_min) else fric
    if not (math.isfinite(fric.ap_min) and math.isfinite(ref.p)):
        raise ValueError("the structure has no rocking mechanism below "
                         f"{LAMBDA_CAP:g} g: nothing can move")
    if fric.ap_min <= 1e-9 * g or ref.delta <= 1e-9:  # a centroid right above its pivot
        who = ", ".join(names[i] for i in np.flatnonzero(fric.moving)) or "a block"
        raise ValueError("the structure cannot stand under gravity with any margin: "
                         f"ap,min = 0 ({who} only just balances on a corner; neutral "
                         "equilibrium)")
    pts = np.concatenate([np.asarray(p, float) for p in polygons])
    size = float(np.ptp(pts, axis=0).max())
    moving = np.flatnonzero(fric.moving).tolist()
    return Assembly(name=name, kind=kind, mass=mass, inertia=inertia, centroid=centroid,
                    corners=corners, normal=normal, polygons=tuple(polygons),
                    ap_min=float(fric.ap_min), p_ref=float(ref.p),
                    delta_ref=float(ref.delta), size=size, g=g,
                    info={**(info or {}), "block_names": names, "mechanism_blocks": moving,
                          "ap_min_no_sliding": float(rock.ap_min),
                          "collapse_direction": int(fric.direction)},
                    poly_body=tuple(poly_body), body_a=body_a, body_b=body_b, mu=mus)


def _faces(polys, supports, tol, pairs=None):
    """Joints from coincident faces: (a, b, end0, end1, normal, None); supports are -1."""
    allp = list(polys) + list(supports)
    nb_ = len(polys)
    lo = np.array([p.min(axis=0) for p in allp])
    hi = np.array([p.max(axis=0) for p in allp])
    joints = []
    if pairs is None:
        near = np.all((lo[:, None] <= hi[None] + tol) & (lo[None] <= hi[:, None] + tol), axis=2)
        cand = [(i, j) for i in range(len(allp)) for j in range(i + 1, len(allp))
                if near[i, j] and i < nb_]
    else:
        cand = pairs
    for i, j in cand:
        f = pg.shared_face(allp[i], allp[j], tol)
        if f is None and pairs is not None:
            raise ValueError(f"contact {i}-{j}: the blocks share no face")
        if f is not None:
            joints.append((i, -1 if j >= nb_ else j, *f))
    return joints


def _check_overlaps(polys, supports, names, tol):
    allp = list(polys) + list(supports)
    nb_ = len(polys)
    label = names + [f"support {k}" for k in range(len(supports))]
    lo = np.array([p.min(axis=0) for p in allp])
    hi = np.array([p.max(axis=0) for p in allp])
    for i in range(len(allp)):  # supports too: one below the ground or two overlapping
        # gave a block a second joint on the same face (the ground's and the support's)
        if lo[i, 1] < -tol:
            raise ValueError(f"{label[i]} reaches below the ground (y = {lo[i, 1]:g} < 0)"
                             + ("; supports stand on the ground" if i >= nb_ else ""))
        for j in range(i + 1, len(allp)):
            if np.all(lo[i] < hi[j] - tol) and np.all(lo[j] < hi[i] - tol) \
                    and pg.overlap_depth(allp[i], allp[j]) > tol:
                raise ValueError(f"{label[i]} and {label[j]} overlap")


def from_polygons(polygons, *, density=1.0, mu=None, contacts=None, supports=(),
                  names=None, g: float = G, name: str = "assembly", kind: str = "assembly",
                  info=None) -> Assembly:
    """A general assembly of convex polygon blocks on the ground y = 0 (Eq. 10.1).

    Parameters
    ----------
    polygons : list of (K, 2) point lists
        Block outlines [m], convex, either orientation.
    density : float or list
        Mass per unit area (per unit depth); only ratios matter.
    mu : float or None
        Friction coefficient of every joint (None: no sliding).
    contacts : list of (i, j, mu_or_None), optional
        The contact pairs (j = -1: the block's faces on the ground and on the supports) with
        their own friction; default: every coincident face, each with ``mu``.
    supports : list of point lists
        Convex polygons fixed to the ground (they move with it).

    Raises
    ------
    ValueError
        Non-convex or self-intersecting polygons, overlapping blocks, a block touching
        nothing or not connected to the ground, a structure that cannot stand.
    """
    check_block_count(len(polygons), name)
    names = list(names) if names is not None else [f"block {i}" for i in
                                                    range(len(polygons))]
    polys = [pg.convex_polygon(p, names[i]) for i, p in enumerate(polygons)]
    sup = [pg.convex_polygon(p, f"support {k}") for k, p in enumerate(supports)]
    if not polys:
        raise ValueError("an assembly needs at least one block")
    nb_ = len(polys)
    dens = np.broadcast_to(np.asarray(density, float), (nb_,))
    for i, d in enumerate(dens):
        positive(f"density of {names[i]}", float(d))
    pts = np.concatenate(polys + sup)
    tol = pg.REL_TOL * float(np.ptp(pts, axis=0).max())
    _check_overlaps(polys, sup, names, tol)
    props = [pg.polygon_props(p) for p in polys]
    mass = np.array([d * a for d, (a, _, _) in zip(dens, props, strict=True)])
    inertia = np.array([d * j for d, (_, _, j) in zip(dens, props, strict=True)])
    centroid = np.array([c for _, c, _ in props])
    if contacts is None:
        joints = [(*j, None) for j in _faces(polys, sup, tol)]
        for i, p in enumerate(polys):
            f = pg.ground_face(p, tol)
            if f is not None:
                joints.append((-1, i, *f, None))
    else:
        joints, seen = [], set()
        for c in contacts:
            i, j, m = int(c[0]), int(c[1]), c[2]
            if (min(i, j), max(i, j)) in seen:
                raise ValueError(f"contact {i}-{j} is given twice (one joint per pair of "
                                 "faces)")
            seen.add((min(i, j), max(i, j)))
            for k in (i, j):
                if not -1 <= k < nb_:
                    raise ValueError(f"contact {i}-{j}: no block {k} (blocks 0..{nb_ - 1}, "
                                     "-1 the ground)")
            joints += _given_contact(polys, sup, i, j, m, tol)
    return assemble(name=name, kind=kind, mass=mass, inertia=inertia, centroid=centroid,
                    polygons=polys, joints=joints, mu=mu, g=g, names=names,
                    info={**(info or {}), "supports": tuple(sup)})


def _given_contact(polys, sup, i, j, m, tol) -> list:
    """The joints of a given contact pair; j = -1 (or i = -1): the block's faces on the
    ground and on every support it touches."""
    if i < 0:
        i, j = j, i
    if i < 0:
        raise ValueError("a contact needs at least one block")
    if j >= 0:
        f = pg.shared_face(polys[i], polys[j], tol)
        if f is None:
            raise ValueError(f"contact {i}-{j}: the blocks share no face")
        return [(i, j, *f, m)]
    faces = [pg.ground_face(polys[i], tol)] + [pg.shared_face(s, polys[i], tol) for s in sup]
    faces = [f for f in faces if f is not None]
    if not faces:
        raise ValueError(f"contact {i}-ground: block {i} has no face on the ground or a "
                         "support")
    return [(-1, i, *f, m) for f in faces]


def with_friction(assembly: Assembly, mu) -> Assembly:
    """The same assembly with every joint's friction coefficient ``mu`` and the
    friction-aware ``ap_min`` (Eq. 10.4; p_ref and delta_ref unchanged: rocking)."""
    mus = np.full(assembly.n_joints, friction_value(mu))
    a = replace(assembly, mu=mus)
    c = collapse(a)
    return replace(a, ap_min=float(min(c.ap_min, assembly.ap_min)),
                   info={**assembly.info, "friction": float(mu),
                         "ap_min_no_sliding": assembly.ap_min})


# --- structures ---------------------------------------------------------------------------

def _rect(x0, y0, w, h) -> np.ndarray:
    return np.array([[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]])


def wall(rows: int, columns: int, width: float, height: float, *, mu=None, g: float = G
         ) -> Assembly:
    """A wall in running bond: ``rows`` courses of ``columns`` blocks width × height [m];
    every second course is offset by half a block, with half blocks at both ends."""
    rows, columns = _count("wall rows", rows, 1), _count("wall columns", columns, 1)
    # every second course has a half block at each end: one block more
    check_block_count(rows * columns + rows // 2, f"a wall of {rows} x {columns} blocks")
    w, h = positive("block width", width), positive("block height", height)
    polys, names = [], []
    for r in range(rows):
        xs = [0.0] + ([w / 2] if r % 2 else []) + [
            (k + (0.5 if r % 2 else 0)) * w for k in range(1, columns)] + [columns * w]
        xs = sorted(set(np.round(xs, 12)))
        for k, (x0, x1) in enumerate(zip(xs[:-1], xs[1:], strict=True)):
            polys.append(_rect(x0, r * h, x1 - x0, h))
            names.append(f"block {len(names)} (course {r + 1}, unit {k + 1})")
    return from_polygons(polys, mu=mu, g=g, names=names, kind="wall",
                         name=f"wall {rows}x{columns} blocks {w:g}x{h:g} m",
                         info={"rows": rows, "columns": columns})


def colonnade(n_columns: int, width: float, height: float, spacing: float,
              lintel_depth: float, *, drums: int = 1, mu=None, g: float = G) -> Assembly:
    """``n_columns`` columns width × height [m] (each of ``drums`` equal drums), clear
    ``spacing`` apart, under one lintel of depth ``lintel_depth`` spanning all of them (two
    columns: a trilithon)."""
    n = _count("columns of a colonnade", n_columns, 2)
    drums = _count("drums per column", drums, 1)
    check_block_count(n * drums + 1, f"a colonnade of {n} columns")
    b, hc = positive("column width", width), positive("column height", height)
    s, d = positive("column spacing", spacing), positive("lintel depth", lintel_depth)
    polys, names = [], []
    for c in range(n):
        x0 = c * (b + s)
        for k in range(drums):
            polys.append(_rect(x0, k * hc / drums, b, hc / drums))
            names.append(f"column {c + 1}" + (f" drum {k + 1}" if drums > 1 else ""))
    polys.append(_rect(0.0, hc, n * b + (n - 1) * s, d))
    names.append("lintel")
    kind = "trilithon" if n == 2 else "colonnade"
    return from_polygons(polys, mu=mu, g=g, names=names, kind=kind,
                         name=f"{kind}: {n} columns {b:g}x{hc:g} m"
                              + (f" of {drums} drums" if drums > 1 else "")
                              + f", spacing {s:g} m, lintel {d:g} m",
                         info={"columns": n, "drums": drums})


def _count(name: str, value, least: int) -> int:
    v = integer(name, value)
    if v < least:
        raise ValueError(f"{name} must be an integer >= {least}, got {v}")
    return v


def _springer(xl, xr, y0, tops) -> np.ndarray:
    """The top block of a pier: its base [xl, xr] at y0, its top through the springing
    points ``tops`` (listed right to left)."""
    return np.array([[xl, y0], [xr, y0], *tops])


def bridge(arch: Arch, n_voussoirs: int, *, spans: int = 1, pier_height: float,
           pier_width: float, pier_blocks: int | None = None, abutments: bool | None = None,
           mu=None, g: float = G) -> Assembly:
    """``spans`` equal arches of ``n_voussoirs`` voussoirs on piers (docs/theory.md §10).

    Every pier is a stack of ``pier_blocks`` blocks (default: about square) of width
    ``pier_width``, from the ground to the intrados springing at ``pier_height``; its top
    block (the springer) carries the springing joint(s). An inner pier spans the clear
    distance ``pier_width`` between the intrados springings of its two arches; an end pier is
    flush with the intrados at its springing. ``abutments``: the two end springings rest on
    rigid abutments moving with the ground instead of end piers (default: True for
    ``spans`` >= 2, a bridge between abutments; False for one span, an arch on two piers).
    """
    spans = _count("--spans", spans, 1)
    abut = spans > 1 if abutments is None else bool(abutments)
    if abut and spans == 1:  # the piers' sizes would be ignored, yet named in the title
        raise ValueError("one span between abutments has no pier: give the arch alone "
                         "(without --spans, --pier-height, --pier-width, --abutments), or "
                         "--spans 2 or more")
    hp, bp = positive("--pier-height", pier_height), positive("--pier-width", pier_width)
    n_piers = spans + 1 - 2 * abut
    per_pier = _count("pier blocks", pier_blocks, 1) if pier_blocks is not None else \
        max(1, round(min(hp / bp, 1e12)))
    check_block_count(spans * _count("voussoirs", n_voussoirs, 1) + n_piers * per_pier,
                      f"a bridge of {spans} span(s)")
    v = voussoirs(arch, n_voussoirs)
    n = v.n
    ip, ep = v.intrados, v.extrados
    dy = hp - ip[0, 1]
    reach = ip[0, 0] - ep[0, 0]  # horizontal thickness of the springing joint
    if ep[0, 1] < ip[0, 1] or reach < 0:
        raise ValueError("this arch's springing joint does not face up and outwards: it "
                         "cannot rest on a pier top")
    need = 2 * reach if spans > 1 else (0.0 if abut else reach)
    if bp < need * (1 + 1e-9):
        raise ValueError(f"--pier-width must exceed {need:.4g} m (the springing joint's "
                         f"horizontal extent{' on both sides' if spans > 1 else ''})")
    clear = ip[-1, 0] - ip[0, 0]
    nc = _count("pier blocks", pier_blocks, 1) if pier_blocks is not None else \
        max(1, round(hp / bp))
    hc = hp / nc
    polys, names, mass, inertia, cen, pb, joints = [], [], [], [], [], [], []

    def add(poly, label, pbody=None):
        a, c, j = pg.polygon_props(poly)
        mass.append(a)
        inertia.append(j)
        cen.append(c)
        names.append(label)
        polys.append(poly)
        pb.append(len(mass) - 1 if pbody is None else pbody)
        return len(mass) - 1

    offsets = [k * (clear + bp) - ip[0, 0] for k in range(spans)]  # x shift of every span
    springers = []
    for k in range(spans + 1):
        if abut and k in (0, spans):
            springers.append(-1)
            continue
        left = offsets[k - 1] + ip[-1, 0] if k > 0 else offsets[0] + ip[0, 0] - bp
        right = left + bp
        tops = []
        if k < spans:  # left springing of span k (pier's right side)
            tops += [ip[0] + (offsets[k], dy), ep[0] + (offsets[k], dy)]
        if k > 0:  # right springing of span k-1 (pier's left side)
            tops += [ep[-1] + (offsets[k - 1], dy), ip[-1] + (offsets[k - 1], dy)]
        if k == 0:
            tops.append([left, tops[-1][1]])
        if k == spans:
            tops.insert(0, [right, tops[0][1]])
        below = -1
        for c in range(nc - 1):
            i = add(_rect(left, c * hc, bp, hc), f"pier {k + 1} block {c + 1}")
            joints.append((below, i, [left, c * hc], [right, c * hc], [0.0, 1.0], None))
            below = i
        s = add(pg.convex_polygon(_springer(left, right, hp - hc, tops), f"pier {k + 1}"),
                f"pier {k + 1} springer")
        joints.append((below, s, [left, hp - hc], [right, hp - hc], [0.0, 1.0], None))
        springers.append(s)
    vpolys = v.polygons()
    for k in range(spans):
        sh = np.array([offsets[k], dy])
        first = len(mass)
        for b in range(n):
            add(vpolys[b] + sh, f"span {k + 1} voussoir {b + 1}")
            inertia[-1], mass[-1], cen[-1] = v.inertia[b], v.mass[b], v.centroid[b] + sh
        for j in range(n + 1):
            a = springers[k] if j == 0 else first + j - 1
            b = springers[k + 1] if j == n else first + j
            joints.append((a, b, ip[j] + sh, ep[j] + sh, v.tangent[j], None))
    # the abutments as supports (drawn, and struck by a block that reaches them): from the
    # springing joint down to the ground and a pier's width outwards
    sup = []
    if abut:
        left, right = ip[0] + (offsets[0], dy), ep[-1] + (offsets[-1], dy)
        top_l, top_r = ep[0] + (offsets[0], dy), ip[-1] + (offsets[-1], dy)
        sup = [pg.convex_polygon([left, [left[0], 0.0], [top_l[0] - bp, 0.0],
                                  [top_l[0] - bp, top_l[1]], top_l], "left abutment"),
               pg.convex_polygon([top_r, [top_r[0], 0.0], [right[0] + bp, 0.0],
                                  [right[0] + bp, right[1]], right], "right abutment")]
    what = (f"{spans}-span arch bridge" if spans > 1 else "arch") + \
        (" between abutments" if abut else " on piers")
    label = f"{arch.shape} l={arch.span:g} f={arch.rise:g}"
    return assemble(name=f"{what}: {label} N={n}, piers {hp:g}x{bp:g} m", kind="bridge",
                    mass=mass, inertia=inertia, centroid=cen, polygons=polys,
                    joints=joints, poly_body=pb, mu=mu, g=g, names=names,
                    info={"spans": spans, "blocks": n, "pier_height": hp,
                          "pier_width": bp, "pier_blocks": nc, "shape": arch.shape,
                          "abutments": int(abut), "supports": tuple(sup)})
