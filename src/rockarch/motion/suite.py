"""Record suites: a folder (or list) of strong-motion records with their metadata.

A suite is what an engineer downloads from the PEER NGA-West2 database: ``.AT2`` files and a
``_SearchResults.csv`` listing each record's RSN, event, station, magnitude, distance, Vs30
and scale factor. :func:`read_suite` reads such a folder (or any list of ``.AT2`` files and
two-column or single-column text files; the csv is optional) into a :class:`Suite` of
:class:`SuiteRecord`. Without the csv, event, station and component come from the ``.AT2``
header line ``EVENT, DATE, STATION, COMPONENT``. Format and matching rules: docs/sites.md.
"""

from __future__ import annotations

import collections
import csv
import io
import math
import os
import re
import warnings
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from rockarch.core import limits
from rockarch.core.constants import G_STANDARD, g_label
from rockarch.core.paths import atomic_write
from rockarch.motion import intensity
from rockarch.motion.records import (
    G_LIKE_PEAK,
    TimeStepWarning,
    UnitsWarning,
    bundled_record_path,
    check_time_step,
    is_cosmos,
    read_cosmos_channels,
    read_record,
    split_channel,
)
from rockarch.motion.signals import GroundMotion
from rockarch.motion.velocity_pulse import baker_pulse, check_method

#: File suffixes read from a folder as text records (``.AT2`` is always read): two-column
#: (time, acceleration), or single-column (accelerations alone) when a time step is given.
TWO_COLUMN_SUFFIXES = (".txt", ".dat", ".acc", ".csv", ".tsv")
#: Suffix of ESM / ITACA ASCII files, read from a folder too (any file that opens with
#: ``KEY: value`` header lines, EVENT_NAME, NDATA or SAMPLING_INTERVAL_S among them, is read
#: as ESM, whatever its suffix).
ESM_SUFFIXES = (".asc",)
#: Suffixes of K-NET (.NS .EW .UD) and KiK-net (1: borehole, 2: surface) ASCII files (any
#: file whose first line is ``Origin Time ...`` is read as K-NET, whatever its suffix).
KNET_SUFFIXES = tuple(f".{c}{n}" for c in ("ns", "ew", "ud") for n in ("", "1", "2"))
#: Suffixes of COSMOS-format files (CESMD, USGS; any file whose first line ends with
#: ``(Format v01.20 with 13 text lines)`` is read as COSMOS, whatever its suffix).
COSMOS_SUFFIXES = (".v1", ".v2", ".v1c", ".v2c")
#: Name of the NGA-West2 metadata file in a downloaded folder.
SEARCH_RESULTS = "_SearchResults.csv"

# csv column -> field: first header (lower case, spaces squeezed) that starts with a key wins
_COLUMNS = {
    "rsn": ("record sequence number", "rsn"),
    "scale_factor": ("scale factor",),
    "event": ("earthquake name", "event"),
    "year": ("year",),
    "station": ("station name", "station"),
    "magnitude": ("magnitude",),
    "mechanism": ("mechanism",),
    "rjb": ("rjb",),
    "rrup": ("rrup",),
    "vs30": ("vs30",),
    "h1": ("horizontal-1 acc. filename", "horizontal-1"),
    "h2": ("horizontal-2 acc. filename", "horizontal-2"),
    "v": ("vertical acc. filename", "vertical"),
}
_FLOATS = ("scale_factor", "magnitude", "rjb", "rrup", "vs30")
_RSN_NAME = re.compile(r"^RSN(\d+)[_\-]", re.IGNORECASE)


