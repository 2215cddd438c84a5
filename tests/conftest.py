"""Test-wide settings: the sweep store of CLI runs goes to a temporary directory (removed
at exit), never to the user's cache.

``ROCKARCH_PERTURB=EPS`` (``make test-perturbed``, run by CI after ``make test``) multiplies
the samples of every ground motion by ``1 + EPS``: every simulation then differs from the
plain run in its last bits, as it would on another machine (other SIMD paths, other builds of
numpy and numba). A test that pins a number beyond its physical tolerance fails there, on
the developer's machine, before it fails on a user's.
"""

import atexit
import os
import shutil
import tempfile

import numpy as np

_CACHE = tempfile.mkdtemp(prefix="rockarch-test-cache-")
os.environ["ROCKARCH_CACHE"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)

PERTURB = float(os.environ.get("ROCKARCH_PERTURB") or 0.0)

if PERTURB:
    from rockarch.motion.signals import GroundMotion

    _post_init = GroundMotion.__post_init__

    def _perturbed_post_init(self) -> None:
        _post_init(self)
        a = np.asarray(self.a) * (1.0 + PERTURB)
        a.setflags(write=False)
        object.__setattr__(self, "a", a)

    GroundMotion.__post_init__ = _perturbed_post_init
