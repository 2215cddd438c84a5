"""Test-wide settings: the sweep store of CLI runs goes to a temporary directory, never to
the user's cache."""

import os
import tempfile

os.environ["ROCKARCH_CACHE"] = tempfile.mkdtemp(prefix="rockarch-test-cache-")
