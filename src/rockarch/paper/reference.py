"""The paper's reference values, in one place (tests, ``rockarch reproduce`` and examples).

Everything here is a number printed in the paper (Tables 1 and 2, Sects. 8 and 9), except
:data:`SECT8_BAND`, the lower-bound replacement construction of docs/theory.md Eqs.
(7.3)–(7.6) for the Sect. 8 arch (half-angle 60°, so f = 5·tan 30° = 2.8868 m), computed
independently of rockarch to three digits; the paper prints only d̄/l′ = 0.0207 and
f′ = 2.924 m of it.
"""

from __future__ import annotations

import math

#: Table 1: (f/l, d/l) -> (c1, c2, c3, c3', c4) of the critical optimal four-hinge mechanism
#: of catenary arches (paper Eq. 14; docs/theory.md Eq. 5.2).
TABLE1 = {
    (0.2, 0.0125): (0.219, 0.823, 0.24, 0.28, 0.34),
    (0.2, 0.025): (0.218, 0.829, 0.22, 0.30, 0.31),
    (0.2, 0.05): (0.229, 0.853, 0.18, 0.34, 0.25),
    (0.3, 0.0125): (0.270, 0.897, 0.26, 0.28, 0.40),
    (0.3, 0.025): (0.267, 0.899, 0.24, 0.29, 0.36),
    (0.3, 0.05): (0.263, 0.907, 0.22, 0.32, 0.34),
    (0.3, 0.1): (0.292, 0.944, 0.17, 0.38, 0.27),
    (0.4, 0.0125): (0.321, 0.983, 0.27, 0.29, 0.45),
    (0.4, 0.025): (0.318, 0.984, 0.26, 0.30, 0.43),
    (0.4, 0.05): (0.313, 0.988, 0.24, 0.31, 0.40),
    (0.4, 0.1): (0.296, 1.006, 0.20, 0.36, 0.34),
}

#: Sect. 8 circular arch (l = 10 m, f/l = 0.289, d/l = 0.0346 in the text, 0.0345 in Table 2).
SECT8 = {"span": 10.0, "rise": 2.89, "d_over_l": 0.0346, "ap_min": 3.036, "c1": 0.242,
         "c2": 0.768}

#: Table 2: the two replacement catenaries of the Sect. 8 arch. ``d/l`` is per l′ for the
#: lower bound (0.0207) and per the original's 10 m for the equivalent (0.0293): the paper
#: mixes the two (docs/validation.md).
TABLE2 = {
    "equivalent": {"d/l": 0.0293, "c1": 0.2473, "c2": 0.8914, "ap_min": 3.036, "R/l": 0.0536,
                   "p": 3.705, "rise": 2.924},
    "lower-bound": {"d/l": 0.0207, "c1": 0.2437, "c2": 0.8896, "ap_min": 2.163,
                    "R/l": 0.0528, "p": 11.82 / math.sqrt(10.0), "rise": 2.924},
}

#: Sect. 9 design example.
SECT9 = {"thickness": 0.35, "ratio": 1.351, "pga_safe": 4.102, "pga_safe_g": 0.418}

#: The lower-bound construction for the Sect. 8 arch (half-angle 60°, d = 0.345 m),
#: independent reference (module docstring): band thickness d̄, its span l′ and rise f′,
#: the axis parameters at the optimum, the springings' offset outward along the joints,
#: and the equivalent thickness with its p (paper: 0.293 m, 3.705 1/s; the −1.9 % in p is
#: the paper's own c1 offset).
SECT8_BAND = {"rise": 5.0 * math.tan(math.radians(30.0)), "thickness": 0.345,
              "d_bar": 0.2097, "span": 10.117, "band_rise": 2.921, "y0": 2.954, "a": 4.80,
              "springing_offset": 0.07, "d_equivalent": 0.292, "p_equivalent": 3.64}

#: c4 (Table 1's delta) against the paper: the largest relative deviation rockarch's exact
#: neutral configuration reaches, by d/l (docs/validation.md).
C4_DEVIATION = {0.0125: 0.025, 0.025: 0.056, 0.05: 0.097, 0.1: 0.115}
