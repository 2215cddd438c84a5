"""How often does a joint of a voussoir chain open at both corners? (docs/theory.md §9)

    PYTHONPATH=src .venv/bin/python validation/open_joints.py

The chain stepper keeps a joint's no-slip row even when both its corners are open, the
general stepper lets such a joint separate (the limit mu -> inf of Coulomb's cone). The two
models differ only in the steps where a joint is open at both corners; this counts them for
the 20-voussoir catenary (l = 10, f = 3, d = 0.25) and circular (l = 10, f = 2.89,
d = 0.35) arches under El Centro at 1-3·ap,min and sine pulses, up to collapse.
"""

from __future__ import annotations

from rockarch import mdof
from rockarch.arch import catenary, circular
from rockarch.motion import signals as motion
from rockarch.motion.records import el_centro


def main() -> None:
    rec = el_centro()
    for label, shape in (("catenary", catenary(10.0, 3.0, 0.25)),
                         ("circular", circular(10.0, 2.89, 0.35))):
        a = mdof.arch_assembly(shape, 20)
        runs = [(f"El Centro {k:g}·ap,min", rec.scaled(k * a.ap_min / rec.pga))
                for k in (1.0, 1.5, 2.0, 3.0)]
        runs += [(f"sine T = {T:g} s, {k:g}·ap,min",
                  motion.sine(1.0, T).scaled_to_pga(k * a.ap_min))
                 for T in (0.5, 1.0, 2.0) for k in (1.5, 3.0)]
        for name, m in runs:
            r = mdof.simulate(a, m, t_free=1.0)
            n = int((r.joints == 3).any(axis=1).sum())
            print(f"{label}, {name}: overturned {r.overturned}; steps with a joint open at "
                  f"both corners: {n} of {r.joints.shape[0]}", flush=True)


if __name__ == "__main__":
    main()
