"""The geometrically exact beam reference (exubrush.shear_beam) against closed forms."""

import numpy as np
import pytest

from exubrush.reference.elastica import solve_cantilever
from exubrush.shear_beam import tip_position

LENGTH, BENDING = 2.0, 0.1  # mm, N mm²


def test_small_load_matches_timoshenko_beam_theory():
    shear = 0.5  # N: EI/(κGA L²) = 0.05, a thick beam
    force = 1e-3 * BENDING / LENGTH**2  # linear range: PL²/EI = 1e-3
    tip = tip_position(LENGTH, BENDING, 100.0, shear, (0.0, force), elements=64)
    linear = force * LENGTH**3 / (3 * BENDING) + force * LENGTH / shear
    # tolerance: the element's interpolation error in bending (~1/elements², 64 elements)
    # and the Newton tolerance 1e-8
    assert tip[1] == pytest.approx(linear, rel=1e-3)


def test_stiff_shear_and_axis_give_the_elastica():
    alpha = 5.0
    force = alpha * BENDING / LENGTH**2
    tip = tip_position(LENGTH, BENDING, 1e3, 1e3, (0.0, force), elements=128) / LENGTH
    exact = solve_cantilever(alpha)
    # tolerance: shear and stretch at 1e3 N (EI/(κGA L²) = 2.5e-5) move the tip by ~1e-4 L;
    # 128 elements converge to ~1e-5 L (the validation notebook shows the convergence).
    # Stiffer axes make Exudyn's static solve fail.
    np.testing.assert_allclose(tip, [exact.tip_x, exact.tip_y], atol=3e-4)
