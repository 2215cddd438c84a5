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


def synthetic_suite(n: int, seed: int = 0, **kw) -> Suite:
    """A :class:`Suite` of ``n`` seeded synthetic records (Rezaeian & Der Kiureghian model,
    parameters from their 2010 fitted distributions;
    :func:`rockarch.motion.synthetic.synthetic_suite`)."""
    from rockarch.motion.synthetic import synthetic_suite as _synthetic_suite

    return _synthetic_suite(n, seed, **kw)


def oas(sys_, motion: GroundMotion, *, p, ratio, tol: float | None = None,
        progress: bool = False, executor=None, store=None):
    """OAS of a system for the motion's shape over p × ratio (docs/theory.md Eqs. 2.1–2.2).

    The same computation as ``rockarch oas`` (which passes the same grids); see
    :func:`rockarch.spectra.oas.compute_oas` for the executor and store options.
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
