"""`rockarch ... | head` : when the reader goes away the command stops quietly (exit 141,
the Unix convention for SIGPIPE), without a Python error on stderr."""

from __future__ import annotations

import os
import subprocess
import sys


def test_closed_pipe_is_quiet():
    exe = os.path.join(os.path.dirname(sys.executable), "rockarch")
    proc = subprocess.Popen(
        [exe, "oas", "--system", "block", "--alpha", "0.1", "--signal", "sine", "--period",
         "0.5", "--p", "1,2", "--ratio-steps", "2"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # the reader is gone before the command writes its table
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141
    assert err == ""
