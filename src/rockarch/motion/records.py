"""Readers for strong-motion records: PEER NGA ``.AT2`` files and two-column text.

Records are returned as :class:`rockarch.motion.signals.GroundMotion` in m/s² with uniform
time steps.
PEER files in units of g are converted with standard gravity (9.80665 m/s²); since an OAS
scales every record to a target PGA, this constant never changes an OAS.
"""

from __future__ import annotations

import math
import re
from importlib import resources
from pathlib import Path

import numpy as np

#: Standard gravity [m/s²] used to convert records given in units of g.
from rockarch.core import limits
from rockarch.core.constants import G_STANDARD
from rockarch.motion.signals import GroundMotion

_UNITS = {  # factor to m/s²
    "g": G_STANDARD,
    "m/s2": 1.0, "m/s/s": 1.0, "m/s^2": 1.0, "m/sec2": 1.0, "m/sec/sec": 1.0,
    "cm/s2": 0.01, "cm/s/s": 0.01, "cm/s^2": 0.01, "cm/sec2": 0.01, "cm/sec/sec": 0.01,
    "cm/sec^2": 0.01, "gal": 0.01, "mm/s2": 0.001,
}
_NEW_HEADER = re.compile(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([-+0-9.eEdD]+)", re.IGNORECASE)
_OLD_HEADER = re.compile(r"^\s*(\d+)\s+([-+0-9.eEdD]+)\s+NPTS\s*,\s*DT", re.IGNORECASE)


def _units_factor(unit: str) -> float:
    key = unit.strip().lower().replace(" ", "")
    if key not in _UNITS:
        raise ValueError(f"unknown acceleration unit {unit!r}: use one of {', '.join(_UNITS)}")
    return _UNITS[key]


def _read_text(path: Path) -> str:
    path = Path(path)
    if not path.exists():
        raise ValueError(f"{path}: no such file")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory, not a record file")
    size = path.stat().st_size
    if size > 64 * limits.max_samples():  # a text sample takes at most ~40 characters
        raise limits.too_many(f"{path} ({size / 1e6:.0f} MB)", size / 40, "samples",
                              limits.max_samples(), "shorten the record")
    try:
        return path.read_text(encoding="latin-1")
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror or exc})") from None


def _check_samples(path, acc: np.ndarray) -> None:
    if acc.size < 2:
        raise ValueError(f"{path}: a record needs at least 2 samples, found {acc.size}")
    bad = np.flatnonzero(~np.isfinite(acc))
    if bad.size:
        raise ValueError(f"{path}: sample {int(bad[0])} is not a finite number")
    if not np.any(acc != 0.0):
        raise ValueError(f"{path}: every sample is zero")


def read_at2(path: str | Path) -> GroundMotion:
    """Read a PEER NGA ``.AT2`` acceleration file (NGA-West2 and older NGA header styles).

    The header has four lines: title, event/station, units (``... IN UNITS OF G``) and the
    sampling line, either ``NPTS=  5372, DT=   .0100 SEC`` (NGA-West2) or
    ``  4000    0.01000    NPTS, DT`` (older NGA). Values follow, several per line.
    """
    path = Path(path)
    text = _read_text(path)
    if "\x00" in text[:8192]:
        raise ValueError(f"{path}: a binary file, not a PEER .AT2 text file")
    lines = text.splitlines()
    if len(lines) < 4:
        raise ValueError(f"{path}: not a PEER .AT2 file (fewer than 4 header lines)")
    header = lines[:4]
    m = _NEW_HEADER.search(header[3]) or _OLD_HEADER.search(header[3])
    if m is None:
        raise ValueError(f"{path}: not a PEER .AT2 file (line 4 should give NPTS and DT, "
                         f"found {header[3].strip()!r})")
    npts = int(m.group(1))
    dt = float(m.group(2).replace("D", "E").replace("d", "e"))
    if not (dt > 0 and math.isfinite(dt)):
        raise ValueError(f"{path}: DT must be > 0, found {dt}")
    unit_line = header[2].upper()
    if "ACCELERATION" not in unit_line:
        raise ValueError(f"{path}: not an acceleration record (line 3: {header[2].strip()!r})")
    um = re.search(r"UNITS\s+OF\s+(\S+)", unit_line)
    factor = _units_factor(um.group(1)) if um else G_STANDARD
    try:
        values = np.array(" ".join(lines[4:]).replace("D", "E").split(), dtype=float)
    except ValueError:
        raise ValueError(f"{path}: the sample values are not all numbers") from None
    if values.size != npts:
        raise ValueError(f"{path}: header says NPTS={npts} but the file holds {values.size} "
                         "values (truncated or corrupted file)")
    _check_samples(path, values)
    t = np.arange(npts) * dt
    title = header[1].strip()
    meta = {"source": str(path), "title": title, "dt": dt, "npts": npts, "format": "AT2",
            "units_in_file": um.group(1) if um else "G"}
    return GroundMotion(t, values * factor, f"{path.name} ({title})", meta)


