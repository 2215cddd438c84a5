"""Which factorisation for the contact solve's H = M + Σ ε⁻¹·JᵀJ (docs/performance.md)?

The semismooth Newton solve (docs/theory.md Eqs. (9.7)–(9.9)) factorises H, banded in the
bodies' order and non-symmetric where joints slide, once per change of the rows' states:
up to tens of times per step. This times one factorisation plus one solve, on the same
matrices, by

- rockarch's banded LU without pivoting (numba, ``contact_solver.band_lu``);
- LAPACK's banded LU with partial pivoting (``scipy.linalg.solve_banded``, gbsv);
- SuperLU (``scipy.sparse.linalg.splu``) on the CSC matrix, its default column order;

on matrices of H's size, half-bandwidth (that of the engine's body order for two walls:
42 blocks, 4 courses of 10, and 210 blocks, 20 courses of 10, of 0.4 x 0.2 m) and scale
(a unit mass diagonal plus 100 times the rows' outer products, a small non-symmetric
part).

    .venv/bin/python benchmarks/lu_choice.py      # ~20 s
"""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from rockarch.mdof import builders as bd
from rockarch.mdof.contact_solver import band_lu, band_lu_solve


def banded_matrix(n: int, kd: int, rng) -> np.ndarray:
    """A dense n x n matrix with H's pattern and scale: M (diagonal) plus ε⁻¹·JᵀJ of random
    rows coupling unknowns at most kd apart, plus a small non-symmetric part (sliding
    rows)."""
    a = np.diag(rng.uniform(1.0, 2.0, n))
    for _ in range(3 * n):
        i = rng.integers(0, n)
        js = np.clip(i + rng.integers(0, kd + 1, 6), 0, n - 1)
        row = np.zeros(n)
        row[js] = rng.normal(size=6)
        a += 1e2 * np.outer(row, row)
        a[i, js[0]] += 10.0 * rng.normal()
    return a


def to_band(a: np.ndarray, kd: int) -> np.ndarray:
    n = a.shape[0]
    b = np.zeros((n, 2 * kd + 1))
    for i in range(n):
        for j in range(max(0, i - kd), min(n, i + kd + 1)):
            b[i, kd + j - i] = a[i, j]
    return b


def best(fn, reps: int) -> float:
    out = []
    for _ in range(reps):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return min(out)


def one_wall(courses: int, cols: int, rng) -> str:
    """The table row of one wall's matrix."""
    from rockarch.mdof.kernel_data import graph_model

    w = bd.wall(courses, cols, 0.4, 0.2, mu=0.6)
    kd = int(graph_model(w).kbody)
    n = 3 * w.n_blocks
    a = banded_matrix(n, kd, rng)
    x = rng.normal(size=n)
    band = to_band(a, kd)
    row = np.zeros(kd + 1)

    def ours():
        f = band.copy()
        band_lu(n, f, kd, row)
        y = x.copy()
        band_lu_solve(n, f, kd, y)
        return y

    ab = np.zeros((2 * kd + 1, n))
    for i in range(n):
        for j in range(max(0, i - kd), min(n, i + kd + 1)):
            ab[kd + i - j, j] = a[i, j]

    def lapack():
        return sla.solve_banded((kd, kd), ab, x, check_finite=False)

    csc = sp.csc_matrix(a)

    def superlu():
        return spla.splu(csc).solve(x)

    ours()  # compiled
    y0, y1, y2 = ours(), lapack(), superlu()
    diff = max(np.abs(y0 - y1).max(), np.abs(y0 - y2).max()) / np.abs(y1).max()
    reps = 200 if n < 300 else 50
    t = [1e6 * best(f, reps) for f in (ours, lapack, superlu)]
    return (f"| wall {courses} x {cols} | {n} | {kd} | {t[0]:.0f} | {t[1]:.0f} | {t[2]:.0f} "
            f"| {diff:.1e} |")


def main() -> None:
    rng = np.random.default_rng(0)
    print("| matrix | unknowns | half-bandwidth | rockarch band LU [µs] | LAPACK gbsv [µs] "
          "| SuperLU [µs] | largest difference of the solutions |")
    print("|---|---|---|---|---|---|---|")
    for courses, cols in ((4, 10), (20, 10)):
        print(one_wall(courses, cols, rng), flush=True)


if __name__ == "__main__":
    main()
