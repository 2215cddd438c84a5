"""Simulation of MDOF assemblies (Moreau–Jean; docs/theory.md §6, §9).

Two steppers behind one API: a chain without friction (arch, column, block: joint k between
body k−1 and body k, every μ infinite) runs on :mod:`rockarch.mdof.chain_stepper` (exact
banded active-set contact solve, O(N)); any other assembly (a general contact graph or any
finite friction coefficient) on :mod:`rockarch.mdof.graph_run` (the exact Newton solve in
the bodies' velocities with Coulomb's cones, docs/theory.md Eqs. (9.7)–(9.9), and new
contacts wherever a corner reaches a face, :mod:`rockarch.mdof.collision`).
"""

from __future__ import annotations

import math
import sys
import threading
from dataclasses import dataclass, replace

import numpy as np

from rockarch.core import limits
from rockarch.core.console import bar_rows, on_terminal
from rockarch.core.constants import GAP_TOL, T_FREE
from rockarch.core.constants import MDOF_H_FACTOR as H_FACTOR
from rockarch.core.jit_cache import announce_compile, kernel_array
from rockarch.core.response import Batch, Response, run_batch
from rockarch.core.validate import in_range
from rockarch.mdof import chain_stepper as _k
from rockarch.mdof import graph_run as _g
from rockarch.mdof.assembly import Assembly
from rockarch.mdof.kernel_data import chain_model, graph_model
from rockarch.motion.signals import GroundMotion

#: Step check of one history (:func:`simulate`, ``check_step``): the rerun at h/2 calls the
#: history sensitive to the step when its verdict differs, or (both safe) its largest
#: rotation ratio differs by more than this, in units of the overturning rotation δ_ref.
#: The engine is O(h) at impacts, so the error at h is about twice the change h → h/2: a
#: change of 0.1 is an error of ~0.2 δ_ref, a fifth of the way to the verdict's threshold
#: (1). Measured on the pulses of docs/mdof.md (20-voussoir catenary, sine/square/step,
#: 20 × 26 cells, default step): the safe histories change by 0.003 δ_ref (median) and 3 of
#: 193 by more than 0.1 (docs/mdof.md, "Convergence on records").
STEP_CHECK_ROTATION = 0.1
#: By default (``check_step=None`` of :meth:`rockarch.systems.MDOFSystem.simulate`, the CLI
#: without ``--step-check``) every structure on the chain stepper is checked (the rerun
#: costs about twice the run: milliseconds to seconds) and, on the general stepper, those
#: of at most this many blocks (a wall of hundreds of blocks takes minutes per history).
STEP_CHECK_MAX_BLOCKS = 20
#: A single simulation shows its progress (:func:`simulate`, ``progress``) once it has run
#: this long [s]: shorter ones stay silent.
PROGRESS_AFTER = 2.0


def check_h_factor(h_factor) -> float:
    """The time step × p as a float in [1e-4, 0.05] (ValueError outside)."""
    return in_range("h_factor (time step · p)", h_factor, 1e-4, 0.05)


#: The overturning rotation [rad] below which the contact tolerance shrinks in proportion
#: (:func:`contact_tolerance`, docs/theory.md Eq. (6.3a)).
DELTA_TOL = 0.05


def contact_tolerance(assembly: Assembly, gap_tol: float) -> float:
    """The contact tolerance as a fraction of the thinnest joint (docs/theory.md Eq. (6.3a)):
    ``gap_tol``, or less for a structure whose overturning rotation δ_ref is below
    :data:`DELTA_TOL`, ``gap_tol``·δ_ref/DELTA_TOL, so that it stays below
    ``gap_tol``/DELTA_TOL (2e-3 by default) of a joint's opening at overturning, d·δ_ref
    (thin arches: their hinges open by little more than the default tolerance)."""
    return gap_tol * min(1.0, assembly.delta_ref / DELTA_TOL)


def check_settings(t_free: float, h_factor: float, gap_tol: float) -> None:
    in_range("t_free", t_free, 0.0, math.inf, hi_open=True)
    check_h_factor(h_factor)
    in_range("gap_tol (fraction of the joint thickness)", gap_tol, 1e-10, 1e-3)


