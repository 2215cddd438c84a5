"""MDOF structures as OAS systems (the protocol of :mod:`rockarch.spectra`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rockarch.block import T_FREE
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.simulate import GAP_TOL, H_FACTOR, _check_settings, simulate_batch
from rockarch.motion import GroundMotion


@dataclass(frozen=True)
class MDOFSystem:
    """An MDOF assembly of fixed shape for an OAS: p varies by scaling its size
    (p ∝ 1/sqrt(size)), ratio scales the motion's peak to ratio·ap_min.

    ``ap_min``/``p_ref`` default to the assembly's own (arch: N-voussoir LP and four-hinge
    mechanism); pass other values to put the map on another structure's axes (e.g. the
    critical optimal four-hinge mechanism's, for Hypotheses 2 and 3).
    """

    assembly: Assembly
    ap_min: float | None = None
    p_ref: float | None = None
    t_free: float = T_FREE
    h_factor: float = H_FACTOR
    gap_tol: float = GAP_TOL

    def __post_init__(self) -> None:
        _check_settings(self.t_free, self.h_factor, self.gap_tol)

    @property
    def name(self) -> str:
        return self.assembly.name

    def run(self, motion: GroundMotion, p: np.ndarray, ratio: np.ndarray):
        res = simulate_batch(self.assembly, motion, p, ratio, ap_min=self.ap_min,
                             p_ref=self.p_ref, t_free=self.t_free, h_factor=self.h_factor,
                             gap_tol=self.gap_tol)
        return res.overturned, res.max_theta_over_alpha

    def attrs(self) -> dict:
        a = self.assembly
        d = {"kind": "mdof", "assembly": a.kind, "blocks": a.n_blocks, "joints": a.n_joints,
             "ap_min": a.ap_min if self.ap_min is None else self.ap_min,
             "p_ref": a.p_ref if self.p_ref is None else self.p_ref,
             "ap_min_assembly": a.ap_min, "p_assembly": a.p_ref, "delta_ref": a.delta_ref,
             "size_ref": a.size, "g": a.g, "t_free": self.t_free, "h_factor": self.h_factor,
             "gap_tol": self.gap_tol}
        d.update({k: v for k, v in a.info.items() if isinstance(v, (int, float, str))})
        return d
