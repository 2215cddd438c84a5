"""pymunk (Chipmunk 2-D) as an independent engine for rockarch's assemblies (tests only).

The same blocks (mass, polar moment, outline) as pymunk bodies; the ground and every support
(joint with body -1: the support's own polygon where the assembly has it, else a block
behind the joint's face) as static shapes; the ground acceleration a_g(t) applied, in the ground's
frame, as a tilted gravity (-a_g(t), -g). Curved voussoirs (non-convex outlines) are split
into convex strips of one body. Friction: pymunk multiplies the two shapes' coefficients, so
every shape gets sqrt(mu) (no sliding: mu = NO_SLIP). A curved voussoir's contact outline
is its convex hull.

It is a qualitative oracle for time histories (its iterative solver and contact slop), a
close one for static collapse loads (docs/validation.md).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import ConvexHull

pymunk = __import__("pytest").importorskip("pymunk")

#: Corner rounding of the contact outlines, relative to the structure's size.
ROUND = 1e-4

#: Friction coefficient standing in for "no sliding" (no contact of these tests needs more).
NO_SLIP = 20.0


def _rounded(poly: np.ndarray, r: float) -> np.ndarray:
    """The convex hull of ``poly`` offset inwards by r: with pymunk's radius r it has the
    same outline with corners rounded by r (so that blocks touching along a face start
    apart by nothing, not interpenetrating at shared vertices). A curved voussoir's hull
    replaces the intrados arc by its chord: the joint faces, where contact happens, are
    exact; mass and inertia are the voussoir's own."""
    p = poly[ConvexHull(poly).vertices]  # counter-clockwise
    e = np.roll(p, -1, axis=0) - p
    n = np.stack([e[:, 1], -e[:, 0]], axis=1) / np.hypot(*e.T)[:, None]
    n_in = np.roll(n, 1, axis=0)  # normal of the edge ending at each vertex
    return p - r * (n_in + n) / (1.0 + np.sum(n_in * n, axis=1))[:, None]


def build(assembly, *, mu: float | None = None, dt: float = 2e-4, iterations: int = 60,
          ground: bool = False):
    """A pymunk Space holding ``assembly`` (its own friction unless ``mu`` is given);
    ``ground``: the ground plane y = 0 whether or not a block stands on it (a block that
    falls off a pedestal lands on it)."""
    a = assembly
    size = float(a.size)
    space = pymunk.Space()
    space.iterations = iterations
    space.collision_slop = 1e-5 * size
    space.collision_bias = pow(1.0 - 0.3, 60.0)
    mus = a.mu if mu is None else np.full(a.n_joints, mu)
    m = float(np.min(np.where(np.isfinite(mus), mus, NO_SLIP)))
    fr = math.sqrt(m)
    bodies = []
    for i in range(a.n_blocks):
        b = pymunk.Body(float(a.mass[i]), float(a.inertia[i]))
        b.position = tuple(a.centroid[i])
        bodies.append(b)
        space.add(b)
    for ip, poly in enumerate(a.polygons):
        i = a.body_of_polygon(ip)
        piece = _rounded(np.asarray(poly, float), ROUND * size) - a.centroid[i]
        s = pymunk.Poly(bodies[i], [tuple(v) for v in piece], radius=ROUND * size)
        s.friction = fr
        space.add(s)
    if ground or any(abs(a.corners[k, :, 1]).max() < 1e-9 * size for k in range(a.n_joints)
                     if min(a.body_a[k], a.body_b[k]) < 0):
        ground = pymunk.Poly(space.static_body, [(-100 * size, -size), (100 * size, -size),
                                                 (100 * size, 0.0), (-100 * size, 0.0)])
        ground.friction = fr
        space.add(ground)
    for poly in a.info.get("supports", ()):  # supports given as polygons: themselves
        s = pymunk.Poly(space.static_body,
                        [tuple(v) for v in _rounded(np.asarray(poly, float), ROUND * size)],
                        radius=ROUND * size)
        s.friction = fr
        space.add(s)
    for k in range(a.n_joints):  # else a static block behind every other ground face
        if (a.body_a[k] >= 0 and a.body_b[k] >= 0) or a.info.get("supports"):
            continue
        p0, p1 = a.corners[k]
        if abs(p0[1]) < 1e-9 * size and abs(p1[1]) < 1e-9 * size:
            continue
        n = a.normal[k] * (1.0 if a.body_a[k] < 0 else -1.0)  # into the structure
        t = p1 - p0
        depth = float(np.hypot(*t))
        quad = [p0 - 0.2 * t, p1 + 0.2 * t, p1 + 0.2 * t - depth * n, p0 - 0.2 * t - depth * n]
        s = pymunk.Poly(space.static_body, [tuple(v) for v in quad])
        s.friction = fr
        space.add(s)
    return space, bodies


def run(assembly, accel, t_end: float, *, mu: float | None = None, dt: float = 2e-4,
        iterations: int = 60):
    """Simulate ``accel(t)`` (ground acceleration, m/s²) for t_end s; return the largest
    displacement of any block's centroid and the largest |rotation| over the run."""
    space, bodies = build(assembly, mu=mu, dt=dt, iterations=iterations)
    g = assembly.g
    x0 = np.array([tuple(b.position) for b in bodies])
    disp, rot = 0.0, 0.0
    for k in range(int(round(t_end / dt))):
        space.gravity = (-accel(k * dt), -g)
        space.step(dt)
        if k % 20 == 0:
            x = np.array([tuple(b.position) for b in bodies])
            disp = max(disp, float(np.max(np.hypot(*(x - x0).T))))
            rot = max(rot, max(abs(b.angle) for b in bodies))
    return disp, rot


def final_state(assembly, accel, t_end: float, *, dt: float = 2e-4, iterations: int = 60):
    """Simulate ``accel(t)`` for t_end s on a space with the ground plane; return every
    block's final centroid and rotation, (nb, 3)."""
    space, bodies = build(assembly, dt=dt, iterations=iterations, ground=True)
    g = assembly.g
    for k in range(int(round(t_end / dt))):
        space.gravity = (-accel(k * dt), -g)
        space.step(dt)
    return np.array([(b.position[0], b.position[1], b.angle) for b in bodies])