@dataclass(frozen=True)
class SuiteRecord:
    """One record of a suite and its metadata (``None`` where unknown).

    ``motion`` is in m/s²; if ``scaled`` it is the file's record times ``scale_factor``.
    ``rrup``, ``rjb`` in km, ``vs30`` in m/s.
    """

    name: str
    motion: GroundMotion
    path: str | None = None
    rsn: int | None = None  # NGA-West2 record sequence number
    event: str | None = None  # earthquake name
    year: int | None = None
    station: str | None = None
    component: str | None = None  # e.g. "180" or "H1"
    magnitude: float | None = None  # Mw (NGA csv, ESM, COSMOS); JMA's Mj for K-NET files
    mechanism: str | None = None  # fault mechanism
    rjb: float | None = None  # Joyner–Boore distance [km]
    rrup: float | None = None  # rupture distance [km]
    vs30: float | None = None  # time-averaged shear-wave velocity of the top 30 m [m/s]
    scale_factor: float | None = None
    scaled: bool = False

    @property
    def dt(self) -> float:
        """Sampling step [s] (mean knot spacing)."""
        t = self.motion.t
        return float((t[-1] - t[0]) / (t.size - 1))

    @property
    def duration(self) -> float:
        """Duration of the record [s]."""
        return float(self.motion.t[-1] - self.motion.t[0])

    def metadata(self) -> dict:
        """Metadata as a plain dict (no motion)."""
        return {"name": self.name, "path": self.path, "rsn": self.rsn, "event": self.event,
                "year": self.year, "station": self.station, "component": self.component,
                "magnitude": self.magnitude, "mechanism": self.mechanism, "rjb": self.rjb,
                "rrup": self.rrup, "vs30": self.vs30, "scale_factor": self.scale_factor,
                "scaled": self.scaled, "dt": self.dt, "duration": self.duration,
                "npts": int(self.motion.t.size)}


@dataclass(frozen=True)
class Suite:
    """An ordered set of records with metadata; ``csv`` is the metadata file used, if any."""

    records: tuple[SuiteRecord, ...]
    csv: str | None = None
    notes: tuple[str, ...] = field(default=(), compare=False)

    def __post_init__(self) -> None:
        recs = tuple(self.records)
        if not recs:
            raise ValueError("a suite needs at least one record")
        object.__setattr__(self, "records", recs)

    def __len__(self) -> int:
        return len(self.records)

    def __iter__(self) -> Iterator[SuiteRecord]:
        return iter(self.records)

    def __getitem__(self, k: int) -> SuiteRecord:
        return self.records[k]

    @property
    def names(self) -> list[str]:
        """The records' names (file names for records read from files)."""
        return [r.name for r in self.records]

    @property
    def motions(self) -> list[GroundMotion]:
        """The records' ground motions [m/s²]."""
        return [r.motion for r in self.records]

    def scaled(self) -> Suite:
        """The suite with each record multiplied by its csv scale factor (records without
        one, or already scaled, are unchanged)."""
        out = []
        for r in self.records:
            if r.scaled or r.scale_factor is None:
                out.append(r)
            else:
                out.append(replace(r, motion=r.motion.scaled(r.scale_factor), scaled=True))
        return replace(self, records=tuple(out))


def from_motions(motions: Sequence[GroundMotion], names: Sequence[str] | None = None
                 ) -> Suite:
    """A suite of in-memory motions (synthetic or pulses), named by ``names`` or by the
    motions' own names."""
    motions = list(motions)
    names = [m.name for m in motions] if names is None else list(names)
    if len(names) != len(motions):
        raise ValueError(f"{len(names)} names for {len(motions)} motions")
    return Suite(tuple(SuiteRecord(name=n, motion=m) for n, m in zip(names, motions,
                                                                       strict=True)))


def as_motions(records, names=None, what: str = "records"
               ) -> tuple[tuple[GroundMotion, ...], tuple[str, ...] | None]:
    """(motions, names) of the records a function takes: a :class:`Suite` (its motions,
    and its names unless ``names`` are given), a sequence of :class:`GroundMotion`, or one
    GroundMotion. TypeError for anything else, files included (read them first)."""
    if isinstance(records, GroundMotion):
        records = [records]
    if isinstance(records, Suite):
        return tuple(records.motions), tuple(records.names if names is None else names)
    path = (str, bytes, os.PathLike)
    if isinstance(records, path) or not hasattr(records, "__iter__"):
        bad = records
    else:
        records = tuple(records)
        bad = next((m for m in records if not isinstance(m, GroundMotion)), None)
    if bad is not None:
        hint = (": read the files first, ra.read_suite(paths)" if isinstance(bad, path) else
                ": a Suite's records are in suite.motions" if isinstance(bad, SuiteRecord)
                else "")
        raise TypeError(f"{what} must be a Suite (ra.read_suite) or a list of GroundMotion,"
                        f" got {type(bad).__name__}{hint}")
    return records, None if names is None else tuple(names)


# --- files and folders ------------------------------------------------------------------------

def _is_record_file(p: Path) -> bool:
    name = p.name.lower()
    if name.startswith(("_", ".")) or "searchresults" in name or name.startswith("readme"):
        return False
    return p.suffix.lower() in (".at2", *TWO_COLUMN_SUFFIXES, *ESM_SUFFIXES, *KNET_SUFFIXES,
                                *COSMOS_SUFFIXES)


