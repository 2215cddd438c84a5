"""Move every ground motion in its last bit, as another machine would (``make test-perturbed``).

With ``ROCKARCH_PERTURB`` set (to anything but ``0``), every :class:`GroundMotion` built in
this process has the lowest mantissa bit of each non-zero sample set: a change of at most one
unit in the last place, of the size by which other SIMD paths or other builds of numpy and
numba move a result. A test that pins a number beyond its physical tolerance, or a chaotic
count, fails here, on the developer's machine, before it fails on a user's.

The change is chosen so that the invariances the tests rely on still hold exactly: it is odd
(``f(-a) = -f(a)``: mirrored motions stay mirrored), idempotent (a motion rebuilt from a
perturbed one, in this process or in a worker, is the same), it keeps zeros and commutes with
scaling by powers of two. ``tests/perturb/sitecustomize.py`` installs it in every Python
process the tests start (CLI runs, process-pool workers, the docs' scripts), so that a result
computed in a worker is the one computed in the test.

A test of an exact construction (a square pulse is exactly its amplitude) opts out with
``@pytest.mark.unperturbed``.
"""

from __future__ import annotations

import os

import numpy as np

#: Whether the perturbation applies now (the unperturbed marker turns it off for one test).
ENABLED = os.environ.get("ROCKARCH_PERTURB", "0") not in ("", "0")


def last_bit(a: np.ndarray) -> np.ndarray:
    """``a`` with the lowest mantissa bit of each non-zero float64 set (a copy)."""
    out = np.array(a, dtype=np.float64, copy=True)
    bits = out.view(np.uint64)
    nz = out != 0.0
    bits[nz] |= np.uint64(1)
    return out


def install() -> bool:
    """Patch ``GroundMotion`` once in this process; False where rockarch is not importable."""
    try:
        from rockarch.motion.signals import GroundMotion
    except ImportError:
        return False
    if getattr(GroundMotion, "_perturbed", False):
        return True
    post_init = GroundMotion.__post_init__

    def perturbed_post_init(self) -> None:
        post_init(self)
        if ENABLED:
            a = last_bit(self.a)
            a.setflags(write=False)
            object.__setattr__(self, "a", a)

    GroundMotion.__post_init__ = perturbed_post_init
    GroundMotion._perturbed = True
    return True
