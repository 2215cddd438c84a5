"""Readers for strong-motion records: PEER NGA ``.AT2`` files, ESM/ITACA ASCII files, K-NET /
KiK-net ASCII files, COSMOS-format files (CESMD, USGS), two-column text (time,
acceleration) and single-column text (accelerations alone, given their time step).

Records are returned as :class:`rockarch.motion.signals.GroundMotion` in m/s² with uniform
time steps.
PEER files in units of g are converted with standard gravity (9.80665 m/s²); since an OAS
scales every record to a target PGA, this constant never changes an OAS.
"""

from __future__ import annotations

import contextlib
import itertools
import math
import os
import re
import warnings
from importlib import resources
from pathlib import Path

import numpy as np

#: Standard gravity [m/s²] used to convert records given in units of g.
from rockarch.core import limits
from rockarch.core.constants import G_STANDARD, g_label
from rockarch.core.validate import number, show
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
    _check_file(path)
    try:
        return path.read_text(encoding="latin-1")
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror or exc})") from None


def _check_file(path: Path) -> None:
    """An existing record file of a size that its sample limit allows."""
    if not path.exists():
        raise ValueError(f"{path}: no such file")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory, not a record file")
    if not path.is_file():  # a pipe (<(...)) or a device: read more than once, it cannot be
        raise ValueError(f"{path}: not a regular file (a pipe?): save the record to a file "
                         "and give that")
    size = path.stat().st_size
    if size > 64 * limits.max_samples():  # a text sample takes at most ~40 characters
        raise limits.too_many(f"{path} ({size / 1e6:.0f} MB)", size / 40, "samples",
                              limits.max_samples(), "shorten the record")


def _check_samples(path, acc: np.ndarray) -> None:
    if acc.size < 2:
        raise ValueError(f"{path}: a record needs at least 2 samples, found {acc.size}")
    bad = np.flatnonzero(~np.isfinite(acc))
    if bad.size:
        raise ValueError(f"{path}: sample {int(bad[0])} is not a finite number")
    if not np.any(acc != 0.0):
        raise ValueError(f"{path}: every sample is zero")