@dataclass(frozen=True, kw_only=True, repr=False)
class MDOFResponse(Response):
    """Time history and summary of one MDOF simulation.

    ``t`` (nt,), ``q`` (nt, nb, 3) = centroid x, y and rotation of every block (ground
    frame), ``joints`` (nt, nj) joint state: 0 closed, 1 rotating about corner 0 (corner 1
    open), 2 about corner 1 (corner 0 open), 3 both corners open; ``energy`` (nt,) kinetic +
    potential energy relative to the start (ground frame, per unit depth and density).
    ``max_slip`` is the largest tangential offset of the two sides of any joint in contact
    [m] (0 for the no-sliding chain model), ``sliding_contacts_max`` the most joints sliding
    at once, ``new_contacts_max`` the most new contacts carrying an impulse at once (corners
    pressing on a face they did not touch as built, docs/theory.md Eq. (9.10)).
    ``steps_at_rest`` of the ``steps`` were not solved: the structure was at rest and the
    ground acceleration kept it there (docs/theory.md Eq. (9.11); general stepper only).
    """

    assembly: Assembly
    scale: float
    q: np.ndarray
    joints: np.ndarray
    energy: np.ndarray
    open_joints_max: int
    steps: int
    h: float
    lcp_failures: int
    ground: GroundMotion | None = None
    max_slip: float = 0.0
    sliding_contacts_max: int = 0
    new_contacts_max: int = 0
    steps_at_rest: int = 0
    h_half: dict | None = None

    @property
    def step_sensitive(self) -> bool | None:
        """True if the rerun at h/2 (``h_half``, from ``check_step``) changes the verdict or,
        both safe, the largest rotation ratio by more than :data:`STEP_CHECK_ROTATION`;
        None if the history was not checked."""
        half = self.h_half
        if half is None:
            return None
        if half["overturned"] != self.overturned:
            return True
        return (not self.overturned and abs(half["max_rotation_ratio"]
                                            - self.max_rotation_ratio) > STEP_CHECK_ROTATION)

    def to_dict(self) -> dict:
        """The verdict plus ``open_joints_max``, ``max_slip`` (m), ``sliding_contacts_max``,
        ``new_contacts_max``, ``steps`` and ``lcp_failures`` (the steps whose contact problem
        was not solved to its tolerance: docs/theory.md §9) (the CLI's ``--json`` output);
        for a checked history
        ``h_half`` (the rerun's ``h_factor``, verdict and largest rotation ratio) and
        ``step_sensitive``."""
        out = {**super().to_dict(), "open_joints_max": int(self.open_joints_max),
               "max_slip": float(self.max_slip),
               "sliding_contacts_max": int(self.sliding_contacts_max),
               "new_contacts_max": int(self.new_contacts_max), "steps": int(self.steps),
               "lcp_failures": int(self.lcp_failures)}
        if self.h_half is not None:
            out["h_half"] = dict(self.h_half)
            out["step_sensitive"] = bool(self.step_sensitive)
        return out

    def slip(self) -> np.ndarray:
        """The largest slip of a joint in contact at every recorded time [m]: the tangential
        offset of the joint's two faces at its midpoint (each face carried by its block, the
        tangent turned with the block on the normal's tail side; docs/theory.md §9), over
        the joints not open at both corners (``joints`` < 3). Its largest value is
        ``max_slip`` as recorded (0 for a structure without friction, up to the turn of a
        rocking joint's midpoint, second order in its rotation)."""
        a = self.assembly
        nt, nj = self.q.shape[0], a.n_joints
        out = np.zeros(nt)
        if nj == 0:
            return out
        mid = a.corners.mean(axis=1) * self.scale
        tan = np.stack([-a.normal[:, 1], a.normal[:, 0]], axis=1)
        sides = []
        for body in (a.body_a, a.body_b):
            ground = body < 0
            idx = np.where(ground, 0, body)
            rel = mid - a.centroid[idx] * self.scale
            sides.append((ground, idx, rel))
        for i0 in range(0, nt, 2048):  # in chunks: (chunk, nj, 2) arrays at a time
            q = self.q[i0:i0 + 2048]
            pts, turn = [], None
            for ground, idx, rel in sides:
                x, y, ph = (q[:, idx, c] for c in range(3))
                c, sn = np.cos(ph), np.sin(ph)
                px = np.where(ground, mid[:, 0], x + c * rel[:, 0] - sn * rel[:, 1])
                py = np.where(ground, mid[:, 1], y + sn * rel[:, 0] + c * rel[:, 1])
                pts.append((px, py))
                if turn is None:  # the tangent turns with body a (fixed on the ground)
                    turn = (np.where(ground, tan[:, 0], c * tan[:, 0] - sn * tan[:, 1]),
                            np.where(ground, tan[:, 1], sn * tan[:, 0] + c * tan[:, 1]))
            off = (turn[0] * (pts[1][0] - pts[0][0]) + turn[1] * (pts[1][1] - pts[0][1]))
            touching = self.joints[i0:i0 + 2048] < 3
            out[i0:i0 + 2048] = np.where(touching, np.abs(off), 0.0).max(axis=1)
        return out

    def corners_at(self, i: int) -> np.ndarray:
        """Block outlines at record i: list of (K, 2) arrays in the ground frame."""
        a = self.assembly
        out = []
        for ip, poly in enumerate(a.polygons):
            j = a.body_of_polygon(ip)
            x, y, ph = self.q[i, j]
            c, s = math.cos(ph), math.sin(ph)
            rel = np.asarray(poly) * self.scale - a.centroid[j] * self.scale
            out.append(np.stack([x + c * rel[:, 0] - s * rel[:, 1],
                                 y + s * rel[:, 0] + c * rel[:, 1]], axis=1))
        return out


