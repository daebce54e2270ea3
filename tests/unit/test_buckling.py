"""The PRB link's axial law against Euler's buckling load and the exact post-buckled
clamped-pinned elastica (exubrush.reference.buckled_column)."""

import math

import numpy as np
import pytest

from exubrush.models.buckling import (
    CLAMPED_PINNED_BETA,
    PEAK_SHORTENING,
    SMOOTHING,
    axial_force,
    clamped_pinned_load,
    postbuckling_ratio,
)
from exubrush.reference.buckled_column import clamped_pinned_load_index

EULER_CLAMPED_PINNED = 20.1907  # β² = 2.046 π² (Timoshenko & Gere 1961, §2.5)


def test_the_buckling_load_is_eulers_clamped_pinned_load():
    assert math.tan(CLAMPED_PINNED_BETA) == pytest.approx(CLAMPED_PINNED_BETA, rel=1e-12)
    assert clamped_pinned_load(1.0, 1.0) == pytest.approx(EULER_CLAMPED_PINNED, rel=1e-5)
    assert clamped_pinned_load(0.1215, 5.0) == pytest.approx(2.0457 * math.pi**2 * 0.1215 / 25,
                                                             rel=1e-4)


def test_the_exact_column_starts_at_eulers_load_and_peaks():
    # at a chord shortening of 1e-4 the elastica's load is Euler's within 1e-4 (its
    # post-buckling slope is ~0.38 per unit shortening)
    assert clamped_pinned_load_index(1e-4) / EULER_CLAMPED_PINNED == pytest.approx(1.0, abs=1e-4)
    loads = [clamped_pinned_load_index(x) for x in (0.4, PEAK_SHORTENING, 0.5)]
    assert loads[1] > loads[0] and loads[1] > loads[2]


@pytest.mark.parametrize("x", [0.02, 0.05, 0.1, 0.2, 0.3, 0.4, PEAK_SHORTENING])
def test_the_fitted_branch_follows_the_exact_elastica(x):
    exact = clamped_pinned_load_index(x) / CLAMPED_PINNED_BETA**2
    # 0.25 %: the cubic's least-squares residual up to the peak is 0.2 %
    assert postbuckling_ratio(x) == pytest.approx(exact, rel=2.5e-3)


def test_the_branch_is_smooth_and_held_beyond_the_peak():
    h = 1e-7
    for x in (0.0, PEAK_SHORTENING):  # where its pieces meet: value and slope continuous
        left = (postbuckling_ratio(x) - postbuckling_ratio(x - h)) / h
        right = (postbuckling_ratio(x + h) - postbuckling_ratio(x)) / h
        assert left == pytest.approx(right, abs=1e-5)
    assert postbuckling_ratio(0.6) == postbuckling_ratio(PEAK_SHORTENING)
    assert postbuckling_ratio(0.0) == 1.0


def test_the_axial_force_is_linear_below_buckling_and_on_the_branch_beyond():
    stiffness, load, length = 0.81, 0.098, 5.0  # default bristle: EA/L, P_b, L
    onset = load / stiffness
    assert axial_force(0.0, stiffness, load, length) == 0.0
    for s in (-0.5, -0.01, 0.2 * onset, 0.5 * onset):
        # the smooth minimum shifts the linear branch by at most ε²/(4 (P_b - F)) + F(0)
        assert axial_force(s, stiffness, load, length) == pytest.approx(
            stiffness * s, abs=SMOOTHING**2 * load / 2)
    for s in (3 * onset, 0.5 * length, 2.0 * length):
        expected = load * postbuckling_ratio((s - onset) / length)
        assert axial_force(s, stiffness, load, length) == pytest.approx(
            expected, abs=SMOOTHING**2 * load / 2)
    peak = onset + PEAK_SHORTENING * length
    forces = [axial_force(s, stiffness, load, length) for s in np.linspace(-1, peak, 401)]
    assert np.all(np.diff(forces) > 0.0)  # never softens to a negative stiffness ...
    beyond = [axial_force(s, stiffness, load, length) for s in (peak + 0.1, peak + 5.0)]
    # ... and holds the peak (up to the smooth minimum's shift, as above)
    assert beyond == pytest.approx([forces[-1]] * 2, abs=SMOOTHING**2 * load / 2)


def test_the_axial_force_runs_in_exudyns_symbolic_back_end():
    exu = pytest.importorskip("exudyn")
    symbol = exu.symbolic.Real("s", 0.0)  # a named Real is a variable of the expression
    expression = axial_force(symbol, 0.81, 0.098, 5.0, exu.symbolic)
    for s in (-0.2, 0.05, 0.3, 2.0):
        symbol.SetValue(s)
        assert expression.Evaluate() == pytest.approx(axial_force(s, 0.81, 0.098, 5.0),
                                                      rel=1e-12)
