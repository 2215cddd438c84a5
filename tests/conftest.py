"""Test-wide settings: the sweep store of CLI runs goes to a temporary directory (removed
at exit), never to the user's cache.

``ROCKARCH_PERTURB=1`` (``make test-perturbed``, run by CI after ``make test``) moves every
ground motion in its last bit, in this process and in every Python process the tests start
(tests/perturb/rockarch_perturb.py says how, and which invariances it keeps): every
simulation then differs from the plain run in its last bits, as it would on another machine.
A test that checks an exact construction opts out with ``@pytest.mark.unperturbed``.
"""

import atexit
import importlib
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import pytest

_CACHE = tempfile.mkdtemp(prefix="rockarch-test-cache-")
os.environ["ROCKARCH_CACHE"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)

_PERTURB_DIR = str(Path(__file__).parent / "perturb")
if _PERTURB_DIR not in sys.path:
    sys.path.insert(0, _PERTURB_DIR)

import rockarch_perturb  # noqa: E402

if rockarch_perturb.ENABLED:
    rockarch_perturb.install()
    # child processes (CLI runs, pool workers, the docs' scripts) start perturbed too
    paths = os.environ.get("PYTHONPATH", "").split(os.pathsep)
    if _PERTURB_DIR not in paths:
        os.environ["PYTHONPATH"] = os.pathsep.join([_PERTURB_DIR, *filter(None, paths)])


def _command_built_once():
    """typer's test runner turns the app into its click command at every ``invoke``: ~40 ms
    for rockarch's ~30 commands, times ~700 invocations in the suite (a sixth of its CPU).
    The command line builds it once per process; so do the tests (the app does not change
    while they run)."""
    import typer.testing

    build = typer.testing._get_command
    built: dict[int, tuple] = {}

    def get_command(app):
        key = id(app)
        if key not in built or built[key][0] is not app:
            built[key] = (app, build(app))
        return built[key][1]

    typer.testing._get_command = get_command


_command_built_once()


@pytest.fixture(autouse=True)
def _unperturbed(request):
    """Turn the perturbation off for a test marked ``unperturbed`` (exact constructions)."""
    if not rockarch_perturb.ENABLED or request.node.get_closest_marker("unperturbed") is None:
        yield
        return
    rockarch_perturb.ENABLED = False
    try:
        yield
    finally:
        rockarch_perturb.ENABLED = True


@pytest.fixture(scope="session")
def short_records(tmp_path_factory):
    """The first 12 s of both bundled El Centro components (the strong motion) as .AT2
    files in one folder: the fragility and risk commands' checks, fast."""
    import rockarch as ra
    from rockarch.motion.suite import write_at2

    d = tmp_path_factory.mktemp("short")
    for c in (180, 270):
        m = ra.el_centro(c)
        write_at2(d / f"ELC{c}-12s.AT2", ra.GroundMotion(m.t[:1200], m.a[:1200]))
    return d


# ------------------------------------------------------- the stepper compiling meanwhile
#: tests/warm_kernels.py --overlap (``make test``) compiles the general contact stepper in the
#: background while the suite starts; this file (its ``MARKER``) holds that process's id
#: until it ends.
_WARMING = Path(__file__).resolve().parents[1] / ".pytest_cache" / "warm-graph.pid"
#: The test modules that run the general contact stepper (or its parts): run last, and wait
#: for the background compilation; any other test that reaches the stepper waits too (below).
GRAPH_MODULES = frozenset({
    "mdof/test_cli.py", "mdof/test_factor_reuse.py", "mdof/test_kernel_records.py",
    "mdof/test_mdof.py",
    "mdof/test_progress.py", "mdof/test_retry.py", "mdof/test_statics_cache.py",
    "output/test_animation.py", "output/test_figures.py", "test_docs_blocks.py",
    "test_fragility_cli.py", "test_jit_cache.py", "test_readme.py", "test_site_design.py",
    "validation/test_assemblies.py", "validation/test_assembly_cli.py",
    "validation/test_friction.py", "validation/test_new_contacts.py",
    "validation/test_oracle_drivers.py", "validation/test_pymunk_dynamic.py",
    "validation/test_rest_skip.py",
})


def _compiling() -> bool:
    """Whether the background compilation of the stepper still runs."""
    try:
        pid = int(_WARMING.read_text())
    except (OSError, ValueError):
        return False
    try:
        with open(f"/proc/{pid}/stat") as f:  # Linux: an ended process may linger as a zombie
            return f.read().rpartition(")")[2].split()[0] != "Z"
    except OSError:
        pass
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True


def wait_for_the_stepper(limit: float = 600.0) -> None:
    """Wait (at most ``limit`` s) while the stepper compiles in the background: compiling it
    here as well would take as long and slow both."""
    end = time.monotonic() + limit
    while _compiling() and time.monotonic() < end:
        time.sleep(0.5)


if _compiling():  # every use of the stepper passes its compile notice first
    _sim = importlib.import_module("rockarch.mdof.simulate")
    _announce = _sim._announce

    def _announce_after_the_warm(chain: bool) -> None:
        if not chain:
            wait_for_the_stepper()
        _announce(chain)

    _sim._announce = _announce_after_the_warm


def _graph_module(item) -> bool:
    try:
        return item.path.relative_to(Path(__file__).parent).as_posix() in GRAPH_MODULES
    except ValueError:  # a test outside tests/
        return False


#: Tests that mostly wait (a sweep interrupted and resumed, a scheduler that never answers,
#: a Dask cluster starting): first, so that the stepper compiling in the background uses the
#: core they leave idle (2026-11-30: 8–12 s of wall time each for ~4 s of CPU).
WAITING = ("sweep/test_resume.py::test_interrupted_sweep_resumes",
           "sweep/test_cli.py::test_unreachable_scheduler_is_one_line_without_hanging",
           "sweep/test_sweep.py::test_dask_workers_option_starts_and_stops_a_cluster")


def _waits(item) -> bool:
    try:
        rel = item.path.relative_to(Path(__file__).parent).as_posix()
    except ValueError:
        return False
    return f"{rel}::{item.name}".startswith(WAITING)


def pytest_collection_modifyitems(config, items):
    """The tests that mostly wait first, the stepper's tests last (stable): the others run
    while it compiles."""
    items.sort(key=lambda item: (_graph_module(item), not _waits(item)))


@pytest.fixture(autouse=True)
def _after_the_warm(request):
    if _graph_module(request.node):
        wait_for_the_stepper()
