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
part). A second table takes H where no joint slides (symmetric) with the walls' own
pattern (three rows per joint on the unknowns of its two bodies, in the engine's body order)
and adds the symmetric factorisations: LAPACK's banded Cholesky
(``scipy.linalg.solveh_banded``, pbsv) and QDLDL (the LDLᵀ of OSQP, with its AMD order;
``qdldl.Solver`` anew, and ``update``, which keeps the symbolic analysis of the same
pattern), where the ``qdldl`` package is installed (``make bench`` installs it).

    .venv/bin/python benchmarks/lu_choice.py      # ~30 s
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


def band_solver(a: np.ndarray, kd: int, x: np.ndarray):
    """rockarch's band LU and solve of a·y = x, as a function of nothing (to be timed)."""
    n = a.shape[0]
    band = to_band(a, kd)
    row = np.zeros(kd + 1)

    def ours():
        f = band.copy()
        band_lu(n, f, kd, row)
        y = x.copy()
        band_lu_solve(n, f, kd, y)
        return y

    return ours


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
    ours = band_solver(a, kd, x)

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


def wall_matrix(w, pos: np.ndarray, rng) -> np.ndarray:
    """H = M + 100·Σ rowᵀrow of a wall where no joint slides: three random rows per joint on
    the unknowns of its two bodies, the bodies at their places ``pos`` of the body order."""
    n = 3 * w.n_blocks
    a = np.diag(rng.uniform(1.0, 2.0, n))
    for ba, bb in zip(w.body_a, w.body_b, strict=True):
        idx = np.array([3 * pos[b] + c for b in (ba, bb) if b >= 0 for c in range(3)])
        for _ in range(3):
            row = rng.normal(size=idx.size)
            a[np.ix_(idx, idx)] += 1e2 * np.outer(row, row)
    return a


def one_wall_symmetric(courses: int, cols: int, rng) -> str:
    """The row of the second table: H of the wall's pattern, symmetric."""
    from rockarch.mdof.kernel_data import graph_model

    w = bd.wall(courses, cols, 0.4, 0.2, mu=0.6)
    gm = graph_model(w)
    kd = int(gm.kbody)
    n = 3 * w.n_blocks
    a = wall_matrix(w, gm.bpos, rng)
    x = rng.normal(size=n)
    ours = band_solver(a, kd, x)

    upper = np.zeros((kd + 1, n))  # the upper band, as solveh_banded wants it
    for j in range(n):
        for i in range(max(0, j - kd), j + 1):
            upper[kd + i - j, j] = a[i, j]

    def pbsv():
        return sla.solveh_banded(upper, x, check_finite=False)

    fns = [ours, pbsv]
    try:
        import qdldl
    except ImportError:
        qdldl = None
    if qdldl is not None:
        csc = sp.csc_matrix(a)
        kept = qdldl.Solver(csc)

        def ldl_new():
            return qdldl.Solver(csc).solve(x)

        def ldl_update():
            kept.update(csc)
            return kept.solve(x)

        fns += [ldl_new, ldl_update]
    ours()
    ys = [f() for f in fns]
    diff = max(np.abs(ys[0] - y).max() for y in ys[1:]) / np.abs(ys[1]).max()
    reps = 200 if n < 300 else 50
    t = [f"{1e6 * best(f, reps):.0f}" for f in fns] + ["not installed"] * (4 - len(fns))
    return f"| wall {courses} x {cols} | {n} | {kd} | {' | '.join(t)} | {diff:.1e} |"


def main() -> None:
    rng = np.random.default_rng(0)
    print("| matrix | unknowns | half-bandwidth | rockarch band LU [µs] | LAPACK gbsv [µs] "
          "| SuperLU [µs] | largest difference of the solutions |")
    print("|---|---|---|---|---|---|---|")
    for courses, cols in ((4, 10), (20, 10)):
        print(one_wall(courses, cols, rng), flush=True)
    print("\nsymmetric (no joint sliding), the walls' own pattern:")
    print("| matrix | unknowns | half-bandwidth | rockarch band LU [µs] | LAPACK pbsv [µs] "
          "| QDLDL anew [µs] | QDLDL update [µs] | largest difference of the solutions |")
    print("|---|---|---|---|---|---|---|---|")
    for courses, cols in ((4, 10), (20, 10)):
        print(one_wall_symmetric(courses, cols, rng), flush=True)


if __name__ == "__main__":
    main()
