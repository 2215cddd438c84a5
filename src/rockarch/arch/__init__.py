"""Masonry arch statics: geometry, thrust-line limit analysis, the four-hinge mechanism.

Theory: docs/theory.md §4 (thrust line, limit analysis), §5 (four-hinge mechanism), §7
(replacement catenary arch).

Typical use (users' guide: docs/arch.md)::

    from rockarch.arch import catenary, analyse
    res = analyse(catenary(span=10.0, rise=3.0, thickness=0.25))
    res.ap_min, res.p, res.delta, res.hinges
"""

from rockarch.arch.cutting import Voussoirs, voussoirs
from rockarch.arch.fourhinge import (
    ArchMechanism,
    FourHinge,
    Kinematics,
    NoFourHingeMechanism,
    analyse,
    closure_limit,
    driving_moment,
    generalized_inertia,
    generalized_inertia_du,
    kinematics,
    mechanism_from_hinges,
    neutral_position,
    neutral_position_linear,
    potential,
    potential_du,
)
from rockarch.arch.funicular import mass_per_horizontal_length, weighted_catenary
from rockarch.arch.geometry import (
    CONTINUOUS_BLOCKS,
    SHAPES,
    Arch,
    catenary,
    circular,
    elliptical,
    from_contour,
    make_arch,
    pointed,
    polyline,
)
from rockarch.arch.shapes import catenary_parameter
from rockarch.arch.thrust import (
    Hinge,
    ThrustResult,
    is_admissible,
    limit_analysis,
    minimum_thickness,
)
from rockarch.arch.weights import HorizontalWeights, horizontal_weights

__all__ = [
    "CONTINUOUS_BLOCKS", "SHAPES", "Arch", "ArchMechanism", "FourHinge", "Hinge",
    "HorizontalWeights", "Kinematics", "NoFourHingeMechanism", "ThrustResult", "Voussoirs",
    "analyse", "catenary", "catenary_parameter", "circular", "closure_limit",
    "driving_moment", "elliptical", "from_contour", "generalized_inertia",
    "generalized_inertia_du", "horizontal_weights", "is_admissible", "kinematics",
    "limit_analysis", "make_arch", "mass_per_horizontal_length", "mechanism_from_hinges",
    "minimum_thickness", "neutral_position", "neutral_position_linear", "pointed", "polyline",
    "potential", "potential_du", "voussoirs", "weighted_catenary",
]
