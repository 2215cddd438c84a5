"""What the command line shows on stderr besides its results: warnings as one line each,
and progress bars that show on any terminal.

Theory: none (presentation only).

:func:`one_line_warnings` makes every Python warning of the process (the library's own, and
numpy's or scipy's from any thread) print as ``warning: MESSAGE`` on one line, without the
source line that Python's default format echoes. The CLI installs it at start-up and the
sweep's worker processes when they start; a library user keeps Python's own format.
"""

from __future__ import annotations

import os
import sys
import warnings

#: Height given to progress bars on a terminal that reports none (see :func:`bar_rows`).
DEFAULT_ROWS = 24


def format_warning(message) -> str:
    """``warning: MESSAGE`` on one line (whitespace and newlines folded)."""
    return "warning: " + " ".join(str(message).split())


def _show(message, category, filename, lineno, file=None, line=None) -> None:
    stream = sys.stderr if file is None else file
    if stream is None:
        return
    try:
        stream.write(format_warning(message) + "\n")
        stream.flush()
    except (OSError, ValueError):  # a closed or broken stderr: nothing to show it on
        pass


def one_line_warnings() -> None:
    """Print every warning of this process as one ``warning: ...`` line on stderr."""
    warnings.showwarning = _show


def on_terminal(progress: bool | None) -> bool:
    """Whether to show a progress bar: ``progress`` if given, else only when stderr is a
    terminal (a log file or a pipe gets no carriage-return bars)."""
    if progress is not None:
        return bool(progress)
    try:
        return sys.stderr is not None and sys.stderr.isatty()
    except (AttributeError, ValueError):  # a replaced or closed stderr
        return False


def bar_rows() -> int | None:
    """The screen height to give a progress bar (tqdm's ``nrows``): None (tqdm asks the
    terminal) unless stderr is a terminal that reports 0 rows (a pseudo-terminal with no size
    set, as under ``script`` or some CI runners), where tqdm would hide every bar; then
    :data:`DEFAULT_ROWS`."""
    try:
        rows = os.get_terminal_size(sys.stderr.fileno()).lines
    except (AttributeError, OSError, ValueError):  # not a terminal, or no stderr
        return None
    return DEFAULT_ROWS if rows <= 0 else None
