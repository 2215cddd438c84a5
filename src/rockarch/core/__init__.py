"""Shared vocabulary and machinery of every stage (the lowest stage; imports no other).

Theory: docs/theory.md §0 (conventions, constants), §8 (work limits).

Constants, argument checks, work limits, the :class:`~rockarch.core.response.Response` of a
simulation, output paths and atomic writes, the numba cache, and the sweep engine.
Modules: :mod:`~rockarch.core.constants` (g, time-step factors, tolerances),
:mod:`~rockarch.core.validate` (one-line checks of arguments),
:mod:`~rockarch.core.limits` (memory and work estimated before allocating),
:mod:`~rockarch.core.response` (``Response``, ``Batch``), :mod:`~rockarch.core.paths`
(output formats, the output-path check, atomic and staged writes),
:mod:`~rockarch.core.jit_cache` (numba's cache keyed by the source digest),
:mod:`~rockarch.core.console` (warnings as one line on stderr) and
:mod:`~rockarch.core.sweep` (how sweeps run and where finished chunks are kept; docs/sweeps.md).
"""

__version__ = "0.1.0"
