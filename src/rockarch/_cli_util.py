"""Helpers shared by the CLI commands: one-line errors with exit status 2, JSON output."""

from __future__ import annotations

import functools
import json
import math
import sys
from collections.abc import Callable
from typing import Any

import numpy as np
import typer


def _clean(obj: Any) -> Any:
    """Turn numpy scalars/arrays and NaN into plain JSON values (NaN/inf -> null)."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _clean(obj.tolist())
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer, int)):
        return int(obj)
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    return obj


def print_json(obj: Any) -> None:
    """Print one JSON object on stdout (NaN -> null, numpy -> plain)."""
    sys.stdout.write(json.dumps(_clean(obj)) + "\n")
    sys.stdout.flush()


def fail(message: str) -> None:
    """Print one clear line on stderr and exit with status 2."""
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code=2)


def guarded(func: Callable) -> Callable:
    """Decorate a CLI command: ValueError / OSError become one line on stderr and exit 2."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except (ValueError, OSError) as exc:
            fail(str(exc) if str(exc) else exc.__class__.__name__)

    return wrapper
