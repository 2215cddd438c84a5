"""Size limits of a sweep, checked before anything is allocated (docs/sweeps.md, "Limits").

An OAS holds, while it is computed, about 50 bytes per simulation (the boolean map, the
float64 response map, the chunks' p and ratio grids and their results), so
:data:`MAX_SIMULATIONS` keeps one command below ~0.5 GB of arrays; a larger study is split
into several commands (e.g. by p range), which the store makes free to resume and combine.
"""

from __future__ import annotations

from rockarch.core.limits import ENV, _limit

#: Most simulations (grid cells, summed over the records of a site) of one sweep, unless
#: the environment variable ROCKARCH_MAX_SIMULATIONS says otherwise.
MAX_SIMULATIONS = 10_000_000
#: Most values on one axis of a grid (--p-steps, --ratio-steps).
MAX_STEPS = 100_000
#: Bytes held per simulation while an OAS is computed (an upper estimate, see above).
BYTES_PER_SIMULATION = 50


def check_steps(option: str, n: int) -> int:
    """``n`` values on one grid axis, if 1 <= n <= :data:`MAX_STEPS`; else ValueError."""
    if n > MAX_STEPS:
        raise ValueError(f"{option} {n} is above the limit of {MAX_STEPS} values per axis "
                         f"(docs/sweeps.md, Limits)")
    return n


def max_simulations() -> int:
    """:data:`MAX_SIMULATIONS`, or the value of ``$ROCKARCH_MAX_SIMULATIONS``."""
    return _limit("simulations", MAX_SIMULATIONS)


def check_simulations(n: int, what: str) -> int:
    """A sweep of ``n`` simulations (``what`` says how they arise), if ``n`` <=
    :func:`max_simulations`; else ValueError naming the limit and what to do."""
    limit = max_simulations()
    if n > limit:
        gb = n * BYTES_PER_SIMULATION / 1e9
        raise ValueError(f"the sweep has {what} = {n:,} simulations (~{gb:.3g} GB), above "
                         f"the limit of {limit:,} per command: use fewer --p-steps/"
                         "--ratio-steps, split the p range over several commands, or "
                         f"raise {ENV['simulations']}")
    return n
