"""Output paths: the one check made before any computation, and the one atomic writer.

Every file rockarch writes goes through :func:`atomic_write` or :func:`staged`: the data is
written to a temporary name unique to the process (``.NAME.PID.RANDOM.tmpSUFFIX`` in the
target's folder) and renamed onto the target only when every output of the command has been
written, so a failing output leaves none behind and two processes writing the same file at
once both succeed with a whole file. Error messages name the target, never the temporary.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class OutputFormat:
    """A kind of file rockarch writes: its accepted extensions and a short description."""

    name: str
    suffixes: tuple[str, ...]
    description: str


#: The output formats (registry): key -> accepted extensions.
FORMATS: dict[str, OutputFormat] = {f.name: f for f in (
    OutputFormat("netcdf", (".nc",), "NetCDF"),
    OutputFormat("png", (".png",), "PNG image"),
    OutputFormat("html", (".html", ".htm"), "HTML page"),
    OutputFormat("gif", (".gif",), "GIF animation"),
    OutputFormat("json", (".json",), "JSON file"),
)}


def _label(option: str | None, path: Path) -> str:
    return f"{option} {path}" if option else str(path)


def _probe_writable(folder: Path, label: str) -> None:
    """Create and delete a file in ``folder``: the only test that also holds for root,
    read-only mounts and pseudo file systems such as /proc."""
    probe = folder / f".rockarch-probe.{os.getpid()}.{secrets.token_hex(4)}"
    try:
        fd = os.open(probe, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600)
    except OSError as exc:
        raise ValueError(f"{label}: cannot write in directory {folder} "
                         f"({exc.strerror or exc.__class__.__name__})") from None
    os.close(fd)
    os.unlink(probe)


def _existing_ancestor(folder: Path) -> Path:
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    return folder


def check_output(path: Path | str | None, option: str | None = None,
                 fmt: str | None = None) -> Path | None:
    """Check that a file can be written at ``path`` (None passes). Raises ValueError.

    Refused: an extension other than ``fmt``'s, an existing directory at ``path``, a missing
    folder, a file where a folder of the path should be, a folder or file not writable.
    ``option`` (e.g. ``"--out"``) names the path in the message.
    """
    if path is None:
        return None
    path = Path(path)
    label = _label(option, path)
    if path.is_dir():
        raise ValueError(f"{label}: is a directory, give a file name")
    if fmt is not None:
        f = FORMATS[fmt]
        if path.suffix.lower() not in f.suffixes:
            got = f"'{path.suffix}'" if path.suffix else "none"
            raise ValueError(f"{label}: a {f.description} is written here, so the name must "
                             f"end in {' or '.join(f.suffixes)} (extension {got})")
    folder = path.absolute().parent
    found = _existing_ancestor(folder)
    if not found.is_dir():
        raise ValueError(f"{label}: {found} is a file, not a directory")
    if found != folder:
        missing = folder
        while missing.parent != found:
            missing = missing.parent
        raise ValueError(f"{label}: directory does not exist: {missing}")
    _probe_writable(folder, label)
    if path.exists() and not os.access(path, os.W_OK):
        raise ValueError(f"{label}: the file exists and is not writable")
    return path


def check_output_dir(path: Path | str | None, option: str | None = None) -> Path | None:
    """Check that ``path`` is, or can be created as, a writable folder (None passes)."""
    if path is None:
        return None
    path = Path(path)
    label = _label(option, path)
    found = _existing_ancestor(path.absolute())
    if not found.is_dir():
        what = "is a file" if found == path.absolute() else f"{found} is a file"
        raise ValueError(f"{label}: {what}, not a directory")
    _probe_writable(found, label)
    return path


def check_outputs(*specs: tuple) -> None:
    """Check several outputs before any computation: ``(path, option[, fmt])`` tuples;
    ``fmt`` ``"dir"`` means a folder. None paths pass. Two outputs on one path are refused."""
    seen: dict[Path, str] = {}
    for spec in specs:
        path, option, fmt = (*spec, None)[:3]
        if path is None:
            continue
        if fmt == "dir":
            check_output_dir(path, option)
        else:
            check_output(path, option, fmt)
        key = Path(path).absolute()
        if key in seen:
            raise ValueError(f"{option} {path}: the same file as {seen[key]}")
        seen[key] = option or str(path)


def temporary_name(path: Path) -> Path:
    """A temporary sibling of ``path``, unique to this process and call, same extension."""
    return path.with_name(f".{path.name}.{os.getpid()}.{secrets.token_hex(4)}.tmp"
                          f"{path.suffix}")


class OutputError(ValueError):
    """An output could not be written (the message names the target, never a temporary)."""


def _without_temporaries(msg: str, pairs: list[tuple[Path, Path]]) -> str:
    for tmp, final in pairs:
        msg = msg.replace(str(tmp), str(final)).replace(tmp.name, final.name)
    return msg


@contextmanager
def staged(*paths: Path | str | None) -> Iterator[list[Path | None]]:
    """Temporary paths for several outputs, renamed onto ``paths`` together on success.

    Every target is checked first (:func:`check_output`). Yields one temporary path per
    target (None stays None). If the block raises, every temporary is removed and no target
    is touched; the error is re-raised as an :class:`OutputError` naming the target (never
    a temporary), unless it is a KeyboardInterrupt/SystemExit. Stages nest (a writer may
    itself write atomically onto the temporary it is given).
    """
    for p in paths:
        check_output(p)
    pairs = [(temporary_name(Path(p)), Path(p)) for p in paths if p is not None]
    it = iter(pairs)
    tmps = [None if p is None else next(it)[0] for p in paths]
    try:
        yield tmps
        for tmp, final in pairs:
            os.replace(tmp, final)
    except Exception as exc:
        if isinstance(exc, OutputError):  # from a nested stage: already says what failed
            raise OutputError(_without_temporaries(str(exc), pairs)) from None
        target = pairs[0][1] if len(pairs) == 1 else ", ".join(str(f) for _, f in pairs)
        for tmp, final in pairs:
            if str(tmp) in str(exc) or tmp.name in str(exc):
                target = final
        why = getattr(exc, "strerror", None) or str(exc) or exc.__class__.__name__
        raise OutputError(f"{target}: cannot write: {_without_temporaries(why, pairs)}"
                          ) from None
    finally:
        for tmp, _ in pairs:
            if tmp.exists() or tmp.is_symlink():
                tmp.unlink()


def atomic_write(path: Path | str, writer: Callable[[Path], object]) -> Path:
    """Write one file atomically: ``writer(tmp)`` writes the temporary, which is then
    renamed onto ``path``. Returns ``path``."""
    path = Path(path)
    with staged(path) as (tmp,):
        writer(tmp)
    return path


def write_text(path: Path | str, text: str) -> Path:
    """Write a UTF-8 text file atomically."""
    return atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))
