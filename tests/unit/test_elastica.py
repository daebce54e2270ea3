"""Tests of the exact cantilever elastica against independent references.

The references are linear beam theory with its first nonlinear correction
and the closed-form elliptic-integral solutions of the elastica, evaluated
here with :mod:`scipy.special`; none of them reuses the shooting code under
test.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

from exubrush.reference.elastica import ElasticaSolution, solve_cantilever

# Both the shooting solver and the elliptic-integral formulas reproduce the
# tip coordinates to about 1e-12 of L (measured); 1e-8 is the documented
# accuracy target of the reference and leaves a wide margin.
TIP_TOL = 1e-8


def transverse_tip_reference(alpha):
    """Tip of a cantilever under a transverse dead load, by elliptic integrals.

    With the tip angle ``theta_1`` the first integral of the elastica is
    ``theta'**2 = 2 alpha (sin(theta_1) - sin(theta))``.  Substituting
    ``1 + sin(theta) = 2 k**2 sin(phi)**2`` with
    ``k**2 = (1 + sin(theta_1)) / 2`` turns the arc length into
    ``ds = dphi / (sqrt(alpha) sqrt(1 - k**2 sin(phi)**2))`` with ``phi``
    running from ``phi_1 = arcsin(1 / (k sqrt(2)))`` at the clamp to
    ``pi/2`` at the tip.  Hence (Bisshopp & Drucker 1945)::

        sqrt(alpha) = K(k) - F(phi_1, k)
        x_1 = sqrt(2 sin(theta_1) / alpha)
        y_1 = 1 - 2 (E(k) - E(phi_1, k)) / sqrt(alpha)

    Parameters
    ----------
    alpha : float
        Load index ``P L**2 / (E I)`` [-], positive.

    Returns
    -------
    tuple of float
        ``x_1 / L`` [-], ``y_1 / L`` [-] and the tip angle [rad].
    """
    root = math.sqrt(alpha)

    def mismatch(m):
        phi_1 = math.asin(1.0 / math.sqrt(2.0 * m))
        return ellipk(m) - ellipkinc(phi_1, m) - root

    # scipy uses the parameter m = k**2; m = 1/2 is the unloaded beam.
    m = brentq(mismatch, 0.5, 1.0 - 1e-16, xtol=1e-16, rtol=1e-15)
    phi_1 = math.asin(1.0 / math.sqrt(2.0 * m))
    sin_tip = 2.0 * m - 1.0
    x_tip = math.sqrt(2.0 * sin_tip / alpha)
    y_tip = 1.0 - 2.0 * (ellipe(m) - ellipeinc(phi_1, m)) / root
    return x_tip, y_tip, math.asin(sin_tip)


def compressed_tip_reference(alpha):
    """Tip of the buckled cantilever under axial compression (``a = pi``).

    The first integral is ``theta'**2 = 2 alpha (cos(theta) - cos(theta_1))``;
    with ``p = sin(theta_1 / 2)`` and ``sin(theta / 2) = p sin(phi)`` the
    classical post-buckling solution (Timoshenko & Gere, sec. 2.7) reads
    ``sqrt(alpha) = K(p)``, ``x_1 = 2 E(p) / K(p) - 1`` and
    ``y_1 = 2 p / sqrt(alpha)``.

    Parameters
    ----------
    alpha : float
        Load index ``P L**2 / (E I)`` [-], above ``pi**2 / 4``.

    Returns
    -------
    tuple of float
        ``x_1 / L`` [-] and ``y_1 / L`` [-] of the mode bent towards ``+y``.
    """
    m = brentq(
        lambda m: ellipk(m) - math.sqrt(alpha),
        0.0,
        1.0 - 1e-16,
        xtol=1e-16,
        rtol=1e-15,
    )
    return 2.0 * ellipe(m) / ellipk(m) - 1.0, 2.0 * math.sqrt(m / alpha)


def test_small_load_matches_linear_beam_theory():
    # A regular perturbation of theta'' = -alpha cos(theta) gives
    # y_1 = alpha/3 - 4 alpha**3 / 105 + O(alpha**5) and
    # x_1 = 1 - alpha**2 / 15 + O(alpha**4).  The tolerances bound the first
    # neglected terms (|4/105| < 1/10) and are far above solver round-off.
    alpha = 1e-3
    sol = solve_cantilever(alpha)
    assert sol.tip_y == pytest.approx(alpha / 3.0, rel=0.0, abs=alpha**3 / 10)
    assert 1.0 - sol.tip_x == pytest.approx(alpha**2 / 15.0, abs=alpha**3)
    assert sol.tip_angle == pytest.approx(alpha / 2.0, abs=alpha**3)


def test_elliptic_reference_has_linear_limit():
    # Guards the reference itself against a convention error.
    alpha = 1e-3
    x_tip, y_tip, _ = transverse_tip_reference(alpha)
    assert y_tip == pytest.approx(alpha / 3.0, abs=alpha**3 / 10)
    assert 1.0 - x_tip == pytest.approx(alpha**2 / 15.0, abs=alpha**3)


@pytest.mark.parametrize("alpha", [1.0, 2.0, 5.0, 10.0, 20.0])
def test_transverse_load_matches_elliptic_integrals(alpha):
    x_ref, y_ref, angle_ref = transverse_tip_reference(alpha)
    sol = solve_cantilever(alpha, np.pi / 2)
    assert sol.tip_x == pytest.approx(x_ref, abs=TIP_TOL)
    assert sol.tip_y == pytest.approx(y_ref, abs=TIP_TOL)
    assert sol.tip_angle == pytest.approx(angle_ref, abs=TIP_TOL)


def test_commonly_quoted_value_for_unit_load_index():
    # Tip of the classical large-deflection table at P L**2 / (E I) = 1.
    sol = solve_cantilever(1.0)
    assert round(sol.tip_x, 4) == 0.9436
    assert round(sol.tip_y, 4) == 0.3017


@pytest.mark.parametrize("alpha", [2.5, 5.0, 20.0])
def test_compression_above_euler_load_gives_first_buckling_mode(alpha):
    x_ref, y_ref = compressed_tip_reference(alpha)
    sol = solve_cantilever(alpha, np.pi)
    assert sol.tip_x == pytest.approx(x_ref, abs=TIP_TOL)
    assert sol.tip_y == pytest.approx(y_ref, abs=TIP_TOL)


def test_compression_below_euler_load_stays_straight():
    sol = solve_cantilever(0.99 * np.pi**2 / 4, np.pi)
    np.testing.assert_array_equal(sol.theta, 0.0)
    assert (sol.tip_x, sol.tip_y) == (1.0, 0.0)


def test_branch_guess_reaches_mirror_image():
    upper = solve_cantilever(5.0, np.pi)
    lower = solve_cantilever(5.0, np.pi, branch_guess=-3.0)
    assert lower.tip_x == pytest.approx(upper.tip_x, abs=TIP_TOL)
    assert lower.tip_y == pytest.approx(-upper.tip_y, abs=TIP_TOL)


def test_centreline_is_inextensible():
    # The chord of a polyline segment of length h with curvature kappa is
    # shorter than the arc by about kappa**2 h**3 / 24.  Since
    # theta'**2 = 2 alpha (sin(theta_1) - sin(theta)) <= 2 alpha, the total
    # shortfall is at most about alpha h**2 / 12 (2.1e-5 here).
    alpha, n_points = 10.0, 201
    sol = solve_cantilever(alpha, n_points=n_points)
    h = 1.0 / (n_points - 1)
    np.testing.assert_allclose(np.diff(sol.s), h, rtol=0.0, atol=1e-15)
    length = np.sum(np.hypot(np.diff(sol.x), np.diff(sol.y)))
    assert 0.0 < 1.0 - length <= alpha * h**2 / 12.0


def test_clamp_conditions():
    sol = solve_cantilever(5.0, 2.0)
    assert (sol.s[0], sol.s[-1]) == (0.0, 1.0)
    assert (sol.x[0], sol.y[0]) == (0.0, 0.0)
    assert sol.theta[0] == pytest.approx(0.0, abs=1e-10)


@pytest.mark.parametrize("alpha", [0.0, 15.0])
def test_axial_tension_keeps_beam_straight(alpha):
    sol = solve_cantilever(alpha, 0.0, n_points=11)
    np.testing.assert_array_equal(sol.x, np.linspace(0.0, 1.0, 11))
    np.testing.assert_array_equal(sol.y, 0.0)
    np.testing.assert_array_equal(sol.theta, 0.0)
    assert (sol.tip_x, sol.tip_y) == (1.0, 0.0)


def test_load_angle_sweep_is_continuous():
    # Along one branch the tip moves by O(step) per angle step (about
    # 0.5 * step here), whereas a jump to another equilibrium (mirror
    # image, straight or inflected shape) moves it by O(1).  The axial
    # compression component exceeds the Euler load for a > 2.09 rad.
    alpha = 5.0
    angles = np.linspace(np.pi / 2, 3 * np.pi / 4, 17)
    step = angles[1] - angles[0]
    tips, tip_angles = [], []
    for angle in angles:
        sol = solve_cantilever(alpha, angle, n_points=21)
        tips.append((sol.tip_x, sol.tip_y))
        tip_angles.append(sol.tip_angle)
        # The default branch has no inflection point.
        assert np.all(np.diff(sol.theta) > 0.0)
    moves = np.hypot(*np.diff(np.array(tips), axis=0).T)
    assert np.all(moves < step)
    assert np.all(np.diff(tip_angles) > 0.0)


def test_negative_load_angle_is_mirror_image():
    upper = solve_cantilever(3.0, 2.0)
    lower = solve_cantilever(3.0, -2.0)
    np.testing.assert_allclose(lower.x, upper.x, rtol=0.0, atol=1e-14)
    np.testing.assert_allclose(lower.y, -upper.y, rtol=0.0, atol=1e-14)


def test_solution_is_read_only():
    sol = solve_cantilever(1.0, n_points=5)
    assert isinstance(sol, ElasticaSolution)
    with pytest.raises(ValueError):
        sol.x[0] = 1.0


@pytest.mark.parametrize(
    "kwargs",
    [
        {"load_index": -1.0},
        {"load_index": math.nan},
        {"load_index": 1.0, "n_points": 1},
        {"load_index": 1.0, "load_angle": math.inf},
    ],
)
def test_invalid_input_raises(kwargs):
    with pytest.raises(ValueError):
        solve_cantilever(**kwargs)
