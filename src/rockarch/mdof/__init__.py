"""Multi-block (MDOF) rocking structures: arches and columns whose joints open and close.

Planar rigid blocks, contact only at the two corners of every joint (compression only),
no sliding, no damping during motion, inelastic impacts; exact (second-order) kinematics.
Moreau–Jean time stepping with an exact LCP solve per step (docs/mdof.md)::

    from rockarch.arch import catenary
    from rockarch import mdof, motion
    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20)
    res = mdof.simulate(a, motion.sine(1.2 * a.ap_min, 1.0))
    res.summary()
"""

from rockarch.mdof.assembly import (
    MIN_VOUSSOIRS,
    Assembly,
    arch_assembly,
    block_from_p_alpha,
    column,
    single_block,
    stack,
)
from rockarch.mdof.simulate import (
    GAP_TOL,
    H_FACTOR,
    MDOFBatch,
    MDOFResponse,
    simulate,
    simulate_batch,
)
from rockarch.mdof.spectra import MDOFSystem

__all__ = ["GAP_TOL", "H_FACTOR", "MIN_VOUSSOIRS", "Assembly", "MDOFBatch", "MDOFResponse",
           "MDOFSystem",
           "arch_assembly", "block_from_p_alpha", "column", "simulate", "simulate_batch",
           "single_block", "stack"]