def check_distinct(suite) -> None:
    """ValueError if two records of ``suite`` are one record (the same samples up to units or
    scale, :meth:`GroundMotion.shape_fingerprint`): a suite scales every record to its own
    PGA, so a record given twice would count twice in a site's percentile or a fragility."""
    seen: dict = {}
    for rec in suite:
        first = seen.setdefault(rec.motion.shape_fingerprint(), rec.name)
        if first != rec.name:  # names: two channels of one COSMOS file share its path
            raise ValueError(f"{rec.name}: the same record as {first} (the same samples, "
                             "up to units or scale); a suite counts each record once: "
                             "leave one out")


def _bundled_hint() -> str:
    """Where the bundled El Centro records are, for an error about a missing path."""
    folder = bundled_record_path().parent
    try:
        folder = folder.relative_to(Path.cwd())
    except ValueError:
        pass
    return f" (the bundled El Centro 1940 records are in {folder}{os.sep})"


def record_files(sources) -> tuple[list[Path], list[Path]]:
    """Expand files and folders into record files and the metadata csv files found.

    A folder contributes its ``.AT2`` files, its ESM/ITACA ``.ASC`` files, its K-NET /
    KiK-net files (:data:`KNET_SUFFIXES`), its COSMOS files (:data:`COSMOS_SUFFIXES`) and
    its text files (two-column or single-column, suffixes :data:`TWO_COLUMN_SUFFIXES`),
    those not starting with ``_``, sorted by name, and its ``_SearchResults.csv`` if
    present. Files given explicitly are taken as they are (a file named
    ``*SearchResults*.csv`` is taken as metadata).
    """
    files: list[Path] = []
    metas: list[Path] = []
    if isinstance(sources, (str, os.PathLike)):
        sources = [sources]
    elif not isinstance(sources, (list, tuple)):
        raise TypeError(f"sources must be a path or a list of paths, got "
                        f"{type(sources).__name__}")
    for src in sources:
        if not isinstance(src, (str, os.PathLike)):
            raise TypeError(f"sources must hold paths (str or Path), got "
                            f"{type(src).__name__}")
        p = Path(src)
        if p.is_dir():
            found = sorted((q for q in p.iterdir() if q.is_file() and _is_record_file(q)),
                           key=lambda q: q.name)
            if not found:
                raise ValueError(f"{p}: folder holds no record (.AT2, .ASC, K-NET .NS/.EW, "
                                 f"COSMOS .V2c or text "
                                 f"{'/'.join(TWO_COLUMN_SUFFIXES)})")
            files.extend(found)
            metas.extend(q for q in sorted(p.iterdir())
                         if q.is_file() and q.name.lower().endswith("searchresults.csv"))
        elif p.is_file():
            (metas if "searchresults" in p.name.lower() else files).append(p)
        elif split_channel(p)[0].is_file():  # FILE#N: one channel of a COSMOS file
            files.append(p)
        else:
            raise ValueError(f"{p}: no such file or folder{_bundled_hint()}")
    if not files:
        raise ValueError("give at least one record (file or folder of records)")
    limits.check_count("the suite", len(files), "records", "give fewer records")
    counts = collections.Counter(f.name for f in files)
    dup = sorted(n for n, c in counts.items() if c > 1)
    if dup:
        same = [f for f in files if f.name == dup[0]]
        if len({f.resolve() for f in same}) == 1:
            raise ValueError(f"{same[0]}: the same record is given twice (a file, or a file "
                             "inside a folder also given): give each record once")
        raise ValueError(f"two records share the file name {dup[0]!r}: rename one")
    return files, metas


# --- NGA-West2 _SearchResults.csv -------------------------------------------------------------

def _norm(text: str) -> str:
    return " ".join(text.strip().lower().split())


def _number(path, line: int, col: str, text: str, kind=float):
    s = text.strip()
    if s in ("", "-", "--", "---", "nan", "n/a"):
        return None
    try:
        v = kind(float(s)) if kind is int else kind(s)
    except (ValueError, OverflowError):  # OverflowError: int(inf)
        raise ValueError(f"{path}: line {line}: column {col!r} should be a number, found "
                         f"{s!r}") from None
    if isinstance(v, float) and not math.isfinite(v):
        raise ValueError(f"{path}: line {line}: column {col!r} is not finite ({s!r})")
    return v


