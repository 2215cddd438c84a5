"""Ground motion (docs/theory.md §8, §11.1): signals and pulses
(:mod:`~rockarch.motion.signals`), record readers and the bundled El Centro 1940 record
(:mod:`~rockarch.motion.records`, data in ``motion/data/``), suites of records with their
NGA-West2 metadata (:mod:`~rockarch.motion.suite`), intensity measures
(:mod:`~rockarch.motion.intensity` and its kernels), velocity pulses
(:mod:`~rockarch.motion.velocity_pulse`) and synthetic records
(:mod:`~rockarch.motion.synthetic`)."""
