"""Multi-block (MDOF) rocking structures: arches and columns whose joints open and close.

Planar rigid blocks, contact only at the two corners of every joint (compression only),
no sliding, no damping during motion, inelastic impacts; exact (second-order) kinematics.
Moreau–Jean time stepping with an exact LCP solve per step (docs/mdof.md)::

    from rockarch.arch import catenary
    from rockarch import mdof, motion
    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20)
    res = mdof.simulate(a, motion.sine(1.2 * a.ap_min, 1.0))
    res.to_dict()
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
    MDOFResponse,
    check_settings,
    simulate,
    simulate_batch,
)

__all__ = ["MIN_VOUSSOIRS", "Assembly", "MDOFResponse", "arch_assembly", "block_from_p_alpha",
           "check_settings", "column", "simulate", "simulate_batch", "single_block", "stack"]
