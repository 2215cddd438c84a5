"""Assemblies read from a JSON file (``--assembly FILE.json``, docs/theory.md §10).

The file is one JSON object::

    {
      "name": "two blocks",                      (optional)
      "friction": 0.6,                           (optional: every contact; absent: no sliding)
      "blocks": [                                (required: convex polygons, metres)
        {"polygon": [[0, 0], [1, 0], [1, 2], [0, 2]], "density": 2400, "name": "base"},
        {"polygon": [[0.2, 2], [0.8, 2], [0.8, 3], [0.2, 3]]}
      ],
      "supports": [[[x, y], ...]],               (optional: polygons fixed to the ground)
      "contacts": [                              (optional: the contact pairs; default every
        {"blocks": [0, 1], "friction": 0.4},      coincident face; -1 = the ground or a
        {"blocks": [-1, 0]}                       support)
      ]
    }

Every block needs a face on the ground (y = 0), on a support or on another block; density
defaults to 1 (only ratios matter).
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np

from rockarch.core import limits
from rockarch.core.constants import G
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.builders import friction_value, from_polygons
from rockarch.motion.records import UnitsWarning

#: Largest size of an assembly file per block allowed by the block limit (a polygon of
#: hundreds of vertices).
MAX_BYTES_PER_BLOCK = 20_000
#: Extent [m] of a plausible structure (a laboratory model to a viaduct): outside it an
#: assembly file's coordinates are probably not in metres, and reading it warns.
PLAUSIBLE_SIZE = (1e-3, 1e3)
#: Largest plausible single block [m] (the tallest monolithic obelisks are ~30 m): a larger
#: one is most likely a block given in millimetres, in a structure of plausible extent.
PLAUSIBLE_BLOCK = 50.0

#: Densities a file may give (kg/m³ or any unit: only their ratios matter); outside, the
#: masses would leave the range of the contact solver's regularisation and tolerances.
DENSITY_RANGE = (1e-6, 1e6)
_TOP = {"name", "friction", "blocks", "supports", "contacts"}
_BLOCK = {"polygon", "density", "name"}
_CONTACT = {"blocks", "friction"}


def _keys(obj, allowed: set, where: str) -> dict:
    if not isinstance(obj, dict):
        raise ValueError(f"{where} must be a JSON object")
    extra = sorted(set(obj) - allowed)
    if extra:
        raise ValueError(f"{where}: unknown key(s) {', '.join(map(repr, extra))} (allowed: "
                         f"{', '.join(sorted(allowed))})")
    return obj


def assembly_from_dict(data: dict, *, mu=None, g: float = G, source: str = "assembly"
                       ) -> Assembly:
    """The :class:`Assembly` described by ``data`` (the JSON schema in the module docstring).

    ``mu`` (the CLI's --friction) replaces the file's ``friction``; a contact's own friction
    wins over both.
    """
    _keys(data, _TOP, source)
    blocks = data.get("blocks")
    if not isinstance(blocks, list) or not blocks:
        raise ValueError(f"{source}: 'blocks' must be a non-empty list of blocks")
    limits.check_count(source, len(blocks), "blocks", "use fewer blocks")
    polys, dens, names = [], [], []
    for i, b in enumerate(blocks):
        _keys(b, _BLOCK, f"{source}: block {i}")
        if "polygon" not in b:
            raise ValueError(f"{source}: block {i} has no 'polygon'")
        polys.append(b["polygon"])
        dens.append(b.get("density", 1.0))
        names.append(str(b.get("name", f"block {i}")))
    for i, d in enumerate(dens):
        if isinstance(d, bool) or not isinstance(d, (int, float)):
            raise ValueError(f"{source}: density of {names[i]} must be a number, got {d!r}")
        if not (math.isfinite(d) and DENSITY_RANGE[0] <= d <= DENSITY_RANGE[1]):
            raise ValueError(f"{source}: density of {names[i]} must lie in "
                             f"[{DENSITY_RANGE[0]:g}, {DENSITY_RANGE[1]:g}] (kg/m³, or any "
                             f"unit: only ratios of densities matter), got {d!r}")
    default = data.get("friction") if mu is None else mu
    if default is not None:
        default = (_named(friction_value, default, f"{source}: 'friction'") if mu is None
                   else friction_value(default))
    contacts = None
    if "contacts" in data:
        if not isinstance(data["contacts"], list):
            raise ValueError(f"{source}: 'contacts' must be a list")
        contacts = []
        for k, c in enumerate(data["contacts"]):
            _keys(c, _CONTACT, f"{source}: contact {k}")
            pair = c.get("blocks")
            if (not isinstance(pair, list) or len(pair) != 2
                    or not all(isinstance(x, int) and not isinstance(x, bool) for x in pair)):
                raise ValueError(f"{source}: contact {k} needs 'blocks': [i, j] (integers, -1 "
                                 "the ground)")
            m = c.get("friction")
            contacts.append((pair[0], pair[1], None if m is None else
                             _named(friction_value, m, f"{source}: contact {k} {pair}")))
        contacts = [(i, j, default if m is None else m) for i, j, m in contacts]
    supports = data.get("supports", [])
    if not isinstance(supports, list):
        raise ValueError(f"{source}: 'supports' must be a list of polygons")
    name = str(data.get("name", source))
    out = from_polygons(polys, density=dens, mu=default, contacts=contacts,
                        supports=supports, names=names, g=g, name=name, kind="assembly")
    warn_implausible_size(out, source, "coordinates")
    return out


def warn_implausible_size(a: Assembly, source: str, what: str = "sizes") -> None:
    """A :class:`UnitsWarning` if the structure ``a`` (from ``source``) is not between
    :data:`PLAUSIBLE_SIZE` across or has a block longer than :data:`PLAUSIBLE_BLOCK`: its
    ``what`` (coordinates, sizes) are probably not in metres."""
    largest = max(float(np.ptp(np.asarray(q, float), axis=0).max()) for q in a.polygons)
    if not PLAUSIBLE_SIZE[0] <= a.size <= PLAUSIBLE_SIZE[1]:
        warnings.warn(UnitsWarning(
            f"{source}: the structure is {a.size:.4g} m across: {what} are in metres "
            + ("(millimetres? divide them by 1000)" if a.size > PLAUSIBLE_SIZE[1] else
               "(kilometres? multiply them by 1000)")), stacklevel=3)
    elif largest > PLAUSIBLE_BLOCK:
        warnings.warn(UnitsWarning(
            f"{source}: a block is {largest:.4g} m long: {what} are in metres "
            "(millimetres? divide them by 1000)"), stacklevel=3)


def _named(check, value, where: str):
    """``check(value)`` with its ValueError or TypeError prefixed by ``where``."""
    try:
        return check(value)
    except (ValueError, TypeError) as exc:
        raise type(exc)(f"{where}: {exc}") from None


def read_assembly(path, *, mu=None, g: float = G) -> Assembly:
    """The assembly of a JSON file (:func:`assembly_from_dict`); one-line ValueErrors."""
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{p}: no such file" if not p.exists() else f"{p}: not a file")
    size = p.stat().st_size
    if size > MAX_BYTES_PER_BLOCK * limits.max_blocks():
        raise ValueError(f"{p}: {size / 1e6:.3g} MB is too large for an assembly of at most "
                         f"{limits.max_blocks()} blocks ({limits.ENV['blocks']})")
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise ValueError(f"{p}: cannot read ({exc.strerror or exc})") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"{p}: not a UTF-8 text file (byte {exc.start}): an assembly is a "
                         "JSON file") from None
    try:
        data = json.loads(text, parse_constant=lambda c: math.nan)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{p}: not JSON ({exc.msg} at line {exc.lineno})") from None
    return assembly_from_dict(data, mu=mu, g=g, source=p.name)