def _numbers(body: str) -> np.ndarray | None:
    """The whitespace-separated numbers of ``body`` (numpy's C parser: 8 bytes per value, no
    Python float objects), or None if one is not a number."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", DeprecationWarning)  # numpy < 2: partial reads
            return np.fromstring(body, sep=" ") if body.strip() else np.zeros(0)
    except (ValueError, DeprecationWarning):
        return None


def _header_numbers(path, header: dict, keys: tuple, names: tuple | None = None,
                    integer: int | None = None) -> list:
    """The numbers of the header fields ``keys`` (``integer``: the index of one that must be
    an integer, returned as int); one ValueError naming them all (as ``names``) otherwise."""
    try:
        vals = [float(header[k]) for k in keys]
        if integer is not None:
            if not vals[integer].is_integer():
                raise ValueError
            vals[integer] = int(vals[integer])
        return vals
    except ValueError:
        raise ValueError(f"{path}: {' and '.join(names or keys)} must be numbers, found "
                         f"{' and '.join(repr(header[k]) for k in keys)}") from None


def _samples(path, body: str, npts: int | None, key: str, factor: float,
             where: str) -> np.ndarray:
    """The ``npts`` whitespace-separated values of ``body`` times ``factor`` [m/s²], checked
    (``key``: the header's count, NPTS or NDATA, or None where the header has none;
    ``where``: the values' place, for errors)."""
    values = _numbers(body)
    if values is None:
        raise ValueError(f"{path}: the sample values{where} are not all numbers")
    if npts is None and values.size > limits.max_samples():
        raise limits.too_many(str(path), values.size, "samples", limits.max_samples(),
                              "shorten or decimate the record")
    if npts is not None and values.size != npts:
        raise ValueError(f"{path}: header says {key}={npts} but the file holds {values.size} "
                         "values (truncated or corrupted file)")
    _check_samples(path, values)
    values = values * factor
    check_acceleration(path, values)
    return values


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
    header = text[:65536].splitlines()[:4]
    if len(header) < 4:
        raise ValueError(f"{path}: not a PEER .AT2 file (fewer than 4 header lines)")
    m = _NEW_HEADER.search(header[3]) or _OLD_HEADER.search(header[3])
    if m is None:
        raise ValueError(f"{path}: not a PEER .AT2 file (line 4 should give NPTS and DT, "
                         f"found {header[3].strip()!r})")
    npts = int(m.group(1))
    if npts > limits.max_samples():  # before the values are parsed
        raise limits.too_many(f"{path} (NPTS={npts})", npts, "samples", limits.max_samples(),
                              "shorten or decimate the record")
    dt = float(m.group(2).replace("D", "E").replace("d", "e"))
    if not (dt > 0 and math.isfinite(dt)):
        raise ValueError(f"{path}: DT must be > 0, found {dt}")
    _check_dt(path, dt)
    unit_line = header[2].upper()
    if "ACCELERATION" not in unit_line:
        raise ValueError(f"{path}: not an acceleration record (line 3: {header[2].strip()!r})")
    um = re.search(r"UNITS\s+OF\s+(\S+)", unit_line)
    factor = _units_factor(um.group(1)) if um else G_STANDARD
    cut = 0
    for _ in range(4):  # the values after the four header lines
        cut = text.find("\n", cut) + 1 if cut >= 0 else cut
        cut = cut if cut > 0 else -1
    body = "" if cut < 0 else text[cut:].replace("D", "E").replace("d", "e")
    values = _samples(path, body, npts, "NPTS", factor, "")
    t = np.arange(npts) * dt
    title = header[1].strip()
    meta = {"source": str(path), "title": title, "dt": dt, "npts": npts, "format": "AT2",
            "units_in_file": um.group(1) if um else "G"}
    return GroundMotion(t, values, f"{path.name} ({title})", meta)


#: Header keys every ESM (Engineering Strong-Motion database, ORFEUS) or ITACA ASCII file
#: has: ``KEY: value`` header lines (``EVENT_NAME:`` first in ESM's files), then one
#: sample a line.
ESM_KEYS = ("NDATA", "SAMPLING_INTERVAL_S")
_ESM_KEY = re.compile(r"^([A-Z][A-Z0-9_/^.()-]*)\s*:(.*)$")  # VS30_M/S, PGA_CM/S^2


def _first_lines(path: Path, n: int) -> list[str]:
    """The file's first ``n`` lines (fewer if it is shorter; none if it cannot be read)."""
    try:
        with contextlib.closing(_lines(path)) as lines:
            return list(itertools.islice(lines, n))
    except OSError:
        return []


def is_at2(path: str | Path) -> bool:
    """True if the file's 4th line is a PEER header's sampling line (NPTS and DT)."""
    head = _first_lines(Path(path), 4)
    return len(head) == 4 and bool(_NEW_HEADER.search(head[3]) or _OLD_HEADER.search(head[3]))


def is_esm(path: str | Path) -> bool:
    """True if the file opens with ESM/ITACA header lines (``KEY: value``): ``EVENT_NAME``
    first, or one of :data:`ESM_KEYS` among them (:func:`read_esm` says which is missing)."""
    keys = set()
    for line in _first_lines(Path(path), 100):
        m = _ESM_KEY.match(line.strip().removeprefix("\ufeff"))
        if m is None:
            break
        keys.add(m.group(1))
    return bool(keys) and ("EVENT_NAME" in keys or any(k in keys for k in ESM_KEYS))


def read_esm(path: str | Path) -> GroundMotion:
    """Read an ESM / ITACA ASCII acceleration file (Engineering Strong-Motion database).

    The header is ``KEY: value`` lines (64 in ESM files); the reader uses ``NDATA``,
    ``SAMPLING_INTERVAL_S``, ``UNITS`` (cm/s^2 in ESM acceleration files) and, where
    present, ``DATA_TYPE`` (must be an acceleration) and ``EVENT_NAME``, ``STATION_CODE``,
    ``STREAM`` for the record's name. One sample a line follows.
    """
    path = Path(path)
    text = _read_text(path)
    if "\x00" in text[:8192]:
        raise ValueError(f"{path}: a binary file, not an ESM ASCII record")
    lines = text.splitlines()
    header: dict[str, str] = {}
    n_head = 0
    for line in lines[:1000]:
        m = _ESM_KEY.match(line.strip().removeprefix("\ufeff"))
        if m is None:
            break
        value = m.group(2).strip()
        header[m.group(1)] = "" if value == "None" else value  # ESM writes None for unknown
        n_head += 1
    for key in ("NDATA", "SAMPLING_INTERVAL_S", "UNITS"):
        if key not in header:
            raise ValueError(f"{path}: an ESM ASCII file needs the header line {key}: ... "
                             f"(found {n_head} header lines without it)")
    kind = header.get("DATA_TYPE", "ACCELERATION").upper()
    if "ACCELERATION" not in kind or "SPECTRUM" in kind:  # ESM also serves spectra (.SA.ASC)
        raise ValueError(f"{path}: not an acceleration time history (DATA_TYPE: {kind})")
    npts, dt = _header_numbers(path, header, ("NDATA", "SAMPLING_INTERVAL_S"), integer=0)
    if npts > limits.max_samples():
        raise limits.too_many(f"{path} (NDATA={npts})", npts, "samples", limits.max_samples(),
                              "shorten or decimate the record")
    if not (dt > 0 and math.isfinite(dt)):
        raise ValueError(f"{path}: SAMPLING_INTERVAL_S must be > 0, found {dt}")
    _check_dt(path, dt)
    factor = _units_factor(header["UNITS"])
    values = _samples(path, "\n".join(lines[n_head:]), npts, "NDATA", factor,
                      f" after the header (line {n_head + 1} on)")
    parts = [header.get(k, "") for k in ("EVENT_NAME", "STATION_CODE", "STREAM")]
    title = " ".join(p for p in parts if p)
    meta = {"source": str(path), "title": title, "dt": dt, "npts": npts, "format": "ESM",
            "units_in_file": header["UNITS"], "header": header}
    return GroundMotion(np.arange(npts) * dt, values,
                        f"{path.name} ({title})" if title else path.name, meta)


#: First header key of a K-NET / KiK-net ASCII file (NIED, Japan): 17 header lines
#: ``Key<padding to column 18>value``, then integer counts, 8 a line.
KNET_FIRST_KEY = "Origin Time"
KNET_HEADER_LINES = 17
#: KiK-net's ``Dir.`` codes: 1-3 the borehole sensor (N-S, E-W, U-D), 4-6 the surface one.
KIKNET_DIRECTIONS = {"1": "N-S", "2": "E-W", "3": "U-D", "4": "N-S", "5": "E-W", "6": "U-D"}


def is_knet(path: str | Path) -> bool:
    """True if the file's first line is a K-NET / KiK-net header line (``Origin Time ...``)."""
    head = _first_lines(Path(path), 1)
    return bool(head) and head[0].lstrip().startswith(KNET_FIRST_KEY)


def _knet_key(key: str) -> str:
    """A K-NET header key without dots and blanks, lower case (``Max. Acc. (gal)`` and
    ``Max Acc. (gal)`` both ``maxacc(gal)``)."""
    return re.sub(r"[.\s]", "", key).lower()


def read_knet(path: str | Path) -> GroundMotion:
    """Read a K-NET or KiK-net ASCII acceleration file (NIED, Japan: ``.NS``, ``.EW``,
    ``.UD``; KiK-net ``.NS1`` ... ``.UD2``).

    docs/sites.md, "What a folder holds". The 17 header lines give ``Sampling Freq(Hz)``,
    ``Scale Factor`` (``A(gal)/B``: one count is A/B gal), ``Duration Time(s)`` and
    ``Max. Acc. (gal)``; integer counts follow. The counts carry the recorder's offset:
    the acceleration is counts × A/B less the record's mean, as NIED defines it (its
    ``Max. Acc.`` is the peak after that mean is removed). The reader checks the file
    against its header: its length against ``Duration Time(s)`` (within a second) and its
    peak against ``Max. Acc.`` (within two counts and the header's rounding, or 1 %).
    """
    path = Path(path)
    text = _read_text(path)
    if "\x00" in text[:8192]:
        raise ValueError(f"{path}: a binary file, not a K-NET ASCII record")
    lines = text.splitlines()
    if len(lines) < KNET_HEADER_LINES:
        raise ValueError(f"{path}: a K-NET file has {KNET_HEADER_LINES} header lines, found "
                         f"{len(lines)} lines")
    header = {_knet_key(line[:18]): line[18:].strip() for line in lines[:KNET_HEADER_LINES]}
    need = {"samplingfreq(hz)": "Sampling Freq(Hz)", "scalefactor": "Scale Factor",
            "durationtime(s)": "Duration Time(s)", "maxacc(gal)": "Max. Acc. (gal)"}
    missing = [name for key, name in need.items() if key not in header]
    if missing:
        raise ValueError(f"{path}: a K-NET file needs the header line {missing[0]!r} in its "
                         f"first {KNET_HEADER_LINES} lines")
    freq = re.fullmatch(r"([0-9]*\.?[0-9]+)\s*(?:Hz)?", header["samplingfreq(hz)"],
                        re.IGNORECASE)
    fs = float(freq.group(1)) if freq else 0.0
    if not fs > 0:
        raise ValueError(f"{path}: Sampling Freq(Hz) must be a positive number such as "
                         f"'100Hz', found {header['samplingfreq(hz)']!r}")
    scale = re.fullmatch(r"([0-9]*\.?[0-9]+)\s*\(gal\)\s*/\s*([0-9]*\.?[0-9]+)",
                         header["scalefactor"], re.IGNORECASE)
    num, den = (float(scale.group(1)), float(scale.group(2))) if scale else (0.0, 0.0)
    if not (num > 0 and den > 0):
        raise ValueError(f"{path}: Scale Factor must read like '3920(gal)/6182761', found "
                         f"{header['scalefactor']!r}")
    duration, peak_gal = _header_numbers(path, header, ("durationtime(s)", "maxacc(gal)"),
                                         names=("Duration Time(s)", "Max. Acc. (gal)"))
    dt = 1.0 / fs
    _check_dt(path, dt)
    gal = _samples(path, "\n".join(lines[KNET_HEADER_LINES:]), None, "", num / den,
                   f" after the header (line {KNET_HEADER_LINES + 1} on)")
    if abs(gal.size / fs - duration) > 1.0:  # NIED rounds the duration to the second
        raise ValueError(f"{path}: {gal.size} samples at {fs:g} Hz last "
                         f"{gal.size / fs:.2f} s, the header's Duration Time(s) is "
                         f"{duration:g} s (truncated or corrupted file)")
    gal -= gal.mean()
    peak = float(np.abs(gal).max())
    # the header's peak is printed to 0.001 gal; the mean of a cut or edited file differs
    if abs(peak - peak_gal) > max(0.01 * peak_gal, 2.0 * num / den + 0.0005):
        raise ValueError(f"{path}: its peak after the mean is removed is {peak:.3f} gal, the "
                         f"header's Max. Acc. is {peak_gal:g} gal (edited or corrupted file?)")
    values = gal * 0.01
    direction = header.get("dir", "")
    sensor = None
    if direction in KIKNET_DIRECTIONS:
        sensor = "borehole" if direction in "123" else "surface"
        direction = KIKNET_DIRECTIONS[direction]
    title = " ".join(x for x in (header.get("stationcode", ""), direction,
                                 header.get("origintime", "")) if x)
    meta = {"source": str(path), "title": title, "dt": dt, "npts": int(gal.size),
            "format": "K-NET", "units_in_file": "counts", "scale_gal": num / den,
            "component": direction, "sensor": sensor, "header": header}
    return GroundMotion(np.arange(gal.size) * dt, values, f"{path.name} ({title})", meta)


#: COSMOS strong-motion data format (v1.20; CESMD and the USGS NSMP serve it): the first line
#: names the data and the text lines, ``Corrected acceleration (Format v01.20 with 13 text
#: lines)``; an integer and a real header follow, comments, then a data line giving the
#: points, units and Fortran format of the values.
_COSMOS_FIRST = re.compile(r"\(Format\s+v\d+\.\d+\s+with\s+(\d+)\s+text\s+lines\)", re.I)
_COSMOS_HEADER = re.compile(r"^\s*(\d+)\s+(Integer|Real)-header\s+values\s+follow\s+on\s+(\d+)"
                            r"\s+lines\s*,\s*Format\s*=\s*\(\s*(\d+)\s*[IF](\d+)", re.I)
_COSMOS_COMMENTS = re.compile(r"^\s*(\d+)\s+Comment\s+line", re.I)
_COSMOS_DATA = re.compile(r"^\s*(\d+)\s+(.*?)\s*pts\s*,\s*approx\s+([0-9.]+)\s*secs\s*,\s*"
                          r"units\s*=\s*([^(,]*?)\s*\(\s*\d+\s*\)\s*,\s*Format\s*=\s*"
                          r"\(\s*(\d+)\s*[EFI](\d+)", re.I)
#: COSMOS channel orientation codes (integer header 54) of vertical sensors.
COSMOS_VERTICAL = {400: "Up", 401: "Down", 402: "Vertical"}


def is_cosmos(path: str | Path) -> bool:
    """True if the file's first line is a COSMOS header's (``... (Format v01.20 with 13 text
    lines)``)."""
    head = _first_lines(Path(path), 1)
    return bool(head) and _COSMOS_FIRST.search(head[0]) is not None


def _cosmos_fields(path, lines: list[str], k: int, n: int, per: int, width: int,
                   what: str) -> str:
    """The ``n`` fixed-width fields (``per`` a line, ``width`` characters each) of the lines
    from ``k`` on, as one blank-separated string (Fortran fields may touch: -1.5-2.5)."""
    rows = -(-n // per)
    if k + rows > len(lines):
        raise ValueError(f"{path}: the file ends inside its {what} (line {len(lines)}): "
                         "truncated file")
    fields = [line[i:i + width] for line in lines[k:k + rows]
              for i in range(0, len(line.rstrip()), width)]
    return " ".join(fields[:n])


def read_cosmos(path: str | Path, channel: int | None = None) -> GroundMotion:
    """Read a COSMOS-format acceleration file (v1.20: CESMD's and the USGS's ``.V2c``,
    ``.V1c`` files).

    docs/sites.md, "What a folder holds". The first line gives the number of text lines;
    the integer header (channel orientation: value 54, 400-402 vertical), the real header
    (the sampling interval in ms: value 62) and the comments follow; then the data line
    ``N acceleration pts, approx T secs, units=cm/sec2(04), Format=(8F10.5)`` and the values
    in that fixed-width format. Corrected (V2) and uncorrected (V1) accelerations are read
    as the file gives them; raw counts (V0) and velocities are refused.

    Parameters
    ----------
    path : the file.
    channel : which acceleration channel of a file that holds several (1, 2, ...; the
        velocity and displacement that a V2 file gives after each are not channels). A file
        of several channels without ``channel`` is an error that lists them
        (:func:`read_cosmos_channels` reads them all; a suite does).
    """
    path = Path(path)
    starts = _cosmos_starts(path)
    if channel is None and len(starts) > 1:
        names = ", ".join(f"#{k + 1} {_cosmos_channel(path, starts[k]).meta['component']}"
                          for k in range(len(starts)))
        raise ValueError(f"{path}: holds {len(starts)} acceleration channels ({names}): give "
                         f"one as {path.name}#N (N = 1..{len(starts)}), or the file in a "
                         "suite (--records), which reads them all")
    if channel is not None and not (isinstance(channel, (int, np.integer))
                                    and 1 <= channel <= len(starts)):
        if len(starts) == 1:
            raise ValueError(f"{path}: holds one acceleration channel, not channel "
                             f"{show(channel)}: give the file without '#N'")
        raise ValueError(f"{path}: channel must be 1..{len(starts)} (the file's acceleration "
                         f"channels), got {show(channel)}")
    return _cosmos_channel(path, starts[(channel or 1) - 1])


_CHANNEL = re.compile(r"^(.+)#(\d+)$")


def split_channel(path: str | Path) -> tuple[Path, int | None]:
    """``FILE#N`` (channel N of a COSMOS file that holds several) as ``(FILE, N)``; any other
    path, and a file whose name does end in ``#N``, as ``(path, None)``."""
    p = Path(path)
    m = _CHANNEL.match(p.name)
    if m is None or p.exists():
        return p, None
    return p.with_name(m.group(1)), int(m.group(2))


def read_cosmos_channels(path: str | Path) -> tuple[GroundMotion, ...]:
    """Every acceleration channel of a COSMOS file (:func:`read_cosmos`), in file order;
    a file of several channels names each ``FILE#N (title)`` and keeps ``N`` in
    ``meta["channel"]``."""
    path = Path(path)
    starts = _cosmos_starts(path)
    return tuple(_cosmos_channel(path, s) for s in starts)


def _cosmos_starts(path: Path) -> tuple[tuple[list[str], int, int, int], ...]:
    """(lines, first line, channel number, channel count) of each acceleration channel: the
    lines whose COSMOS first line names an acceleration (V2 files follow each channel with
    its velocity and displacement, under first lines of their own)."""
    text = _read_text(path)
    if "\x00" in text[:8192]:
        raise ValueError(f"{path}: a binary file, not a COSMOS record")
    lines = text.splitlines()
    if not lines or _COSMOS_FIRST.search(lines[0]) is None:
        raise ValueError(f"{path}: not a COSMOS file (its first line should end with "
                         "'(Format v01.20 with 13 text lines)')")
    firsts = [i for i, line in enumerate(lines)
              if _COSMOS_FIRST.search(line) is not None and "accel" in line.lower()]
    if not firsts or firsts[0] != 0:
        firsts = [0] + firsts  # the first block is read (and refused if not an acceleration)
    n = len(firsts)
    if n > limits.max_records():
        raise limits.too_many(f"{path} ({n} channels)", n, "records", limits.max_records(),
                              "split the file")
    return tuple((lines, i, k + 1, n) for k, i in enumerate(firsts))


def _cosmos_channel(path: Path, where: tuple[list[str], int, int, int]) -> GroundMotion:
    """One channel of a COSMOS file from its first line (``where``: :func:`_cosmos_starts`);
    line numbers in messages are the file's."""
    lines, s, channel, channels = where
    first = _COSMOS_FIRST.search(lines[s])
    k = s + int(first.group(1))
    blocks = {}
    for what in ("Integer", "Real"):
        m = _COSMOS_HEADER.match(lines[k]) if k < len(lines) else None
        if m is None or m.group(2).lower() != what.lower():
            raise ValueError(f"{path}: line {k + 1} should announce the {what.lower()} "
                             f"header ('100 {what}-header values follow on ...')")
        n, rows, per, width = int(m.group(1)), int(m.group(3)), int(m.group(4)), int(m.group(5))
        if rows != -(-n // per):
            raise ValueError(f"{path}: line {k + 1}: {n} values at {per} a line do not take "
                             f"{rows} lines")
        body = _cosmos_fields(path, lines, k + 1, n, per, width, f"{what.lower()} header")
        blocks[what] = _numbers(body)
        if blocks[what] is None or blocks[what].size != n:
            raise ValueError(f"{path}: the {what.lower()} header (lines {k + 2}-{k + 1 + rows}) "
                             f"does not hold {n} numbers")
        k += 1 + rows
    ints, reals = blocks["Integer"], blocks["Real"]
    m = _COSMOS_COMMENTS.match(lines[k]) if k < len(lines) else None
    if m is None:
        raise ValueError(f"{path}: line {k + 1} should announce the comment lines")
    comments = lines[k + 1:k + 1 + int(m.group(1))]
    k += 1 + int(m.group(1))
    m = _COSMOS_DATA.match(lines[k]) if k < len(lines) else None
    if m is None:
        raise ValueError(f"{path}: line {k + 1} should give the data "
                         "('N acceleration pts, approx T secs, units=..., Format=(...)')")
    npts, approx = int(m.group(1)), float(m.group(3))
    kind, units = m.group(2).strip(), m.group(4).strip()
    if "accel" not in kind.lower() or units.lower() == "counts":
        raise ValueError(f"{path}: holds {kind} in {units}, not an acceleration in physical "
                         "units (a raw V0 file or a velocity): use the corrected (V2) file")
    if npts > limits.max_samples():
        raise limits.too_many(f"{path} ({npts} pts)", npts, "samples", limits.max_samples(),
                              "shorten or decimate the record")
    per, width = int(m.group(5)), int(m.group(6))
    body = _cosmos_fields(path, lines, k + 1, npts, per, width, "values")
    dt_ms = float(reals[61]) if reals.size > 61 else -999.0
    if not (dt_ms > 0 and math.isfinite(dt_ms)):
        raise ValueError(f"{path}: the sampling interval (real header value 62, ms) is "
                         f"unknown ({dt_ms:g})")
    dt = dt_ms * 1e-3
    _check_dt(path, dt)
    if abs(npts * dt - approx) > max(1.0, 0.02 * approx):  # "approx T secs": rounded
        raise ValueError(f"{path}: {npts} pts at {dt:g} s last {npts * dt:.2f} s, the data "
                         f"line says approx {approx:g} secs")
    factor = _units_factor(units)
    values = _samples(path, body, npts, "pts", factor, f" after line {k + 1}")
    peak = float(reals[63]) if reals.size > 63 else -999.0  # real header 64: the peak value
    got = float(np.abs(values).max()) / factor
    if peak != -999.0 and abs(got - abs(peak)) > max(1e-3 * abs(peak), 1e-5):
        raise ValueError(f"{path}: its peak is {got:.6g} {units}, its header's (real value 64) "
                         f"{abs(peak):.6g} {units} (edited or corrupted file?)")
    orientation = int(ints[53]) if ints.size > 53 else -999
    scnl = re.search(r"<SCNL>\s*[^.\s]+\.([A-Z0-9]{3})\.", "\n".join(comments))
    if orientation in COSMOS_VERTICAL:
        component = COSMOS_VERTICAL[orientation]
    elif 0 < orientation <= 360:
        component = f"{orientation:03d}"
    else:
        component = scnl.group(1) if scnl else None
    head = lines[s:s + 5]
    station = re.search(r"Code:\s*(\S+)", head[4]) if len(head) > 4 else None
    mw = re.search(r"\bMw\s*=\s*([0-9.]+)", head[2]) if len(head) > 2 else None
    year = int(ints[39]) if ints.size > 39 and 1800 < ints[39] < 2300 else None
    title = head[1].strip() if len(head) > 1 else ""
    meta = {"source": str(path), "title": title, "dt": dt, "npts": npts, "format": "COSMOS",
            "units_in_file": units, "component": component,
            "station": station.group(1) if station else None,
            "magnitude": float(mw.group(1)) if mw else None, "year": year,
            "channel": channel, "channels": channels}
    name = path.name if channels == 1 else f"{path.name}#{channel}"
    return GroundMotion(np.arange(npts) * dt, values, f"{name} ({title})" if title else name,
                        meta)


#: Largest |acceleration| of a record sample [m/s²] (1e5 g): above it a file is not an
#: acceleration record in the units given, and its integrals (PGV, Arias) would overflow.
MAX_ACCELERATION = 1e5 * G_STANDARD
#: Largest peak (in the file's own numbers) of a text record read without units that
#: is also a plausible peak in g: such a record is read as m/s² with a warning.
G_LIKE_PEAK = 2.0
#: Largest plausible PGA [m/s²] (5 g): above it a record read without units warns.
MAX_PLAUSIBLE_PGA = 5.0 * G_STANDARD

_SEPARATORS = str.maketrans(",;\t", "   ")


def _lines(path: Path):
    """The file's lines, one at a time (latin-1: every byte is a character)."""
    with open(path, encoding="latin-1", newline=None) as f:
        first = f.readline()
        yield first.removeprefix("\xef\xbb\xbf")  # a UTF-8 byte-order mark, read as latin-1
        yield from f


def _sample_lines(path: Path, comment: str):
    """(line number, stripped line) of every line that is not blank or a comment."""
    for k, line in enumerate(_lines(path), start=1):
        s = line.strip()
        if s and not s.startswith(comment):
            yield k, s


#: What a file of accelerations alone needs (the hint of a two-column reader's error).
_DT_HINT = ("accelerations alone carry no time step: give it (--dt on the command line, dt= "
            "in Python), or write 'time acceleration' lines, or a PEER .AT2 or ESM .ASC "
            "file, whose header gives it")


def _two_numbers(path, k: int, s: str, first: bool = False) -> tuple[float, float] | None:
    """The two numbers of sample line ``k`` (``first``: the file's first sample line); None
    for a text line; ValueError otherwise."""
    parts = re.split(r"[\s,;]+", s)
    try:
        vals = [float(v) for v in parts]
    except ValueError:
        return None
    if len(vals) != 2:
        if len(vals) == 4 and "," in s and "." not in s:
            hint = ": decimal commas? write numbers with a point (0.01, not 0,01)"
        elif len(vals) == 1:
            hint = f": {_DT_HINT}"
        elif first:  # several values a line from the first: accelerations in rows?
            hint = (": if these are accelerations alone, several a line, give their time "
                    "step (--dt, dt= in Python)")
        else:
            hint = ""
        raise ValueError(f"{path}: line {k} has {len(vals)} column(s), expected 2 "
                         f"(time, acceleration){hint}")
    return vals[0], vals[1]


def _diagnose(path, comment: str) -> None:
    """Find the first bad line of a two-column file (the fast parser refused it) and raise
    the error that names it; streams the lines, keeps none."""
    started = False
    for k, s in _sample_lines(path, comment):
        vals = _two_numbers(path, k, s, first=not started)
        if vals is None:
            if started:
                raise ValueError(f"{path}: line {k} is not two numbers: {s[:60]!r}")
            continue  # a header line such as "time acc"
        started = True
        if not all(math.isfinite(v) for v in vals):
            raise ValueError(f"{path}: line {k} holds a value that is not a finite number")
    raise ValueError(f"{path}: cannot be read as two columns (time, acceleration)")


def _line_of_sample(path: Path, comment: str, skip: int, index: int) -> int:
    """Line number of sample ``index`` (0-based) after the ``skip`` header lines."""
    for n, (k, _) in enumerate(_sample_lines(path, comment)):
        if n == index + skip:
            return k
    return -1


#: Time steps a record may have [s] (strong-motion records: 0.001 … 0.05 s).
DT_RANGE = (1e-5, 1.0)


def _check_dt(path, dt: float) -> None:
    lo, hi = DT_RANGE
    if not lo <= dt <= hi:
        raise ValueError(f"{path}: time step {dt:.3g} s is not that of a strong-motion record "
                         f"(it must lie in [{lo:g}, {hi:g}] s): check the time column")


def check_acceleration(path, acc: np.ndarray) -> None:
    """Samples [m/s²] that an acceleration record can hold: |a| <= :data:`MAX_ACCELERATION`
    (ValueError naming the file, the sample and the units to check)."""
    big = np.flatnonzero(np.abs(acc) > MAX_ACCELERATION)
    if big.size:
        k = int(big[0])
        raise ValueError(f"{path}: sample {k} is {float(acc[k]):.3g} m/s², not a plausible "
                         f"ground acceleration (above {MAX_ACCELERATION:.3g} m/s² = 1e5 g): "
                         "check the file and its units")


def read_two_column(path: str | Path, *, units: str = "m/s2", comment: str = "#",
                    rtol: float = 1e-4) -> GroundMotion:
    """Read a two-column text record: time [s] and acceleration (``units``: m/s2, g, cm/s2).

    Columns may be separated by spaces, tabs, commas or semicolons; lines starting with
    ``comment`` are skipped, and so are text lines before the first sample (a header such
    as ``time acc``). Every sample line holds exactly two numbers. The time step must be
    uniform (relative tolerance ``rtol``, for rounding in the file); resample a non-uniform
    record before using it. Every error names the file and the line. At most
    :func:`rockarch.core.limits.max_samples` samples (counted from the lines before they are
    parsed; numpy's C parser keeps the memory at 16 bytes per sample).
    """
    path = Path(path)
    factor = _units_factor(units)
    _check_file(path)
    with open(path, "rb") as f:
        if b"\x00" in f.read(8192):
            raise ValueError(f"{path}: a binary file, not a text record (time, acceleration)")
        f.seek(0)
        n_lines, last = 0, b"\n"
        for chunk in iter(lambda: f.read(1 << 22), b""):
            n_lines, last = n_lines + chunk.count(b"\n"), chunk[-1:]
        n_lines += last != b"\n"  # a last line without its newline
    limit = limits.max_samples()
    if n_lines > limit + min(1000, limit // 100):  # a sample a line (and a few headers)
        raise limits.too_many(f"{path} ({n_lines:,} lines)", n_lines, "samples", limit,
                              "shorten or decimate the record")
    skip, first = 0, None
    for k, s in _sample_lines(path, comment):
        if _two_numbers(path, k, s, first=True) is not None:
            first = k
            break
        skip += 1
        if skip > 1000:
            break
    if first is None:
        raise ValueError(f"{path}: no samples: a record needs at least 2 samples "
                         "(lines 'time acceleration')")
    try:  # numpy's C parser, fed line by line: 16 bytes per sample
        data = np.loadtxt((line.translate(_SEPARATORS) for line in _lines(path)),
                          comments=comment, skiprows=first - 1, ndmin=2, dtype=float)
    except ValueError:
        _diagnose(path, comment)
    if data.shape[1] != 2:
        _diagnose(path, comment)
    if data.shape[0] < 2:
        raise ValueError(f"{path}: a record needs at least 2 samples, found {data.shape[0]}")
    if data.shape[0] > limit:
        raise limits.too_many(str(path), data.shape[0], "samples", limit,
                              "shorten or decimate the record")
    if not np.isfinite(data).all():
        _diagnose(path, comment)
    t, acc = data[:, 0], data[:, 1]
    _check_samples(path, acc)
    dts = np.diff(t)
    back = np.flatnonzero(dts <= 0)
    if back.size:
        k = int(back[0])
        line = _line_of_sample(path, comment, skip, k + 1)
        raise ValueError(f"{path}: time must increase (line {line}: "
                         f"t={t[k + 1]:g} s after t={t[k]:g} s)")
    dt = (t[-1] - t[0]) / (t.size - 1)
    _check_dt(path, dt)
    typical = float(np.median(dts))
    off = np.flatnonzero(np.abs(dts - typical) > rtol * typical)
    if off.size:
        k = int(off[0])
        line = _line_of_sample(path, comment, skip, k + 1)
        raise ValueError(f"{path}: non-uniform time step at line {line} "
                         f"(dt={dts[k]:g} s, elsewhere {typical:g} s); resample to a uniform "
                         "dt first")
    acc = acc * factor
    check_acceleration(path, acc)
    t_uniform = np.arange(t.size) * dt
    meta = {"source": str(path), "dt": dt, "npts": int(t.size), "format": "two-column",
            "units_in_file": units}
    return GroundMotion(t_uniform, acc, path.name, meta)


#: Largest time step [s] given for a single-column record without a warning: strong-motion
#: records are sampled every 0.001-0.05 s (a larger dt was likely meant in other units).
DT_WARN = 0.1


class TimeStepWarning(UserWarning):
    """A time step given for a single-column record above :data:`DT_WARN`."""


def check_time_step(dt) -> float:
    """``dt`` [s] given for a single-column record (:func:`read_single_column`) as a float.

    TypeError if it is not a number; ValueError naming it if it is not finite and > 0 or
    lies outside :data:`DT_RANGE` (dt is in seconds); :class:`TimeStepWarning` above
    :data:`DT_WARN`.
    """
    dt = number("dt", dt)
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt (--dt) must be a finite time step > 0 in seconds, got {show(dt)}")
    lo, hi = DT_RANGE
    if dt > hi:
        raise ValueError(f"dt (--dt) = {show(dt)} s is not the time step of a strong-motion "
                         f"record, sampled every 0.001-0.05 s: dt is in seconds ({show(dt)} "
                         f"ms is dt = {show(dt / 1000)}; a rate of {show(dt)} Hz is dt = "
                         f"{show(1 / dt)})")
    if dt < lo:
        raise ValueError(f"dt (--dt) = {show(dt)} s is not the time step of a strong-motion "
                         f"record, sampled every 0.001-0.05 s: dt is in seconds (at least "
                         f"{lo:g})")
    if dt > DT_WARN:
        warnings.warn(TimeStepWarning(
            f"dt = {show(dt)} s is coarser than the step of a strong-motion record "
            f"(0.001-0.05 s): dt is in seconds"), stacklevel=3)
    return dt


#: Every blank and separator (tab, comma, semicolon, carriage return) of a text record as
#: a blank (bytes.translate).
_BLANKS = bytes.maketrans(b",;\t\r\v\f", b"      ")
#: Bytes counted per chunk by :func:`_values_per_line` (bounds its temporary arrays).
_CHUNK = 1 << 22


def _values_per_line(body: bytes) -> np.ndarray:
    """The number of blank-separated values on each line of ``body`` (blanks and
    separators made spaces; a blank line has none), counted by numpy in chunks of whole
    lines."""
    out = []
    pos = 0
    while pos < len(body):
        end = body.find(b"\n", pos + _CHUNK)
        end = len(body) if end < 0 else end + 1
        b = np.frombuffer(body, np.uint8, count=end - pos, offset=pos)
        gap = b <= 32  # a blank, a newline or another control character
        starts = np.flatnonzero(gap[:-1] & ~gap[1:]) + 1
        if not gap[0]:
            starts = np.r_[0, starts]
        newlines = np.flatnonzero(b == 10)
        lines = newlines.size + int(b[-1] != 10)
        out.append(np.bincount(np.searchsorted(newlines, starts), minlength=lines))
        pos = end
    return np.concatenate(out) if out else np.zeros(0, dtype=np.int64)


def _is_numbers(words: list[bytes]) -> bool:
    """True if every word is a number."""
    try:
        for w in words:
            float(w)
    except ValueError:
        return False
    return True


def _single_column_body(path: Path, comment: str) -> tuple[bytes, int]:
    """The text of a single-column file from its first sample line on, with comments
    removed, separators and line ends made blanks and ``\n`` (line numbers kept), and the
    number of that first line; leading text lines (a header) are skipped."""
    raw = path.read_bytes()
    if b"\x00" in raw[:8192]:
        raise ValueError(f"{path}: a binary file, not a text record (accelerations)")
    raw = raw.removeprefix(b"\xef\xbb\xbf")  # a UTF-8 byte-order mark
    if b"\r" in raw:  # Windows and old Mac line ends, as Python's text files read them
        raw = raw.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
    mark = comment.encode("latin-1")
    pos, k, skipped = 0, 1, 0
    while pos < len(raw):
        end = raw.find(b"\n", pos)
        end = len(raw) if end < 0 else end
        words = raw[pos:end].split(mark, 1)[0].translate(_BLANKS).split()
        if words:
            if _is_numbers(words):
                break
            skipped += 1
            if skipped > 1000:
                raise ValueError(f"{path}: no samples in its first 1000 text lines (a "
                                 "single-column record holds numbers, one or more a line)")
        pos, k = end + 1, k + 1
    body, raw = raw[pos:], b""
    if mark in body:  # a comment line, or a comment after the values of a line
        body = re.sub(re.escape(mark) + rb"[^\n]*", b"", body)
    if b"," in body and b"." not in body and re.search(rb"[eE]", body) is None:
        raise ValueError(f"{path}: commas and no decimal point: decimal commas? write numbers "
                         "with a point (0.01, not 0,01)")
    return body.translate(_BLANKS), k


def _bad_line(path: Path, first: int, comment: str) -> None:
    """Raise the error that names the first line from line ``first`` on that is not
    numbers (the fast parser refused it)."""
    for k, line in enumerate(_lines(path), start=1):
        words = line.split(comment, 1)[0].translate(_SEPARATORS).split()
        if k >= first and words and not _is_numbers(words):
            raise ValueError(f"{path}: line {k} is not numbers: {line.strip()[:60]!r} (a "
                             "single-column record holds only numbers after its header)")
    raise ValueError(f"{path}: cannot be read as numbers (values that touch? separate them "
                     "with blanks)")


def _check_no_time_column(path, values: np.ndarray, width: int, lines: int,
                          last: int) -> None:
    """ValueError for a file of ``lines`` lines of ``width`` values whose first column is a
    time axis: two numbers a line, the first increasing on every line (a two-column file,
    uniform or not), or more, the first increasing by a uniform step. Accelerations do not
    increase over every line of a record (from 3 lines on)."""
    if width < 2 or lines < 3:
        return
    first = values[::width]
    steps = np.diff(first)
    if not np.all(steps > 0):
        return
    lead = ", ".join(f"{v:g}" for v in first[:3])
    if width == 2 and last == 2:
        raise ValueError(f"{path}: every line holds two numbers, the first increasing ({lead}, "
                         "...): a two-column file (time, acceleration), which has its own "
                         "time column: read it without dt (--dt)")
    if np.ptp(steps) <= 1e-4 * float(np.median(steps)):
        raise ValueError(f"{path}: the first value of every line increases by one step "
                         f"({lead}, ...): a time column? a single-column record holds "
                         f"accelerations only ({width} a line here)")


def read_single_column(path: str | Path, dt: float, *, units: str = "m/s2",
                       comment: str = "#") -> GroundMotion:
    """Read a text record of accelerations alone (``units``: m/s2, g, cm/s2) sampled every
    ``dt`` [s].

    Every number of every sample line is one sample, in reading order: one value a line,
    or several (rows of 5 or 8 values, as fixed-width legacy formats write them); sample k
    is at time k·dt. Values may be separated by blanks, tabs, commas or semicolons; text
    lines before the first sample (a header) are skipped, and so is what follows
    ``comment`` on a line. Every sample line holds as many values as the first, the last
    one at most as many; a text line among the samples is an error that names it. A file
    whose every line holds two numbers, the first increasing, is a two-column file (time,
    acceleration: :func:`read_two_column`) and is refused. ``dt`` is checked by
    :func:`check_time_step`. At most :func:`rockarch.core.limits.max_samples` samples
    (counted before they are parsed).
    """
    path = Path(path)
    factor = _units_factor(units)
    dt = check_time_step(dt)
    return _single_column(path, dt, units, factor, comment)


def _single_column(path: Path, dt: float, units: str, factor: float,
                   comment: str) -> GroundMotion:
    """:func:`read_single_column` of a checked ``dt`` and units ``factor``."""
    _check_file(path)
    body, first = _single_column_body(path, comment)
    counts = _values_per_line(body)
    rows = np.flatnonzero(counts)  # the sample lines (index into body's lines)
    if rows.size == 0:
        raise ValueError(f"{path}: no samples: a record needs at least 2 samples (numbers, "
                         "one or more a line)")
    n = int(counts.sum())
    if n > limits.max_samples():  # before the values are parsed
        raise limits.too_many(str(path), n, "samples", limits.max_samples(),
                              "shorten or decimate the record")
    per = counts[rows]
    width = int(per[0])
    odd = np.flatnonzero(per[:-1] != width)
    if odd.size or per[-1] > width:
        j = int(odd[0]) if odd.size else rows.size - 1
        raise ValueError(f"{path}: line {first + int(rows[j])} holds {int(per[j])} value(s), "
                         f"the first sample line (line {first + int(rows[0])}) {width}: every "
                         "sample line holds as many values as the first (the last may hold "
                         "fewer); a header line of numbers (NPTS, DT?) must start with "
                         f"{comment!r}")
    values = _numbers(body)
    del body
    if values is None or values.size != n:
        _bad_line(path, first, comment)
    _check_no_time_column(path, values, width, rows.size, int(per[-1]))
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        k = int(bad[0])
        line = first + int(rows[np.searchsorted(np.cumsum(per), k, side="right")])
        raise ValueError(f"{path}: line {line} holds a value that is not a finite number "
                         f"(sample {k})")
    _check_samples(path, values)
    acc = values * factor
    check_acceleration(path, acc)
    meta = {"source": str(path), "dt": dt, "npts": int(acc.size), "format": "single-column",
            "units_in_file": units}
    return GroundMotion(np.arange(acc.size) * dt, acc, path.name, meta)


def read_record(path: str | Path, *, units: str | None = None,
                dt: float | None = None) -> GroundMotion:
    """Read one ground-motion record (acceleration history) from a file, by its format.

    The format is recognised from the file: ``.AT2`` (or a PEER header under any name) as
    PEER NGA; a file that opens with ``KEY: value`` lines giving NDATA and
    SAMPLING_INTERVAL_S as ESM/ITACA ASCII; one whose first line is ``Origin Time ...`` as
    K-NET / KiK-net ASCII; one whose first line ends with ``(Format v01.20 with 13 text
    lines)`` as COSMOS; anything else as two-column text (time [s], acceleration), or, with
    ``dt``, as single-column text (accelerations alone, one or more a line). See
    docs/sites.md, "Record suites".

    Parameters
    ----------
    path : str or path
        The record file. ``FILE#N``: channel N of a COSMOS file that holds several.
    units : str, optional
        Acceleration units of a text file (two-column or single-column): ``"m/s2"``
        (default), ``"g"``, ``"cm/s2"`` (or ``"gal"``), ``"mm/s2"``. The other formats
        state their own, and ``units`` does not apply to them.
    dt : float, optional
        Time step [s] of a single-column text file: its data lines hold accelerations alone,
        every number one sample in reading order (one a line, or rows of several as legacy
        fixed-width formats write them), sample k at time k·dt; leading text lines (a
        header) and ``#`` comments are skipped. Strong-motion records are sampled every
        0.001-0.05 s; dt is in seconds. The other formats, two-column text included, give
        their own time step, and ``dt`` is refused for them.

    Returns
    -------
    GroundMotion
        Times ``t`` [s] (uniform step) and accelerations ``a`` [m/s²], converted from the
        file's units; ``name`` (file name and, where the header gives them, event and
        station) and ``meta`` (the header's metadata; for text files ``format``
        (``"two-column"`` or ``"single-column"``), ``dt``, ``npts``, ``units_in_file``,
        ``source``).

    Raises
    ------
    TypeError
        If ``path`` is not a path, ``units`` not a string or ``dt`` not a number.
    ValueError
        If the file does not exist, is unreadable or malformed (the message names the file
        and line), has a non-uniform time step, more samples than
        :func:`rockarch.core.limits.max_samples`, unknown ``units``, is an older CSMIP
        ``.V1``/``.V2`` file, or ``#N`` names a channel of a file that is not COSMOS. A
        text file of accelerations alone without ``dt``; a ``dt`` that is not finite and
        > 0 or lies outside :data:`DT_RANGE` (:func:`check_time_step`); a ``dt`` given for
        a file that gives its own time step (``.AT2``, ESM, K-NET, COSMOS, two-column
        text); a text line among the samples of a single-column file.

    Warns
    -----
    UnitsWarning
        A text file read without ``units`` whose peak is at most :data:`G_LIKE_PEAK`
        (plausible in g too) or above :data:`MAX_PLAUSIBLE_PGA` (5 g).
    TimeStepWarning
        A ``dt`` above :data:`DT_WARN` (0.1 s): coarser than a strong-motion record's.

    Examples
    --------
    >>> import rockarch as ra
    >>> from rockarch.motion.records import bundled_record_path
    >>> m = ra.read_record(bundled_record_path(180))
    >>> round(m.pga, 3), round(float(m.t[1] - m.t[0]), 3)
    (2.754, 0.01)

    A file of accelerations alone (here in g, one a line) needs its time step:

    >>> import os, tempfile
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = os.path.join(folder, "elcentro_g.txt")
    ...     np.savetxt(path, m.a / 9.80665)
    ...     s = ra.read_record(path, dt=0.01, units="g")
    >>> s.meta["format"], s.meta["npts"], round(s.pga, 3)
    ('single-column', 5372, 2.754)
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a file path (str or Path), got {type(path).__name__}")
    if units is not None and not isinstance(units, str):
        raise TypeError(f"units must be a string such as 'm/s2', 'g' or 'cm/s2', got "
                        f"{type(units).__name__}")
    if dt is not None:
        dt = check_time_step(dt)
    path, channel = split_channel(path)
    if channel is not None:
        _check_file(path)
        if not is_cosmos(path):
            raise ValueError(f"{path}#{channel}: '#N' picks a channel of a COSMOS file of "
                             f"several, and {path.name} is not a COSMOS file")
        _own_step(path, "COSMOS", dt)
        return read_cosmos(path, channel)
    if path.suffix.lower() == ".at2":
        _own_step(path, "PEER .AT2", dt)
        return read_at2(path)
    _check_file(path)
    for fmt, test, read in (("PEER .AT2", is_at2, read_at2), ("ESM", is_esm, read_esm),
                            ("K-NET", is_knet, read_knet), ("COSMOS", is_cosmos, read_cosmos)):
        if test(path):  # a PEER file under another name too
            _own_step(path, fmt, dt)
            return read(path)
    if path.suffix.lower() in (".v1", ".v2"):
        raise ValueError(f"{path}: not a COSMOS-format file (its first line should end with "
                         "'(Format v01.20 with 13 text lines)'); the older CSMIP .V1/.V2 format "
                         "is not read: download the COSMOS format (V2c) from CESMD")
    if dt is None:
        motion = read_two_column(path, units=units or "m/s2")
    else:
        unit = units or "m/s2"
        motion = _single_column(path, dt, unit, _units_factor(unit), "#")
    if units is None and motion.pga <= G_LIKE_PEAK:
        warnings.warn(UnitsWarning(
            f"{path.name}: read as m/s² (no units given), but its peak {motion.pga:.3g} is "
            f"also a plausible PGA in g: give --units m/s2 or --units g (units= in Python)"),
            stacklevel=2)
    elif units is None and motion.pga > MAX_PLAUSIBLE_PGA:
        warnings.warn(UnitsWarning(
            f"{path.name}: read as m/s² (no units given), its PGA {motion.pga:.4g} m/s² = "
            f"{motion.pga / G_STANDARD:.3g} g ({g_label(G_STANDARD)}) is not plausible: wrong "
            "units? (--units cm/s2, mm/s2 or g)"), stacklevel=2)
    return motion


def _own_step(path: Path, fmt: str, dt: float | None) -> None:
    """ValueError if ``dt`` is given for a ``fmt`` file, whose header gives its time step."""
    if dt is not None:
        raise ValueError(f"{path}: a {fmt} file gives its own time step (in its header); dt "
                         "(--dt) is for text files of accelerations alone and does not apply "
                         "to it: leave it out")


class UnitsWarning(UserWarning):
    """A text record read without units whose peak is also plausible in g (or not plausible
    in m/s²)."""


_BUNDLED = {180: "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", 270: "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"}


def bundled_record_path(component: int = 180) -> Path:
    """Path of a bundled El Centro 1940 component (180 or 270), see PROVENANCE.md."""
    if component not in _BUNDLED:
        raise ValueError(f"bundled El Centro components are 180 and 270, got {show(component)}")
    return Path(str(resources.files("rockarch.motion") / "data" / _BUNDLED[component]))


def el_centro(component: int = 180) -> GroundMotion:
    """The bundled demo record: El Centro 1940 (Imperial Valley-02), one horizontal component.

    PEER NGA-West2 RSN6, El Centro Array #9, read from the package's ``.AT2`` file (see
    ``rockarch/motion/data/PROVENANCE.md`` for its source and citation); no download.

    Parameters
    ----------
    component : int
        180 (default: the 180° component, PGA 2.754 m/s² = 0.281 g) or 270 (PGA 2.07 m/s²
        = 0.211 g).

    Returns
    -------
    GroundMotion
        Acceleration [m/s²] sampled every 0.01 s over 53.7 s (180) or 53.5 s (270), named
        after the file, the event and the station.

    Raises
    ------
    ValueError
        If ``component`` is not 180 or 270.

    Examples
    --------
    >>> import rockarch as ra
    >>> m = ra.el_centro(270)
    >>> round(m.pga / 9.80665, 3), round(float(m.t[-1]), 1)
    (0.211, 53.5)
    """
    return read_at2(bundled_record_path(component))
