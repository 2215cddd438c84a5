"""rockarch: seismic overturning assessment of rocking blocks, columns and masonry arches.

The data flow is ``ground motion -> structure -> simulation -> spectrum -> design check``
(docs/architecture.md). The front door::

    import numpy as np
    import rockarch as ra

    sys_ = ra.system("block", alpha=0.1)        # "fourhinge", "mdof", "frame", "sdof"
    m = ra.pulse("sine", period=0.5)            # or ra.read_record(path)
    r = ra.simulate(sys_, m, p=2.0, ratio=2.0)  # -> ra.Response
    r.overturned, r.t_overturn, r.max_rotation_ratio, r.impacts
    ds = ra.oas(sys_, m, p=[1.0, 2.0], ratio=np.linspace(1, 5, 41))  # xarray.Dataset
    d = ra.design_system(sys_, p=2.0, records=ra.read_suite("DIR"))  # safe PGA, fragility

Units are SI (m, s, m/s², rad); sign conventions in docs/theory.md.
"""

from rockarch.core import __version__
from rockarch.core import jit_cache as _jit_cache

_jit_cache.use_digest_cache()  # before any numba kernel is defined

from rockarch.arch.geometry import make_arch  # noqa: E402
from rockarch.core.constants import G  # noqa: E402
from rockarch.core.response import Batch, Response  # noqa: E402
from rockarch.core.validate import number as _number  # noqa: E402
from rockarch.design import design_system  # noqa: E402
from rockarch.motion.records import el_centro, read_record  # noqa: E402
from rockarch.motion.signals import SIGNALS, GroundMotion, pulse  # noqa: E402
from rockarch.motion.suite import Suite, read_suite  # noqa: E402
from rockarch.spectra.oas import compute_oas as _compute_oas  # noqa: E402
from rockarch.systems import KINDS, batch, simulate, system  # noqa: E402


def synthetic_suite(n: int, seed: int = 0, *, dt: float | None = None,
                    f_corner: float | None = None, pulse_fraction: float = 0.0) -> Suite:
    """A suite of ``n`` seeded synthetic ground-motion records.

    Rezaeian & Der Kiureghian's modulated, filtered white-noise model, its six parameters
    drawn per record from their 2010 fitted distributions (docs/theory.md §11.1,
    Eqs. (11.8)–(11.11); docs/sites.md, "Synthetic suites"). The same ``(n, seed)`` gives
    the same records, sample for sample.

    Parameters
    ----------
    n : int
        Number of records, >= 1.
    seed : int
        Seed of the random draws (parameters and noise).
    dt : float, optional
        Sampling interval [s] (None: 0.01, :data:`rockarch.motion.synthetic.DT`).
    f_corner : float, optional
        Corner frequency of the high-pass post-processing [Hz] (None: 0.2,
        :data:`rockarch.motion.synthetic.F_CORNER`).
    pulse_fraction : float
        Share of the records given a near-fault velocity pulse, in [0, 1] (Mavroeidis &
        Papageorgiou, Eq. (11.14)).

    Returns
    -------
    Suite
        Records named ``rdk-s{seed}-{k:03d}``, accelerations in m/s²; each record's model
        parameters are in ``suite[k].motion.meta``.

    Raises
    ------
    TypeError, ValueError
        If ``n``, ``seed``, ``dt``, ``f_corner`` or ``pulse_fraction`` is of the wrong type
        or out of range.

    Examples
    --------
    >>> import rockarch as ra
    >>> suite = ra.synthetic_suite(3, seed=1)
    >>> len(suite), suite.names[0]
    (3, 'rdk-s1-000')
    """
    from rockarch.motion.synthetic import synthetic_suite as _synthetic_suite

    kw = {k: v for k, v in (("dt", dt), ("f_corner", f_corner)) if v is not None}
    return _synthetic_suite(n, seed, pulse_fraction=pulse_fraction, **kw)


