"""Rigid rocking blocks and SDOF rocking mechanisms in motion.

Theory: docs/theory.md §1 (Housner's block), §3 (SDOF mechanisms), §5 (the four-hinge arch
in motion).

Housner's block (:mod:`~rockarch.rocking.block`) and its event-driven numba kernel
(:mod:`~rockarch.rocking.kernels`), generic SDOF mechanisms and the rocking frame
(:mod:`~rockarch.rocking.mechanism`), the four-hinge arch in motion with its exact linkage
kinematics (:mod:`~rockarch.rocking.fourhinge_motion`). Users' guides: docs/block.md,
docs/mechanism.md."""
