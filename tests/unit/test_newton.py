"""The backtracking line search's step length (exubrush.run.newton.backtrack) on residual
profiles whose answer follows from Armijo's condition by hand."""

import pytest

from exubrush.run.newton import SHORTEST, SUFFICIENT_DECREASE, backtrack


def _profile(residual):
    """residual_at for backtrack, recording the step lengths it was asked for."""
    asked = []

    def residual_at(alpha):
        asked.append(alpha)
        return residual(alpha)

    return residual_at, asked


def test_a_sufficient_full_update_is_kept_without_trials():
    residual_at, asked = _profile(lambda alpha: 1.0 - 0.9 * alpha)
    assert backtrack(residual_at, 1.0, 0.1) == (1.0, 0.1, 0)
    assert asked == []


def test_an_overshooting_update_is_halved_until_the_residual_falls():
    # the residual along the update is |1 − 3α|: the full update overshoots to 2, half of
    # it reaches 0.5 ≤ 1 − c/2, the first halving that satisfies Armijo's condition
    residual_at, asked = _profile(lambda alpha: abs(1.0 - 3.0 * alpha))
    assert backtrack(residual_at, 1.0, 2.0) == (0.5, 0.5, 1)
    assert asked == [0.5]


def test_a_far_overshoot_takes_several_halvings():
    # |1 − 20α|: 1/2 gives 9, 1/4 gives 4, 1/8 gives 1.5, 1/16 gives 0.25
    residual_at, asked = _profile(lambda alpha: abs(1.0 - 20.0 * alpha))
    alpha, residual, trials = backtrack(residual_at, 1.0, 19.0)
    assert (alpha, residual, trials) == (1.0 / 16.0, 0.25, 4)
    assert asked == [0.5, 0.25, 0.125, 0.0625]


def test_without_a_sufficient_step_the_smallest_residual_is_kept():
    # rises along the whole update: no α satisfies Armijo's condition; the shortest trial
    # (SHORTEST) has the smallest residual
    residual_at, asked = _profile(lambda alpha: 1.0 + alpha)
    alpha, residual, trials = backtrack(residual_at, 1.0, 2.0)
    assert alpha == SHORTEST and residual == pytest.approx(1.0 + SHORTEST)
    assert trials == len(asked) == 6


def test_a_full_update_that_beats_every_shorter_one_is_kept_when_none_suffices():
    # the residual barely falls at α = 1 (not by c·α) and is higher at every halving
    barely = 1.0 - 0.5 * SUFFICIENT_DECREASE
    residual_at, _ = _profile(lambda alpha: barely if alpha == 1.0 else 1.5)
    assert backtrack(residual_at, 1.0, barely)[:2] == (1.0, barely)


def test_a_nan_residual_counts_as_not_sufficient():
    # a diverged trial (nan) is never kept: the next halving is
    residual_at, _ = _profile(lambda alpha: float("nan") if alpha > 0.3 else 0.5)
    assert backtrack(residual_at, 1.0, float("nan"))[:2] == (0.25, 0.5)


def test_a_nan_full_update_loses_to_any_finite_trial():
    # no trial is sufficient (3 > 1); the first finite one is kept, not the nan
    residual_at, _ = _profile(lambda alpha: 3.0 if alpha < 1.0 else float("nan"))
    assert backtrack(residual_at, 1.0, float("nan"))[:2] == (0.5, 3.0)
