"""Bounds on the memory and the work of one simulation, known before the work starts.

Every time history is estimated before anything is allocated (docs/theory.md, Sect. 8):

- a ground motion holds at most :func:`max_samples` knots (a sampled pulse is refused
  above it: ``--cycles``, ``--period`` against the sampling of :mod:`rockarch.motion.signals`);
- a recorded SDOF history (:mod:`rockarch.rocking.block`,
  :mod:`rockarch.rocking.mechanism`) holds at most :func:`max_samples` samples: above it
  the history is *decimated* (every k-th sample is kept, k a power of 2); the integration,
  the verdict and the summary are unchanged;
- one SDOF simulation may take at most :func:`max_steps` RK4 steps (one per knot and per
  h_factor/p seconds of motion and free motion: an upper bound, since a block at rest
  takes none), one MDOF simulation at most :func:`max_mdof_steps` time steps (the MDOF
  engine runs to the end of the free motion); above it the command stops before any work
  with one line that names the limit and the environment variable that raises it.

The estimates are docs/theory.md Eqs. (8.4)–(8.7); the defaults keep every command below
~1 GB of memory (measured in docs/limits.md). Each limit can be raised (or lowered) with an
environment variable.
"""

from __future__ import annotations

import os

#: Largest number of knots of a ground motion and of samples of a recorded history
#: (8 bytes each per array: 5e6 samples are 40 MB per array).
MAX_SAMPLES = 5_000_000
#: Largest number of RK4 steps of one recorded SDOF simulation (estimated before the run;
#: 5e7 steps are 10-30 s of computing).
MAX_STEPS = 50_000_000
#: Largest number of Moreau–Jean steps of one MDOF simulation (minutes of computing).
MAX_MDOF_STEPS = 20_000_000
#: Largest size of a recorded MDOF history [bytes]; above it every k-th step is recorded.
MAX_HISTORY_BYTES = 400_000_000
#: Most records of one suite (read, or written by ``records synth``).
MAX_RECORDS = 10_000
#: Most samples of all the records of a suite held in memory together (16 bytes each:
#: 2e7 samples are 320 MB).
MAX_SUITE_SAMPLES = 20_000_000
#: Most blocks of an MDOF structure (its limit analysis and its contact dynamics grow
#: with the number of joints: a 200-block wall takes about a minute to build).
MAX_BLOCKS = 500
#: Most voussoirs of an arch's thrust-line LP (about 3.5 kB each: 1e5 are 350 MB).
MAX_VOUSSOIRS = 100_000

ENV = {"samples": "ROCKARCH_MAX_SAMPLES", "steps": "ROCKARCH_MAX_STEPS",
       "mdof_steps": "ROCKARCH_MAX_MDOF_STEPS", "records": "ROCKARCH_MAX_RECORDS",
       "suite_samples": "ROCKARCH_MAX_SUITE_SAMPLES", "blocks": "ROCKARCH_MAX_BLOCKS",
       "voussoirs": "ROCKARCH_MAX_VOUSSOIRS",
       "simulations": "ROCKARCH_MAX_SIMULATIONS"}  # rockarch.core.sweep.limits


def _limit(key: str, default: int) -> int:
    name = ENV[key]
    text = os.environ.get(name)
    if text is None or not text.strip():
        return default
    try:
        value = int(float(text))
    except ValueError:
        raise ValueError(f"{name} must be a positive integer, got {text!r}") from None
    if value < 1:
        raise ValueError(f"{name} must be a positive integer, got {text!r}")
    return value


def max_samples() -> int:
    """Largest number of motion knots / recorded samples (env ``ROCKARCH_MAX_SAMPLES``)."""
    return _limit("samples", MAX_SAMPLES)


def max_steps() -> int:
    """Largest number of RK4 steps of a recorded SDOF run (env ``ROCKARCH_MAX_STEPS``)."""
    return _limit("steps", MAX_STEPS)


def max_mdof_steps() -> int:
    """Largest number of MDOF time steps (env ``ROCKARCH_MAX_MDOF_STEPS``)."""
    return _limit("mdof_steps", MAX_MDOF_STEPS)


def max_records() -> int:
    """Largest number of records of a suite (env ``ROCKARCH_MAX_RECORDS``)."""
    return _limit("records", MAX_RECORDS)


def max_suite_samples() -> int:
    """Largest number of samples of a suite in memory (env ``ROCKARCH_MAX_SUITE_SAMPLES``)."""
    return _limit("suite_samples", MAX_SUITE_SAMPLES)


def max_blocks() -> int:
    """Largest number of blocks of an MDOF structure (env ``ROCKARCH_MAX_BLOCKS``)."""
    return _limit("blocks", MAX_BLOCKS)


def max_voussoirs() -> int:
    """Largest number of voussoirs of an arch's limit analysis (env
    ``ROCKARCH_MAX_VOUSSOIRS``)."""
    return _limit("voussoirs", MAX_VOUSSOIRS)


def check_count(what: str, n: int, key: str, hint: str) -> int:
    """``n`` (records, blocks, ...) if at most the limit of ``key``, else the one-line
    error of :func:`too_many`, before anything of that size is built."""
    limit = _limit(key, _DEFAULT[key])
    if n > limit:
        raise ValueError(f"{what} has {n:,} {_UNIT[key]}, above the limit of {limit:,} "
                         f"({ENV[key]}); {hint}, or raise {ENV[key]}")
    return n


def too_many(what: str, needed: float, key: str, limit: int, hint: str) -> ValueError:
    """The one-line error of a bound: what needs how much, the limit and how to raise it."""
    verb = "may need up to" if key == "steps" else "needs"
    return ValueError(f"{what} {verb} {needed:.3g} {_UNIT[key]}, above the limit of "
                      f"{limit:.3g} ({ENV[key]}); {hint}, or raise {ENV[key]}")


_UNIT = {"samples": "samples", "steps": "integration steps", "mdof_steps": "time steps",
         "records": "records", "suite_samples": "samples", "blocks": "blocks",
         "voussoirs": "voussoirs"}
_DEFAULT = {"samples": MAX_SAMPLES, "steps": MAX_STEPS, "mdof_steps": MAX_MDOF_STEPS,
            "records": MAX_RECORDS, "suite_samples": MAX_SUITE_SAMPLES, "blocks": MAX_BLOCKS,
            "voussoirs": MAX_VOUSSOIRS}
