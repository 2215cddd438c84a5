"""Test-wide settings: the sweep store of CLI runs goes to a temporary directory (removed
at exit), never to the user's cache."""

import atexit
import os
import shutil
import tempfile

_CACHE = tempfile.mkdtemp(prefix="rockarch-test-cache-")
os.environ["ROCKARCH_CACHE"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)
