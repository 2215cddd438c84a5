"""Constants and defaults shared by every module (SI units; docs/theory.md, Sect. 0).

One place for g and for the numerical defaults, so that the library, the CLI and the docs
agree. The names say which model a default belongs to: the SDOF rocking kernel (rigid
block, tabulated Lagrange mechanisms) integrates with RK4 and a step bound
``SDOF_H_FACTOR / p``; the MDOF Moreau–Jean engine steps with ``MDOF_H_FACTOR / p``.
"""

from __future__ import annotations

#: Acceleration of gravity used unless the caller passes another value [m/s²].
G = 9.81
#: Standard gravity, the unit "g" of records (PEER .AT2 files) [m/s²].
G_STANDARD = 9.80665

#: Free motion simulated after the ground motion ends, before "safe" is declared [s].
T_FREE = 10.0

#: SDOF kernel (rocking_kernels): RK4 step bound h_max = SDOF_H_FACTOR / p. The global
#: error of RK4 is O((p·h)^4); tests/test_block.py checks that halving it changes
#: overturning times by < 1e-6 s.
SDOF_H_FACTOR = 0.05
#: SDOF kernel: settling threshold of the chatter criterion (fraction of alpha or delta).
EPS_REST = 1e-6

#: MDOF engine (rockarch.mdof): time step h = MDOF_H_FACTOR / p. The convergence studies in
#: docs/mdof.md: halving it changes < 1 % of the cells of a pulse's OAS map; on records
#: 2-3 % of the cells of a map change with any halving of any step tried (chaotic cells on
#: the boundary), the same share as at finer steps.
MDOF_H_FACTOR = 0.005
#: MDOF engine: contact tolerance as a fraction of the thinnest joint.
GAP_TOL = 1e-4

#: Default bisection tolerance of an OAS boundary (ratio units).
OAS_TOL = 1e-3


def g_label(g: float) -> str:
    """Which g an acceleration shown in g was divided by.

    Parameters
    ----------
    g : float
        A structure's own g (default :data:`G`, docs/theory.md §0) or :data:`G_STANDARD`
        (records and hazard curves in units of g are converted with it).

    Returns
    -------
    str
        ``"g = 9.81 m/s²"``.
    """
    return f"g = {g:g} m/s²"


def standard_g(units: str) -> str:
    """:func:`g_label` of standard gravity where a file's units are g.

    Parameters
    ----------
    units : str
        Units as a hazard curve or a record writes them (``"g"``, ``"m/s2"``).

    Returns
    -------
    str
        ``"g = 9.80665 m/s²"`` for ``"g"``, else ``""``.
    """
    return g_label(G_STANDARD) if units.strip() == "g" else ""
