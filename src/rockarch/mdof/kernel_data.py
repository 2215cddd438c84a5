"""Typed inputs of the MDOF kernels, built from an :class:`~rockarch.mdof.assembly.Assembly`.

The kernels take one small named tuple (numba passes it as a record) instead of a long
positional argument list: :func:`chain_model` for the banded chain stepper,
:func:`graph_model` for the general contact-graph stepper with friction.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rockarch.mdof.assembly import Assembly


class ChainModel(NamedTuple):
    """A chain assembly for :mod:`rockarch.mdof.chain_stepper` (unit scale)."""

    mass: np.ndarray  # (nb,)
    inertia: np.ndarray  # (nb,) about the centroid
    c0: np.ndarray  # (nb, 2) reference centroids
    rl: np.ndarray  # (nj, 2, 2) corners relative to the left/lower body (absolute: ground)
    rr: np.ndarray  # (nj, 2, 2) corners relative to the right/upper body
    n0: np.ndarray  # (nj, 2) reference normals
    thick_min: float  # thinnest joint (contact tolerance scale)
    delta_ref: float  # reference rotation of max_rotation_ratio
    g: float


def _f(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=float)


def chain_model(assembly: Assembly) -> ChainModel:
    """The chain stepper's input (joint k between body k−1 and body k)."""
    nb_, nj = assembly.n_blocks, assembly.n_joints
    rl = np.empty((nj, 2, 2))
    rr = np.empty((nj, 2, 2))
    for k in range(nj):
        rl[k] = assembly.corners[k] - (assembly.centroid[k - 1] if k >= 1 else 0.0)
        rr[k] = assembly.corners[k] - (assembly.centroid[k] if k < nb_ else 0.0)
    return ChainModel(_f(assembly.mass), _f(assembly.inertia), _f(assembly.centroid), rl, rr,
                      _f(assembly.normal), float(assembly.thickness.min()),
                      float(assembly.delta_ref), float(assembly.g))


class GraphModel(NamedTuple):
    """Any assembly for :mod:`rockarch.mdof.graph_stepper` (unit scale)."""

    mass: np.ndarray  # (nb,)
    inertia: np.ndarray  # (nb,)
    c0: np.ndarray  # (nb, 2)
    ba: np.ndarray  # (nj,) body on the tail side of the normal (-1: ground)
    bb: np.ndarray  # (nj,) body the normal points into (-1: ground)
    ra: np.ndarray  # (nj, 2, 2) corners relative to body a (absolute for the ground)
    rb: np.ndarray  # (nj, 2, 2) corners relative to body b (absolute for the ground)
    n0: np.ndarray  # (nj, 2) reference normals (turn with body a)
    mu: np.ndarray  # (nj,) friction coefficients (inf: no sliding)
    chain: bool  # joint k joins body k-1 to body k: banded exact contact solve
    thick_min: float
    delta_ref: float
    g: float


def graph_model(assembly: Assembly) -> GraphModel:
    """The general stepper's input: the contact graph (body_a, body_b) and mu per joint."""
    ba = np.ascontiguousarray(assembly.body_a, dtype=np.int64)
    bb = np.ascontiguousarray(assembly.body_b, dtype=np.int64)
    cen = np.asarray(assembly.centroid, dtype=float)
    corners = np.asarray(assembly.corners, dtype=float)

    def rel(bodies):
        return np.ascontiguousarray(corners - np.where(bodies[:, None, None] >= 0,
                                                       cen[bodies][:, None, :], 0.0))

    return GraphModel(_f(assembly.mass), _f(assembly.inertia), _f(cen), ba, bb, rel(ba),
                      rel(bb), _f(assembly.normal), _f(assembly.mu), assembly.is_chain,
                      float(assembly.thickness.min()), float(assembly.delta_ref),
                      float(assembly.g))
