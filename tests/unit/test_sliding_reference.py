"""The exact sliding-bristle reference (exubrush.reference.sliding)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from exubrush.reference.sliding import sliding_load_index, sliding_normal_force, sliding_shape


def post_buckling_load_index(height_ratio):
    """Clamped-free column under axial compression (Euler's elastica, elliptic integrals).

    With p = sin(θ_tip / 2): √α = K(p) and the tip's axial position x₁/L = 2E(p)/K(p) - 1
    (scipy's ellipk/ellipe take the parameter m = p²).
    """
    m = brentq(lambda m: 2.0 * ellipe(m) / ellipk(m) - 1.0 - height_ratio, 1e-12, 0.999999)
    return ellipk(m) ** 2


@pytest.mark.parametrize("height_ratio", [0.95, 0.8, 0.6])
def test_frictionless_limit_is_euler_post_buckling(height_ratio):
    alpha = sliding_load_index(height_ratio, 1e-7, 0.0)
    # tolerance: μ = 1e-7 tilts the load by 1e-7 rad, which moves α by O(1e-7) relative to
    # the buckled shape; the BVP tolerance is 1e-10
    assert alpha == pytest.approx(post_buckling_load_index(height_ratio), rel=1e-6)


@pytest.mark.parametrize("height_ratio, friction, offset", [(0.9, 0.3, 0.02), (0.7, 0.76, 0.08)])
def test_clamp_moment_balances_the_offset_tip_load(height_ratio, friction, offset):
    solution = sliding_shape(height_ratio, friction, offset)
    alpha = solution.p[0]
    angle = math.pi - math.atan(friction)
    s = np.linspace(0.0, 1.0, 2001)
    theta, curvature, x = solution.sol(s)
    y = np.concatenate([[0.0], np.cumsum(0.5 * (np.sin(theta[1:]) + np.sin(theta[:-1]))
                                         * np.diff(s))])
    # moment of the force P(cos a, sin a) acting at (x₁ + ρ, y₁) about the clamp, over EI/L
    clamp = alpha * ((x[-1] + offset) * math.sin(angle) - y[-1] * math.cos(angle))
    # tolerance: y₁ by the trapezoidal rule on 2000 intervals (error ~1e-7)
    assert curvature[0] == pytest.approx(clamp, rel=1e-5)
    assert x[-1] == pytest.approx(height_ratio, abs=1e-9)


def test_normal_force_scales_with_bending_stiffness_over_length_squared():
    one = sliding_normal_force(4.0, 0.5, 5.0, 0.1, 0.2)
    alpha = sliding_load_index(0.8, 0.5, 0.04)
    assert one == pytest.approx(alpha * 0.1 / 25.0 * math.cos(math.atan(0.5)), rel=1e-12)


@pytest.mark.parametrize("args, message", [
    ((1.0, 0.5, 0.0), "height_ratio must lie in"),
    ((0.8, 0.0, 0.0), "friction must be positive"),
    ((0.8, 0.5, -0.1), "offset_ratio must be non-negative"),
])
def test_arguments_outside_their_range_are_refused(args, message):
    with pytest.raises(ValueError, match=message):
        sliding_load_index(*args)