def read_two_column(path: str | Path, *, units: str = "m/s2", comment: str = "#",
                    rtol: float = 1e-4) -> GroundMotion:
    """Read a two-column text record: time [s] and acceleration (``units``: m/s2, g, cm/s2).

    Columns may be separated by spaces, tabs, commas or semicolons; lines starting with
    ``comment`` are skipped, and so are text lines before the first sample (a header such
    as ``time acc``). Every sample line holds exactly two numbers. The time step must be
    uniform (relative tolerance ``rtol``, for rounding in the file); resample a non-uniform
    record before using it. Every error names the file and the line.
    """
    path = Path(path)
    factor = _units_factor(units)
    text = _read_text(path)
    if "\x00" in text[:8192]:
        raise ValueError(f"{path}: a binary file, not a text record (time, acceleration)")
    rows, lines = [], []
    for k, line in enumerate(text.splitlines(), start=1):
        s = line.strip()
        if not s or s.startswith(comment):
            continue
        parts = re.split(r"[\s,;]+", s)
        try:
            vals = [float(v) for v in parts]
        except ValueError:
            if not rows:  # a header line such as "time acc"
                continue
            raise ValueError(f"{path}: line {k} is not two numbers: {s[:60]!r}") from None
        if len(vals) != 2:
            raise ValueError(f"{path}: line {k} has {len(vals)} column(s), expected 2 "
                             "(time, acceleration)")
        rows.append(vals)
        lines.append(k)
    if not rows:
        raise ValueError(f"{path}: no samples: a record needs at least 2 samples "
                         "(lines 'time acceleration')")
    if len(rows) < 2:
        raise ValueError(f"{path}: a record needs at least 2 samples, found {len(rows)}")
    data = np.array(rows)
    bad = np.flatnonzero(~np.isfinite(data).all(axis=1))
    if bad.size:
        raise ValueError(f"{path}: line {lines[int(bad[0])]} holds a value that is not a "
                         "finite number")
    t, acc = data[:, 0], data[:, 1]
    _check_samples(path, acc)
    dts = np.diff(t)
    back = np.flatnonzero(dts <= 0)
    if back.size:
        raise ValueError(f"{path}: time must increase (line {lines[int(back[0]) + 1]}: "
                         f"t={t[back[0] + 1]:g} s after t={t[back[0]]:g} s)")
    dt = (t[-1] - t[0]) / (t.size - 1)
    typical = float(np.median(dts))
    off = np.flatnonzero(np.abs(dts - typical) > rtol * typical)
    if off.size:
        k = int(off[0])
        raise ValueError(f"{path}: non-uniform time step at line {lines[k + 1]} "
                         f"(dt={dts[k]:g} s, elsewhere {typical:g} s); resample to a uniform "
                         "dt first")
    t_uniform = t[0] + np.arange(t.size) * dt
    meta = {"source": str(path), "dt": dt, "npts": int(t.size), "format": "two-column",
            "units_in_file": units}
    return GroundMotion(t_uniform - t[0], acc * factor, path.name, meta)


def read_record(path: str | Path, *, units: str | None = None) -> GroundMotion:
    """Read a record by its file type: ``.AT2`` as PEER, anything else as two-column text.

    ``units`` applies to two-column files (default m/s2); AT2 files state their own.
    """
    path = Path(path)
    if path.suffix.lower() == ".at2":
        return read_at2(path)
    return read_two_column(path, units=units or "m/s2")


_BUNDLED = {180: "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", 270: "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"}


def bundled_record_path(component: int = 180) -> Path:
    """Path of a bundled El Centro 1940 component (180 or 270), see PROVENANCE.md."""
    if component not in _BUNDLED:
        raise ValueError(f"bundled El Centro components are 180 and 270, got {component!r}")
    return Path(str(resources.files("rockarch.motion") / "data" / _BUNDLED[component]))


def el_centro(component: int = 180) -> GroundMotion:
    """Bundled demo record: El Centro 1940, component 180° (default) or 270°
    (PEER NGA-West2 RSN6). See ``rockarch/motion/data/PROVENANCE.md`` for source and citation.
    """
    return read_at2(bundled_record_path(component))