def uses_chain_stepper(assembly: Assembly) -> bool:
    """True if the assembly runs on the banded chain stepper (a chain, no friction)."""
    return assembly.is_chain and assembly.frictionless


def checks_step_by_default(assembly: Assembly) -> bool:
    """True if a single history of the assembly is rerun at h/2 unless told otherwise: on
    the chain stepper, or with at most :data:`STEP_CHECK_MAX_BLOCKS` blocks."""
    return uses_chain_stepper(assembly) or assembly.n_blocks <= STEP_CHECK_MAX_BLOCKS


def _motion_arrays(motion: GroundMotion | None):
    if motion is None:
        return kernel_array(np.zeros(2)), kernel_array([0.0, 1.0]), "free", 0.0
    return kernel_array(motion.t), kernel_array(motion.a), motion.name, float(motion.duration)


def _plan(t_end: float, h: float, n_blocks: int, n_joints: int, record_every: int
          ) -> tuple[int, int]:
    """Time steps of a simulation and the recording stride, known before anything is
    allocated (docs/theory.md Eq. (8.7)): at most :func:`rockarch.core.limits.max_mdof_steps`
    steps (else ValueError), a history of at most :data:`rockarch.core.limits.MAX_HISTORY_BYTES`
    (every k-th step recorded above it; the simulation itself is unchanged)."""
    need = t_end / h
    if not need <= limits.max_mdof_steps():
        raise limits.too_many(f"an MDOF simulation of {t_end:.6g} s at h = {h:.3g} s", need,
                              "mdof_steps", limits.max_mdof_steps(),
                              "lower --t-free or the motion's duration")
    n_steps = int(math.ceil(need))
    per_sample = 8 * (2 + 3 * n_blocks) + n_joints
    rec = max(int(record_every), 1, math.ceil(n_steps * per_sample / limits.MAX_HISTORY_BYTES))
    return n_steps, rec