def oas(sys_, motion: GroundMotion, *, p, ratio, tol: float | None = None,
        progress: bool = False, executor=None, store=None):
    """Overturning acceleration spectrum (OAS) of a system for one ground-motion shape.

    At every (p, ratio) of the grid the structure, at frequency parameter p, is excited by
    the motion scaled to a peak ground acceleration ap = ratio·ap,min (docs/theory.md §2,
    Eq. (2.1)); the boundary is the lowest overturning ratio at each p (Eq. (2.2)), refined
    by bisection. The same computation as ``rockarch oas``
    (:func:`rockarch.spectra.oas.compute_oas`).

    Parameters
    ----------
    sys_ : BlockSystem, MechanismSystem or MDOFSystem
        The structure, from :func:`rockarch.system`. A block is taken at each p with its
        alpha; any other structure is scaled geometrically to each p (size ∝ 1/p²,
        docs/theory.md Eq. (11.33)), its ap,min unchanged.
    motion : GroundMotion
        The ground motion (:func:`rockarch.pulse`, :func:`rockarch.read_record`,
        :func:`rockarch.el_centro`); only its shape matters: each run scales it to a peak
        |a_g| of ratio·ap,min [m/s²].
    p : float or array-like
        Frequency parameters [1/s]: > 0, strictly increasing.
    ratio : float or array-like
        Peak ground acceleration over the structure's ap,min [-]: >= 0, strictly
        increasing.
    tol : float, optional
        Bisection tolerance of the boundary, in ratio units (default 1e-3,
        :data:`rockarch.core.constants.OAS_TOL`); 0: the boundary is the first overturning
        grid value.
    progress : bool
        Show a progress bar on stderr.
    executor : None, str or rockarch.core.sweep.Executor
        Where the simulations run: None (default) in this process with numba threads on
        every core; ``"serial"`` or ``"processes"`` (a pool of local processes); or an
        :class:`~rockarch.core.sweep.Executor`. For Dask give an Executor, not the string
        ``"dask"``: ``Executor(dask_workers=n)`` (a local cluster of n workers) or
        ``Executor(scheduler="tcp://HOST:PORT")``, used as a context manager.
    store : None, bool, path or rockarch.core.sweep.Store
        Resumable store of finished chunks (True: the default cache directory; None or
        False: none); a rerun reuses every stored chunk, bit for bit (docs/sweeps.md).

    Returns
    -------
    xarray.Dataset
        ``overturned`` (p, ratio): bool; ``max_response`` (p, ratio): the largest rotation
        over its overturning value [-] (1 at collapse); ``boundary`` (p): the lowest
        overturning ratio [-], NaN where no ratio of the grid overturns. Coordinates ``p``
        [1/s] and ``ratio`` [-]; the structure's parameters as attributes ``system_*``
        (their units in the attribute ``attribute_units``). Save it with
        :func:`rockarch.spectra.oas.save`.

    Raises
    ------
    TypeError
        If ``sys_`` is not a system or ``motion`` not a GroundMotion.
    ValueError
        If a grid is empty, not finite or not strictly increasing, a p <= 0 or a
        ratio < 0, the grid has more simulations than the limit (docs/limits.md), or
        ``executor`` is not one of the forms above (the string ``"dask"`` included).

    Examples
    --------
    >>> import numpy as np
    >>> import rockarch as ra
    >>> ds = ra.oas(ra.system("block", alpha=0.1), ra.pulse("sine", period=0.5),
    ...             p=[1.0, 2.0], ratio=np.linspace(1.0, 5.0, 9))
    >>> ds["boundary"].dims, ds["overturned"].shape
    (('p',), (2, 9))
    """
    from rockarch.core.validate import numbers
    from rockarch.systems import check_motion, check_system

    check_system(sys_)
    check_motion(motion)
    kw = {} if tol is None else {"tol": _number("tol", tol)}
    return _compute_oas(sys_, motion, numbers("p", p), numbers("ratio", ratio),
                        progress=progress, executor=executor, store=store, **kw)


__all__ = ["G", "KINDS", "SIGNALS", "Batch", "GroundMotion", "Response", "Suite", "__version__",
           "batch", "design_system", "el_centro", "make_arch", "oas", "pulse", "read_record",
           "read_suite", "simulate", "synthetic_suite", "system"]
