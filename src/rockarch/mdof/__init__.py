"""Assemblies of rigid blocks: arches, columns, piers, bridges, walls, in motion and at rest.

Theory: docs/theory.md §6 (Moreau–Jean time stepping), §9 (Coulomb friction at the joints),
§10 (general contact graphs, limit analysis with friction).

Planar rigid blocks whose joints open, close and (with a friction coefficient) slide;
inelastic impacts; exact (second-order) kinematics. Moreau–Jean time stepping with an exact
contact solve per step (users' guides: docs/mdof.md, docs/assemblies.md)::

    import rockarch as ra
    from rockarch import mdof
    from rockarch.arch import catenary

    a = mdof.arch_assembly(catenary(10.0, 3.0, 0.25), 20)
    res = mdof.simulate(a, ra.pulse("sine", period=1.0, ap=1.2 * a.ap_min))
    res.to_dict()

General assemblies (any contact graph, Coulomb friction per joint)::

    b = mdof.bridge(catenary(10.0, 3.0, 0.25), 10, spans=2, pier_height=3, pier_width=1)
    w = mdof.wall(6, 5, 0.4, 0.2, mu=0.6)
    mdof.collapse(w).sliding          # the static collapse mechanism (limit analysis)
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
from rockarch.mdof.assembly_file import assembly_from_dict, read_assembly
from rockarch.mdof.builders import bridge, colonnade, from_polygons, wall, with_friction
from rockarch.mdof.simulate import (
    MDOFResponse,
    check_settings,
    simulate,
    simulate_batch,
)
from rockarch.mdof.statics import Collapse, collapse

__all__ = ["MIN_VOUSSOIRS", "Assembly", "Collapse", "MDOFResponse", "arch_assembly",
           "assembly_from_dict", "block_from_p_alpha", "bridge", "check_settings", "colonnade",
           "collapse", "column", "from_polygons", "read_assembly", "simulate", "simulate_batch",
           "single_block", "stack", "wall", "with_friction"]