def simulate(assembly: Assembly, motion: GroundMotion | None, *, p: float | None = None,
             t_free: float = T_FREE, h_factor: float = H_FACTOR, gap_tol: float = GAP_TOL,
             record_every: int = 1, through_collapse: bool = False,
             check_step: bool = False, skip_rest: bool = True,
             progress: bool | None = None) -> MDOFResponse:
    """Simulate the assembly on the ground motion (used as given, m/s²).

    ``p``: run the same shape scaled to frequency parameter p (default: its own size).
    ``gap_tol``: the contact tolerance, a fraction of the thinnest joint (less for thin
    structures, :func:`contact_tolerance`).
    Free motion continues ``t_free`` s after the motion ends, or until rest or collapse.
    ``record_every``: record every k-th step (raised when the history would exceed
    :data:`rockarch.core.limits.MAX_HISTORY_BYTES`). ``through_collapse``: follow the blocks
    after a collapse (falling, landing, coming to rest) until rest or the end of the free
    motion (on the general stepper, whose new contacts let them land); the verdict,
    ``t_overturn``, ``max_rotation_ratio``, ``impacts``, ``open_joints_max``, ``max_slip``
    and ``sliding_contacts_max`` are those of the first collapse, as without it (the
    history, ``t_end``, ``steps`` and ``new_contacts_max`` include the fall).
    ``check_step``: run the history again at h/2 (its verdict only, no history kept) and
    report it in ``h_half`` and
    ``step_sensitive`` (:data:`STEP_CHECK_ROTATION`): a chaotic history may change its
    verdict with the step while maps and suites do not (docs/mdof.md, "Convergence on
    records"). ``skip_rest`` False solves every step of the general stepper, also those
    where the structure is at rest and stays there (docs/theory.md Eq. (9.11); the
    reference of that shortcut's tests and benchmarks). ``progress``: a progress bar on
    stderr (the simulated time reached) for a run that lasts more than
    :data:`PROGRESS_AFTER` s; None: only when stderr is a terminal.
    """
    check_settings(t_free, h_factor, gap_tol)
    for name, flag in (("check_step", check_step), ("skip_rest", skip_rest)):
        if not isinstance(flag, (bool, np.bool_)):
            raise TypeError(f"{name} must be True or False, got {type(flag).__name__}")
    res = _simulate(assembly, motion, p, t_free, h_factor, gap_tol, record_every,
                    through_collapse, skip_rest, progress, "simulating")
    if not check_step:
        return res
    # the verdict at h/2 (Moreau–Jean is O(h) at impacts); a history of two samples
    half = _simulate(assembly, motion, p, t_free, h_factor / 2, gap_tol, 2 ** 40,
                     through_collapse, skip_rest, progress, "step check at h/2")
    return replace(res, h_half={"h_factor": h_factor / 2, "overturned": half.overturned,
                                "t_overturn": half.t_overturn,
                                "max_rotation_ratio": half.max_rotation_ratio})


def _announce(chain: bool) -> None:
    """The one-line notice of a first compilation of the stepper (command line only)."""
    if chain:
        announce_compile(_k.run, "the chain stepper", 10)
    else:
        announce_compile(_g.run, "the general contact stepper", 60)


def _with_progress(run, out_t: np.ndarray, t_end: float, label: str, progress: bool | None):
    """``run()`` (a compiled kernel that releases the GIL and writes the times it records
    into ``out_t`` in order), with a progress bar of the simulated time on stderr once it
    has taken :data:`PROGRESS_AFTER` s (``progress``: :func:`rockarch.core.console.on_terminal`).
    The kernel runs in a daemon thread: an interrupt (Ctrl-C) ends the process without
    waiting for it. The result is the kernel's, bit for bit."""
    if not on_terminal(progress):
        return run()
    box: dict = {}

    def work() -> None:
        try:
            box["out"] = run()
        except BaseException as exc:  # noqa: BLE001 - re-raised in the caller's thread
            box["err"] = exc

    th = threading.Thread(target=work, daemon=True, name="rockarch-simulate")
    th.start()
    th.join(PROGRESS_AFTER)
    if th.is_alive():
        from tqdm import tqdm

        timed = out_t.size > 10  # a history of a few samples (the step check): time alone
        fmt = ("{desc}: {percentage:3.0f}%|{bar}| t = {n:.2f} of {total:.2f} s "
               "[{elapsed}<{remaining}]" if timed else "{desc}: {elapsed}")
        rows = bar_rows()  # the terminal's size on every refresh, unless it reports none
        with tqdm(total=round(t_end, 2) if timed else None, desc=label, file=sys.stderr,
                  leave=False, dynamic_ncols=rows is None, bar_format=fmt, nrows=rows) as bar:
            while th.is_alive():
                th.join(0.5)
                if timed:
                    n = int(np.count_nonzero(out_t))
                    bar.n = round(float(out_t[n - 1]) if n else 0.0, 2)
                bar.refresh()  # the elapsed time runs on where the motion is slow
    if "err" in box:
        raise box["err"]
    return box["out"]


