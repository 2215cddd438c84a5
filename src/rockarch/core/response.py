"""One result vocabulary for every rocking system: :class:`Response` and :class:`Batch`.

A simulation of a rigid block, of an SDOF mechanism (four-hinge arch, rocking frame, any
(p, delta, ap,min) mechanism) or of an MDOF assembly returns a :class:`Response` (or a
subclass carrying the kind's own time histories); many simulations of one motion return a
:class:`Batch`. The verdict is the same everywhere (docs/theory.md §0, Eqs. 1.5 and 3.5):

- ``overturned``: the structure collapsed (block: |theta| reached alpha; mechanism: |u|
  reached delta; MDOF: the frozen-configuration collapse test of docs/mdof.md);
- ``t_overturn``: when [s], None if safe;
- ``max_rotation_ratio``: the largest rotation over its overturning value (theta/alpha,
  u/delta, or an assembly's largest block rotation over delta_ref): 1 at collapse for a
  block or a mechanism, as a rule above 1 for an overturned assembly (:class:`Response`);
- ``impacts``: the number of impacts.
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from rockarch.core.validate import P_MAX, P_MIN, RATIO_MAX, numbers


@dataclass(frozen=True, kw_only=True)
class Response:
    """The outcome of one simulation: the verdict of docs/theory.md Eqs. (1.5) and (3.5).

    Subclasses add the kind's own time histories.

    Attributes
    ----------
    system : str
        Name of the simulated structure.
    motion_name : str
        Name of the ground motion.
    t : ndarray
        Recorded times [s].
    overturned : bool
        True if the structure collapsed: a block's |theta| reached alpha (Eq. (1.5)), a
        mechanism's |u| reached its neutral angle delta (Eq. (3.5)), an MDOF assembly
        passed the frozen-configuration collapse test of docs/mdof.md.
    t_overturn : float or None
        Time of the collapse, on the time axis of the ground motion (t = 0 at its first
        sample) [s]; None if the structure did not collapse.
    max_rotation_ratio : float
        Largest rotation over the rotation at which the structure overturns [-]:
        max |theta|/alpha for a block, max |u|/delta for an SDOF mechanism, the largest
        block rotation over delta_ref for an assembly. Exactly 1 at collapse for a block or
        an SDOF mechanism, not for an assembly: its collapse test (docs/mdof.md) runs only
        every ``CHECK_EVERY`` = 4 steps (:mod:`rockarch.mdof.chain_stepper`, once a block
        has turned by 0.5·delta_ref), and its blocks turn by other angles than the
        reference part, in a mechanism that need not be the reference one; so an
        overturned assembly's ratio overshoots 1 (1.45 in README.md's ``simulate mdof``
        example), and a safe one's may pass 1 too. Below 1 it tells how close a safe run
        came.
    impacts : int
        Number of impacts (a block or mechanism returning to its rest position, an MDOF
        joint closing).
    t_end : float
        Time at which the simulation stopped (rest, collapse or end of free motion) [s].

    Notes
    -----
    :meth:`to_dict` also returns ``max_theta_over_alpha``, the same number as
    ``max_rotation_ratio`` under its earlier name (kept for scripts that read the CLI's
    ``--json`` output).
    """

    system: str
    motion_name: str
    t: np.ndarray
    overturned: bool
    t_overturn: float | None
    max_rotation_ratio: float
    impacts: int
    t_end: float

    def __repr__(self) -> str:
        """One line: the kind, structure, motion and verdict (not the histories, which the
        attributes hold). Subclasses are declared with ``repr=False`` to keep it."""
        verdict = (f"overturned at t={self.t_overturn:.4g} s" if self.overturned
                   else f"safe, max rotation ratio {self.max_rotation_ratio:.3g}")
        return (f"{type(self).__name__}({self.system!r}, {self.motion_name!r}: {verdict}, "
                f"{self.impacts} impacts, {np.size(self.t)} samples to t={self.t_end:.4g} s)")

    def to_dict(self) -> dict:
        """The verdict as plain numbers (the CLI's ``--json`` output).

        ``max_theta_over_alpha`` repeats ``max_rotation_ratio`` under its earlier name.
        """
        return {
            "overturned": bool(self.overturned),
            "t_overturn": self.t_overturn,
            "max_rotation_ratio": float(self.max_rotation_ratio),
            "max_theta_over_alpha": float(self.max_rotation_ratio),
            "impacts": int(self.impacts),
        }


@dataclass(frozen=True, kw_only=True)
class Batch:
    """Verdicts of many simulations of one motion (arrays shaped like the broadcast inputs).

    ``extras`` holds kind-specific arrays (MDOF: ``open_joints_max``, ``lcp_failures``).
    """

    overturned: np.ndarray
    t_overturn: np.ndarray
    max_rotation_ratio: np.ndarray
    impacts: np.ndarray
    extras: dict | None = None


def run_batch(p, ratio, run: Callable[[np.ndarray, np.ndarray], tuple], *,
              extras: tuple[str, ...] = ()) -> Batch:
    """Validate and broadcast (p, ratio), run them in a fixed balanced order, return a Batch.

    ``run(p, ratio)`` receives flat contiguous arrays (a fixed random permutation of the
    pairs, so that the numba threads share early-ending runs evenly) and returns the kernel
    arrays (status, t_overturn, max ratio, impacts, *extras); status 1 means collapse.
    """
    p, ratio = numbers("p", p), numbers("ratio", ratio)
    try:
        p_arr, r_arr = np.broadcast_arrays(p, ratio)
    except ValueError:
        raise ValueError(f"p and ratio must broadcast together, got shapes {p.shape} and "
                         f"{ratio.shape}") from None
    shape = p_arr.shape
    pf = np.ascontiguousarray(p_arr.ravel())
    rf = np.ascontiguousarray(r_arr.ravel())
    if pf.size and not (np.all(np.isfinite(pf)) and np.all(pf > 0)):
        raise ValueError("p must be a finite number > 0 for every run")
    if pf.size and (np.max(pf) > P_MAX or np.min(pf) < P_MIN):
        bad = np.max(pf) if np.max(pf) > P_MAX else np.min(pf)
        raise ValueError(f"p must lie in [{P_MIN:g}, {P_MAX:g}] 1/s, got {bad:g}")
    if rf.size and not (np.all(np.isfinite(rf)) and np.all(rf >= 0)):
        raise ValueError("ratio ap/ap,min must be finite and >= 0")
    if rf.size and np.max(rf) > RATIO_MAX:
        raise ValueError(f"ratio ap/ap,min must be at most {RATIO_MAX:g}, got {np.max(rf):g}")
    perm = np.random.default_rng(0).permutation(pf.size)
    out = run(np.ascontiguousarray(pf[perm]), np.ascontiguousarray(rf[perm]))
    inv = np.empty_like(perm)
    inv[perm] = np.arange(perm.size)
    back = [np.asarray(a)[inv].reshape(shape) for a in out]
    return Batch(overturned=back[0] == 1, t_overturn=back[1], max_rotation_ratio=back[2],
                 impacts=back[3], extras=dict(zip(extras, back[4:], strict=True)) or None)


def thread_map(fn: Callable[[int], tuple], n: int) -> list:
    """``[fn(i) for i in range(n)]`` on ``numba.get_num_threads()`` threads, in order.

    ``fn`` calls a kernel compiled with ``nogil=True``, so the runs go side by side as in a
    ``prange`` loop, without a parallel copy of the kernel to compile (for the MDOF
    steppers that copy took 9–23 s of compilation on top of the kernel's own). If one run
    raises, the runs not started are cancelled and the error propagates.
    """
    import numba

    k = min(max(int(numba.get_num_threads()), 1), n)
    if k <= 1:
        return [fn(i) for i in range(n)]
    with ThreadPoolExecutor(max_workers=k) as pool:
        futures = [pool.submit(fn, i) for i in range(n)]
        try:
            return [f.result() for f in futures]
        except BaseException:
            for f in futures:
                f.cancel()
            raise