def read_search_results(path: str | Path) -> list[dict]:
    """Rows of the metadata table of an NGA-West2 ``_SearchResults.csv``.

    The file starts with a free-text header block and holds several tables; the metadata
    table is the one whose header row names a ``Record Sequence Number`` (or ``RSN``)
    column; it ends at the first blank line or the first row whose RSN is not an integer.
    Each row becomes a dict with keys ``rsn``, ``scale_factor``, ``event``, ``year``,
    ``station``, ``magnitude``, ``mechanism``, ``rjb``, ``rrup``, ``vs30``, ``h1``, ``h2``,
    ``v`` (file names; absent columns give ``None``).
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="latin-1")
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    rows = list(csv.reader(io.StringIO(text), skipinitialspace=True))  # blank line: []
    start = None
    for k, row in enumerate(rows):
        cells = [_norm(c) for c in row]
        if any(c in ("record sequence number", "rsn") for c in cells):
            start = k
            break
    if start is None:
        raise ValueError(f"{path}: not an NGA-West2 search-results file (no header row with "
                         "a 'Record Sequence Number' column)")
    header = [_norm(c) for c in rows[start]]
    index = {}
    for key, names in _COLUMNS.items():
        for j, h in enumerate(header):
            if any(h.startswith(n) for n in names):
                index[key] = j
                break
    if "rsn" not in index:  # pragma: no cover - guaranteed by the header search
        raise ValueError(f"{path}: no 'Record Sequence Number' column")
    out = []
    line_of = [k + 1 for k in range(len(rows))]  # PEER cells hold no newlines
    for k in range(start + 1, len(rows)):
        row = rows[k]
        if not row or all(not c.strip() for c in row):
            break
        rsn_text = row[index["rsn"]].strip() if index["rsn"] < len(row) else ""
        if not re.fullmatch(r"\d+", rsn_text):
            break
        if len(row) < len(header) - 1:
            raise ValueError(f"{path}: line {line_of[k]}: {len(row)} columns, the header has "
                             f"{len(header)} (truncated row?)")
        rec = {}
        for key in _COLUMNS:
            j = index.get(key)
            cell = row[j] if j is not None and j < len(row) else ""
            if key in _FLOATS:
                rec[key] = _number(path, line_of[k], header[j] if j is not None else key, cell)
            elif key in ("rsn", "year"):
                rec[key] = _number(path, line_of[k], key, cell, int)
            else:
                s = cell.strip().strip("\\/")
                rec[key] = None if not s or set(s) <= {"-"} else s
        if rec["scale_factor"] is not None and rec["scale_factor"] <= 0:
            raise ValueError(f"{path}: line {line_of[k]}: scale factor must be > 0, found "
                             f"{rec['scale_factor']}")
        out.append(rec)
    if not out:
        raise ValueError(f"{path}: the metadata table (line {line_of[start]}) has no record "
                         "rows")
    return out


def _match(name: str, rows: list[dict]) -> tuple[dict | None, str | None]:
    """The csv row of a record file and its component (H1, H2, V): by file name, then RSN."""
    low = name.lower()
    stem = Path(low).stem
    for row in rows:
        for comp in ("h1", "h2", "v"):
            fname = row.get(comp)
            if fname and Path(fname.lower()).name == low:
                return row, comp.upper()
    m = _RSN_NAME.match(name)
    if m is None:
        return None, None
    rsn = int(m.group(1))
    cands = [r for r in rows if r["rsn"] == rsn]
    if not cands:
        return None, None
    row = cands[0]
    for comp in ("h1", "h2", "v"):  # a renamed file whose stem extends the csv's stem
        fname = row.get(comp)
        if fname and stem.startswith(Path(fname.lower()).stem):
            return row, comp.upper()
    comp = {"hor1": "H1", "hor2": "H2", "up": "V", "ver": "V"}
    for key, val in comp.items():
        if stem.endswith(f"-{key}") or stem.endswith(f"_{key}"):
            return row, val
    return row, None


def _esm_number(text: str | None) -> float | None:
    """A finite number of an ESM header value; None for an empty or unknown one."""
    try:
        v = float(text)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def _header_fields(motion: GroundMotion) -> dict:
    """Event, year, station, component from an NGA ``.AT2`` title line
    ``EVENT, M/D/YYYY, STATION, COMPONENT``, or from an ESM header (EVENT_NAME,
    EVENT_DATE_YYYYMMDD, STATION_NAME or STATION_CODE, STREAM, MAGNITUDE_W, VS30_M/S), or
    from a K-NET header (the origin time names the event; Mag. is JMA's magnitude), or from
    a COSMOS header (its second line names the event; Mw from its third)."""
    if motion.meta.get("format") == "COSMOS":
        m = motion.meta
        return {"event": m.get("title") or None, "year": m.get("year"),
                "station": m.get("station"), "component": m.get("component"),
                "magnitude": m.get("magnitude")}
    if motion.meta.get("format") == "K-NET":
        h = motion.meta.get("header", {})
        origin = h.get("origintime", "")
        return {"event": origin or None,
                "year": int(origin[:4]) if origin[:4].isdigit() else None,
                "station": h.get("stationcode") or None,
                "component": motion.meta.get("component") or None,
                "magnitude": _esm_number(h.get("mag"))}
    if motion.meta.get("format") == "ESM":
        h = motion.meta.get("header", {})
        date = h.get("EVENT_DATE_YYYYMMDD", "")
        return {"event": h.get("EVENT_NAME") or None,
                "year": int(date[:4]) if date[:4].isdigit() else None,
                "station": h.get("STATION_NAME") or h.get("STATION_CODE") or None,
                "component": h.get("STREAM") or None,
                "magnitude": _esm_number(h.get("MAGNITUDE_W")),
                "vs30": _esm_number(h.get("VS30_M/S"))}
    title = motion.meta.get("title") if motion.meta.get("format") == "AT2" else None
    if not title:
        return {}
    parts = [p.strip() for p in title.split(",")]
    if len(parts) < 4:
        return {"event": title.strip() or None}
    year = re.search(r"(\d{4})\s*$", parts[1])
    return {"event": parts[0] or None, "year": int(year.group(1)) if year else None,
            "station": ", ".join(parts[2:-1]) or None, "component": parts[-1] or None}


#: A record whose PGA lies outside this range [m/s²] has its units wrong (site-oas: an
#: error; suites: a note, printed as a warning by the CLI).
PGA_RANGE = (1e-4 * G_STANDARD, 5.0 * G_STANDARD)


#: Component names (AT2 header, K-NET's U-D, lower case) of vertical records; a SEED
#: channel code (three letters, ESM's STREAM such as HNZ) is vertical when it ends in Z.
VERTICAL = ("up", "dwn", "dn", "down", "v", "ver", "vert", "vertical", "z", "u-d", "ud")


def _is_vertical(component) -> bool:
    c = str(component or "").strip().lower()
    return c in VERTICAL or (len(c) == 3 and c.isalpha() and c[2] == "z")


def _read_all(files, units, dt, g_like: list):
    """(file, record name, motion) of every record of ``files``: one per file, one per
    acceleration channel of a COSMOS file that holds several (named ``FILE#N``). A text
    file read without units whose peak is plausible in g goes into ``g_like``; ``dt``
    (checked by the caller, who warned of a coarse one once) goes to every file."""
    for f in files:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", UnitsWarning)
            if f.is_file() and is_cosmos(f) and dt is None:
                motions = read_cosmos_channels(f)
            else:  # with dt, read_record refuses a COSMOS file (it gives its own step)
                motions = (read_record(f, units=units, dt=dt),)
        for w in caught:
            if issubclass(w.category, UnitsWarning):
                if motions[0].pga <= G_LIKE_PEAK:  # an implausible PGA has its own note
                    g_like.append(f.name)
            elif issubclass(w.category, TimeStepWarning):
                continue  # said once, by read_suite
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        base = split_channel(f)[0]
        for motion in motions:
            n = motion.meta.get("channels", 1)
            yield base, (f"{base.name}#{motion.meta['channel']}" if n > 1 else f.name), motion


def read_suite(sources, *, units: str | None = None, apply_scale: bool = False,
               search_results: str | Path | None = None, vertical: bool = False,
               dt: float | None = None) -> Suite:
    """Read a suite of ground-motion records from files and folders (see :func:`record_files`).

    Parameters
    ----------
    sources : path or list of paths
        Record files (``.AT2``, ESM ``.ASC``, K-NET, COSMOS, two-column or, with ``dt``,
        single-column text) and/or folders of them. A COSMOS file of several channels
        gives one record per acceleration channel, named ``FILE#1``, ``FILE#2``, ...;
        ``FILE#N`` given as a source gives channel N.
    units : str, optional
        Units of text records, two-column or single-column (m/s2 by default; the other
        formats state their own).
    apply_scale : bool
        Multiply each record by the scale factor of its csv row.
    search_results : path, optional
        The NGA-West2 metadata csv; by default the ``_SearchResults.csv`` found in a folder
        given in ``sources`` (at most one).
    vertical : bool
        Keep vertical components (csv component V, or an ``.AT2`` header component such as
        ``UP``); by default they are left out and listed in ``notes`` (rocking structures
        are assessed under horizontal ground motion). KiK-net borehole records (a motion
        at depth) are left out and listed in ``notes`` too.
    dt : float, optional
        Time step [s] of single-column text records (accelerations alone, one or more a
        line: :func:`rockarch.motion.records.read_record`), given to every record file: a
        folder of such files, all sampled at ``dt``. A file that gives its own time step
        (``.AT2``, ESM, K-NET, COSMOS, two-column text) is then an error.

    Returns
    -------
    Suite
        The records in file-name order (``suite.names``, ``suite.motions`` in m/s², and per
        record ``suite[k]`` its path and metadata: event, station, component, magnitude,
        rrup [km], vs30 [m/s], ...), and ``suite.notes``: records left out or suspicious.

    Raises
    ------
    TypeError
        If ``dt`` is not a number.
    ValueError
        If a source does not exist or holds no record, a record cannot be read (see
        :func:`rockarch.motion.records.read_record`), ``dt`` is not a time step in seconds
        or is given for a file with its own, several search-results files are found, or
        ``apply_scale`` has no csv or a record without a csv row.

    Notes
    -----
    Records without a csv row keep the metadata of their ``.AT2`` header; with
    ``apply_scale`` and a csv, a record missing from the csv is an error (its scale is
    unknown). A record missing from the csv or with an implausible PGA (outside
    :data:`PGA_RANGE`: wrong units?) is listed in ``notes``.
    """
    if dt is not None:
        dt = check_time_step(dt)  # before any file; a coarse dt warns once, not per file
    files, metas = record_files(sources)
    if search_results is not None:
        metas = [Path(search_results)]
        if not metas[0].is_file():
            raise ValueError(f"{search_results}: no such file")
    if len(metas) > 1:
        raise ValueError(f"several search-results files ({', '.join(map(str, metas))}): "
                         "give one with --search-results")
    rows = read_search_results(metas[0]) if metas else []
    if apply_scale and not rows:
        raise ValueError("--apply-scale needs an NGA-West2 _SearchResults.csv (none found)")
    records, notes, g_like, seen = [], [], [], set()
    text = "two-column" if dt is None else "single-column"
    total = 0
    for f, name, motion in _read_all(files, units, dt, g_like):
        total += motion.t.size
        if total > limits.max_suite_samples():  # before the next record is read
            raise limits.too_many(f"the suite (up to {name})", total, "suite_samples",
                                  limits.max_suite_samples(), "give fewer or shorter records")
        fields = _header_fields(motion)
        row, comp = _match(name, rows) if rows else (None, None)
        if row is not None:
            fields.update({k: row[k] for k in ("rsn", "event", "year", "station", "magnitude",
                                               "mechanism", "rjb", "rrup", "vs30",
                                               "scale_factor") if row[k] is not None})
            fields["component"] = fields.get("component") or comp
        elif rows:
            if apply_scale:
                raise ValueError(f"{name}: not listed in {metas[0].name} (no RSN match), so "
                                 "its scale factor is unknown")
            notes.append(f"{name}: not listed in {metas[0].name}")
        if not vertical and (comp == "V" or _is_vertical(fields.get("component"))):
            notes.append(f"{name}: vertical component left out (--vertical keeps it)")
            continue
        if motion.meta.get("sensor") == "borehole":
            notes.append(f"{name}: KiK-net borehole sensor left out (a motion at depth, not "
                         "the ground surface's: its .NS2/.EW2 files are)")
            continue
        m = _RSN_NAME.match(name)
        if "rsn" not in fields and m:
            fields["rsn"] = int(m.group(1))
        if name in seen:
            raise ValueError(f"{name}: the same record is given twice (a COSMOS file and its "
                             "channel FILE#N): give each record once")
        rec = SuiteRecord(name=name, motion=motion, path=str(f), **fields)
        records.append(rec)
        seen.add(name)
        lo, hi = PGA_RANGE
        if not lo <= motion.pga <= hi:
            notes.append(f"{name}: PGA = {motion.pga / G_STANDARD:.3g} g "
                         f"({g_label(G_STANDARD)}) is not plausible: wrong units? ({text} "
                         "files: --units g, m/s2 or cm/s2)")
    if g_like:
        notes.append(f"{len(g_like)} {text} record(s) read as m/s² without --units have "
                     f"peaks of at most {G_LIKE_PEAK:g}, plausible in g too ({g_like[0]}"
                     f"{', ...' if len(g_like) > 1 else ''}): give --units m/s2 or --units g")
    if not records:
        if any("borehole" in n for n in notes):
            raise ValueError("every record is a vertical component or a KiK-net borehole "
                             "sensor's: give the surface sensor's .NS2/.EW2 files")
        raise ValueError("every record is a vertical component: give --vertical to use them")
    suite = Suite(tuple(records), csv=str(metas[0]) if metas else None, notes=tuple(notes))
    return suite.scaled() if apply_scale else suite


def describe(suite: Suite, periods: Sequence[float] | None = None,
             damping: float | None = None, pulse_method: str = "2007") -> list[dict]:
    """Metadata and intensity measures of every record (``rockarch records info``): one dict
    per record, :meth:`SuiteRecord.metadata` plus the fields of
    :class:`rockarch.motion.intensity.IntensityMeasures` (``sa`` aligned with ``periods``) and the
    velocity-pulse classification of ``pulse_method`` (Baker 2007 or Shahi & Baker 2014,
    :mod:`rockarch.motion.velocity_pulse`): ``pulse_method``, ``pulse_indicator``, ``tp``
    [s], ``pulse_class`` (the indicator's class), the flags ``pulse_late`` and
    ``pulse_low_pgv``, and ``pulse_like`` (the method's full criterion)."""

    per = intensity.PERIODS if periods is None else periods
    zeta = intensity.DAMPING if damping is None else damping
    method = check_method(pulse_method)
    out = []
    for rec in suite:
        d = rec.metadata()
        d.update(intensity.measures(rec.motion, per, zeta).to_dict())
        try:
            pulse = baker_pulse(rec.motion, method=method).to_dict()
        except ValueError:  # a record shorter than the shortest pulse period, or PGV = 0
            pulse = {"pulse_indicator": None, "tp": None, "pulse_like": None,
                     "classification": "-", "late": None, "low_pgv": None}
        d.update(pulse_method=method, pulse_indicator=pulse["pulse_indicator"],
                 tp=pulse["tp"], pulse_class=pulse["classification"],
                 pulse_late=pulse["late"], pulse_low_pgv=pulse["low_pgv"],
                 pulse_like=pulse["pulse_like"])
        out.append(d)
    return out


def write_at2(path: str | Path, motion: GroundMotion, *, event: str = "", date: str = "",
              station: str = "", component: str = "") -> Path:
    """Write a uniformly sampled motion as a PEER-layout ``.AT2`` file (units of g, 5
    values a line, 7 significant digits), readable by :func:`rockarch.motion.records.read_at2`.
    The title line is ``EVENT, DATE, STATION, COMPONENT`` as in NGA-West2 files."""
    t = np.asarray(motion.t)
    dt = float((t[-1] - t[0]) / (t.size - 1))
    if abs(t[0]) > 1e-12 or np.any(np.abs(np.diff(t) - dt) > 1e-9 * max(dt, 1.0)):
        raise ValueError(f"{motion.name}: only a uniformly sampled motion starting at t = 0 "
                         "can be written as .AT2")
    vals = np.asarray(motion.a) / G_STANDARD
    rows = [" ".join(f"{v:15.7E}" for v in vals[k:k + 5]) for k in range(0, vals.size, 5)]
    for name, text in (("event", event), ("station", station), ("component", component)):
        if "," in text or "\n" in text:
            raise ValueError(f"{name} may not contain commas or newlines: {text!r}")
    lines = ["ROCKARCH RECORD (PEER NGA .AT2 LAYOUT)",
             f"{event}, {date}, {station}, {component}",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS={vals.size:7d}, DT={dt:10.7f} SEC", *rows]

    text = "\n".join(lines) + "\n"
    return atomic_write(Path(path), lambda tmp: tmp.write_text(text, encoding="latin-1"))
