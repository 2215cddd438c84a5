"""Progress bars on any terminal (rockarch.core.console)."""

import os

from rockarch.core import console


def test_a_terminal_without_a_height_still_shows_bars(monkeypatch):
    # tqdm hides every bar below the screen's height: a pseudo-terminal that reports 0 rows
    # (``script``, some CI runners) gets a height; any other terminal keeps its own
    monkeypatch.setattr(console.os, "get_terminal_size",
                        lambda fd: os.terminal_size((100, 0)))
    assert console.bar_rows() == console.DEFAULT_ROWS
    monkeypatch.setattr(console.os, "get_terminal_size",
                        lambda fd: os.terminal_size((100, 40)))
    assert console.bar_rows() is None

    def not_a_terminal(fd):
        raise OSError("Inappropriate ioctl for device")

    monkeypatch.setattr(console.os, "get_terminal_size", not_a_terminal)
    assert console.bar_rows() is None
