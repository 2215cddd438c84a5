"""Ground motion: pulses, records, suites, intensity measures, velocity pulses, synthetics.

Theory: docs/theory.md §8 (excitations), §11.1 (intensity measures, synthetic records,
velocity pulses).

Signals and pulses (:mod:`~rockarch.motion.signals`; ``ra.pulse``), record readers and the
bundled El Centro 1940 record (:mod:`~rockarch.motion.records`, data in ``motion/data/``),
suites of records with their NGA-West2 metadata (:mod:`~rockarch.motion.suite`), intensity
measures (:mod:`~rockarch.motion.intensity` and its kernels), velocity pulses
(:mod:`~rockarch.motion.velocity_pulse`) and synthetic records
(:mod:`~rockarch.motion.synthetic`). Users' guide: docs/sites.md."""