def _simulate(assembly: Assembly, motion: GroundMotion | None, p: float | None,
              t_free: float, h_factor: float, gap_tol: float, record_every: int,
              through_collapse: bool, skip_rest: bool, progress: bool | None = False,
              label: str = "simulating") -> MDOFResponse:
    """:func:`simulate` without the step check (its settings already checked)."""
    scale = 1.0 if p is None else assembly.size_for(in_range("p", p, 0, math.inf,
                                                             lo_open=True, hi_open=True)) \
        / assembly.size
    p_act = assembly.p_ref / math.sqrt(scale)
    h = h_factor / p_act
    tk, ak, name, duration = _motion_arrays(motion)
    t_end = duration + t_free
    gap_tol = contact_tolerance(assembly, gap_tol)
    nb_, nj = assembly.n_blocks, assembly.n_joints
    n_steps, rec = _plan(t_end, h, nb_, nj, record_every)
    cap = n_steps // rec + 2
    out_t, out_q = np.zeros(cap), np.zeros((cap, nb_, 3))
    out_s, out_e = np.zeros((cap, nj), dtype=np.int8), np.zeros(cap)
    if uses_chain_stepper(assembly) and not through_collapse:
        model = chain_model(assembly)
        _announce(True)
        out = _with_progress(lambda: _k.run(model, scale, tk, ak, 1.0, h, t_end, duration,
                                            gap_tol, rec, out_t, out_q, out_s, out_e),
                             out_t, t_end, label, progress) + (0.0, 0, 0, 0)
    else:
        model = graph_model(assembly)
        _announce(False)
        out = _with_progress(lambda: _g.run(model, scale, tk, ak, 1.0, h, t_end, duration,
                                            gap_tol, rec, out_t, out_q, out_s, out_e,
                                            bool(through_collapse), bool(skip_rest)),
                             out_t, t_end, label, progress)
    st, tc, mx, imp, nopen, n_rec, steps, fails, slip, n_slide, n_points, n_rest = out[:12]
    # prepend the initial state (the model's c0: the centroids as floats; read from the
    # assembly, a record's field read from Python boxes all its fields)
    q0 = np.zeros((1, nb_, 3))
    q0[0, :, :2] = np.asarray(assembly.centroid, dtype=float) * scale
    return MDOFResponse(
        system=assembly.name, assembly=assembly, motion_name=name, scale=scale,
        t=np.concatenate([[0.0], out_t[:n_rec]]), q=np.concatenate([q0, out_q[:n_rec]]),
        joints=np.concatenate([np.zeros((1, nj), np.int8), out_s[:n_rec]]),
        energy=np.concatenate([[0.0], out_e[:n_rec]]), overturned=bool(st == 1),
        t_overturn=float(tc) if st == 1 else None, max_rotation_ratio=float(mx),
        t_end=float(out_t[n_rec - 1]) if n_rec else 0.0,
        impacts=int(imp), open_joints_max=int(nopen), steps=int(steps), h=h,
        lcp_failures=int(fails), ground=motion, max_slip=float(slip),
        sliding_contacts_max=int(n_slide), new_contacts_max=int(n_points),
        steps_at_rest=int(n_rest))


def simulate_batch(assembly: Assembly, motion: GroundMotion, p, ratio, *,
                   ap_min: float | None = None, p_ref: float | None = None,
                   t_free: float = T_FREE, h_factor: float = H_FACTOR,
                   gap_tol: float = GAP_TOL) -> Batch:
    """Run the assembly's shape at many (p, ratio) pairs in parallel (as many threads as numba has).

    The motion's shape is normalised to unit peak and scaled to ratio·ap_min; the size is
    set so that the reference frequency parameter equals p. ``ap_min``/``p_ref`` override
    the assembly's own reference values (e.g. those of the continuous four-hinge mechanism).
    """
    check_settings(t_free, h_factor, gap_tol)
    ap = assembly.ap_min if ap_min is None else float(ap_min)
    pr = assembly.p_ref if p_ref is None else float(p_ref)
    unit = motion.normalized()
    tk, ak = kernel_array(unit.t), kernel_array(unit.a)
    chain = uses_chain_stepper(assembly)
    model = chain_model(assembly) if chain else graph_model(assembly)

    def run(pf, rf):
        scales = (pr / pf) ** 2
        hs = h_factor / (assembly.p_ref / np.sqrt(scales))
        if hs.size:  # the longest run's steps and history, before any (Eq. 8.7)
            _plan(float(unit.duration + t_free), float(np.min(hs)), assembly.n_blocks,
                  assembly.n_joints, 1)
        args = (model, scales, tk, ak, np.ascontiguousarray(rf * ap), hs,
                float(unit.duration + t_free), float(unit.duration),
                contact_tolerance(assembly, gap_tol))
        _announce(chain)
        if chain:
            out = _k.run_batch(*args)
            return out + (np.zeros(scales.size), np.zeros(scales.size, dtype=np.int64))
        return _g.run_batch(*args)

    return run_batch(p, ratio, run, extras=("open_joints_max", "lcp_failures", "max_slip",
                                            "sliding_contacts_max"))
