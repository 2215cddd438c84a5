"""Rigid rocking blocks and SDOF rocking mechanisms (docs/theory.md §1, §3, §5): Housner's
block (:mod:`~rockarch.rocking.block`) and its event-driven numba kernel
(:mod:`~rockarch.rocking.kernels`), generic SDOF mechanisms and the rocking frame
(:mod:`~rockarch.rocking.mechanism`), the four-hinge arch in motion with its exact linkage
kinematics (:mod:`~rockarch.rocking.fourhinge_motion`)."""
