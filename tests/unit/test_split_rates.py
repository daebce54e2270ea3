"""The coupling rates of validation/benchmarks/split_rates.py: block Jacobi's and block
Gauss-Seidel's spectral radii, against the iteration matrices worked by hand and against
the sweeps themselves."""

import math

import numpy as np
import pytest


@pytest.fixture
def script(benchmark_script):
    return benchmark_script("split_rates")


def test_two_scalar_blocks_have_the_textbook_radii(script):
    # [[2, -1], [-1, 2]]: Jacobi's iteration matrix [[0, 1/2], [1/2, 0]] (radius 1/2),
    # Gauss-Seidel's [[0, 1/2], [0, 1/4]] (radius 1/4, Jacobi's squared)
    jacobi, gauss_seidel, coupled = script.block_rates(
        np.array([[2.0, -1.0], [-1.0, 2.0]]), np.array([0, 1]))
    assert jacobi == pytest.approx(0.5, rel=1e-12)
    assert gauss_seidel == pytest.approx(0.25, rel=1e-12)
    assert coupled == 2


def test_blocks_that_do_not_touch_converge_in_one_sweep(script):
    matrix = np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 5.0]])
    jacobi, gauss_seidel, coupled = script.block_rates(matrix, np.array([0, 0, 1]))
    assert jacobi == pytest.approx(0.0, abs=1e-14)
    assert gauss_seidel == pytest.approx(0.0, abs=1e-14)
    assert coupled == 0


def test_radii_are_the_rates_the_sweeps_show(script):
    # three blocks of two, interleaved in the matrix's order (radii about 0.84 and 0.60):
    # the sweeps themselves shrink the error at the radii the function gives
    rng = np.random.default_rng(3)
    matrix = rng.normal(size=(6, 6)) + 2.4 * np.eye(6)
    owner = np.array([2, 0, 1, 2, 0, 1])
    jacobi, gauss_seidel, _ = script.block_rates(matrix, owner)
    solution = rng.normal(size=6)
    right = matrix @ solution
    blocks = [np.nonzero(owner == b)[0] for b in range(3)]

    def sweep(x, newest):
        new = x.copy()
        for rows in blocks:
            source = new if newest else x
            rest = right[rows] - matrix[rows] @ source + matrix[np.ix_(rows, rows)] @ source[rows]
            new[rows] = np.linalg.solve(matrix[np.ix_(rows, rows)], rest)
        return new

    for newest, radius in ((False, jacobi), (True, gauss_seidel)):
        x = np.zeros(6)
        errors = []
        for _ in range(40):
            x = sweep(x, newest)
            errors.append(np.linalg.norm(x - solution))
        observed = (errors[39] / errors[9]) ** (1.0 / 30)
        # the error's asymptotic rate is the radius; the next modes (Jacobi's next at 0.78,
        # a complex pair for Gauss-Seidel) still bend the mean rate of sweeps 10 to 40 by
        # 2 %, and the errors stay far above rounding (0.60**40 is 1e-9)
        assert observed == pytest.approx(radius, rel=5e-2)


def test_sweeps_for_a_reduction(script):
    assert script.sweeps(0.5, 1e-3) == 10  # 0.5**10 < 1e-3 < 0.5**9
    assert script.sweeps(1.0, 1e-3) == math.inf
    assert script.sweeps(0.0, 1e-6) == 1


def test_accelerated_sweeps_end_within_the_distinct_eigenvalues(script):
    # GMRES stops, exactly, after as many iterations as the preconditioned matrix has
    # distinct eigenvalues: D⁻¹A of [[2, -1], [-1, 2]] has 1/2 and 3/2, blocks that do
    # not touch have only 1
    pair = np.array([[2.0, -1.0], [-1.0, 2.0]])
    assert script.accelerated_sweeps(pair, np.array([0, 1]), 1e-10) == 2
    apart = np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 5.0]])
    assert script.accelerated_sweeps(apart, np.array([0, 0, 1]), 1e-10) == 1
