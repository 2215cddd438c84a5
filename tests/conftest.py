"""Test-wide settings: the sweep store of CLI runs goes to a temporary directory (removed
at exit), never to the user's cache.

``ROCKARCH_PERTURB=1`` (``make test-perturbed``, run by CI after ``make test``) moves every
ground motion in its last bit, in this process and in every Python process the tests start
(tests/perturb/rockarch_perturb.py says how, and which invariances it keeps): every
simulation then differs from the plain run in its last bits, as it would on another machine.
A test that checks an exact construction opts out with ``@pytest.mark.unperturbed``.
"""

import atexit
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

_CACHE = tempfile.mkdtemp(prefix="rockarch-test-cache-")
os.environ["ROCKARCH_CACHE"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)

_PERTURB_DIR = str(Path(__file__).parent / "perturb")
if _PERTURB_DIR not in sys.path:
    sys.path.insert(0, _PERTURB_DIR)

import rockarch_perturb  # noqa: E402

if rockarch_perturb.ENABLED:
    rockarch_perturb.install()
    # child processes (CLI runs, pool workers, the docs' scripts) start perturbed too
    paths = os.environ.get("PYTHONPATH", "").split(os.pathsep)
    if _PERTURB_DIR not in paths:
        os.environ["PYTHONPATH"] = os.pathsep.join([_PERTURB_DIR, *filter(None, paths)])


@pytest.fixture(autouse=True)
def _unperturbed(request):
    """Turn the perturbation off for a test marked ``unperturbed`` (exact constructions)."""
    if not rockarch_perturb.ENABLED or request.node.get_closest_marker("unperturbed") is None:
        yield
        return
    rockarch_perturb.ENABLED = False
    try:
        yield
    finally:
        rockarch_perturb.ENABLED = True


@pytest.fixture(scope="session")
def short_records(tmp_path_factory):
    """The first 12 s of both bundled El Centro components (the strong motion) as .AT2
    files in one folder: the fragility and risk commands' checks, fast."""
    import rockarch as ra
    from rockarch.motion.suite import write_at2

    d = tmp_path_factory.mktemp("short")
    for c in (180, 270):
        m = ra.el_centro(c)
        write_at2(d / f"ELC{c}-12s.AT2", ra.GroundMotion(m.t[:1200], m.a[:1200]))
    return d
