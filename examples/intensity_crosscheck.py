"""Cross-check rockarch's Sa(T), D5-95, Arias against eqsig and pyrotd on El Centro 180.

Neither library is a rockarch dependency; install them anywhere on sys.path first, e.g.::

    pip install --target /tmp/ext --no-deps eqsig pyrotd
    PYTHONPATH=/tmp/ext python examples/intensity_crosscheck.py

Prints the relative difference of each library's 5 %-damped Sa at 11 periods (docs/sites.md
quotes the result).
"""

from __future__ import annotations

import numpy as np

from rockarch.motion import intensity as im
from rockarch.motion.records import el_centro

PERIODS = np.array([0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 5.0])


def main() -> None:
    m = el_centro()
    dt, acc = im.uniform_samples(m)
    ours = im.spectral_acceleration(m, PERIODS)
    print("T [s]      " + " ".join(f"{t:7.2f}" for t in PERIODS))
    print("Sa [m/s2]  " + " ".join(f"{s:7.3f}" for s in ours))
    try:
        import eqsig

        rec = eqsig.AccSignal(acc, dt)
        rec.generate_response_spectrum(response_times=PERIODS, xi=im.DAMPING)
        print("eqsig/ours " + " ".join(f"{r:7.4f}" for r in rec.s_a / ours))
        d = eqsig.im.calc_sig_dur(rec, start=0.05, end=0.95)
        print(f"D5-95: eqsig {d:.3f} s, rockarch {im.significant_duration(m):.3f} s")
        ia = eqsig.im.calc_arias_intensity(rec)[-1]
        print(f"Arias: eqsig {ia:.4f} m/s, rockarch {im.arias(m):.4f} m/s")
    except ImportError:
        print("eqsig not installed")
    try:
        import pyrotd

        res = pyrotd.calc_spec_accels(dt, acc, 1.0 / PERIODS, im.DAMPING)
        print("pyrotd/ours " + " ".join(f"{r:7.4f}" for r in res["spec_accel"] / ours))
    except ImportError:
        print("pyrotd not installed")


if __name__ == "__main__":
    main()
