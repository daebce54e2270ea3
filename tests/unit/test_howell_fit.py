"""Howell's γ(n) and K_Θ(n) fitted from the project's own elastica, against his table.

Each fit solves 300 exact elasticas (about 12 s), so all of these are in the slow tier.
Fits are cached per process (functools.lru_cache): the K_Θ trend reuses the ten fits of the
table's checks, as this file runs on one worker. The fit at load ratios off the table is
checked in test_howell_fit_off_the_table.py, a file of its own so that the other worker can
take its two fits.

What the fit should reach, and why:
- γ: Howell's criterion evaluated on an exact elastica must give Howell's γ. The table has
  4 digits and the γ search grid is 2e-4, so |Δγ| ≤ 0.003 (issue target; measured ≤ 2e-4).
- K_Θ: by its definition here, the least-squares slope (through the origin) of the exact
  perpendicular load index against Θ over the fitted range. Howell averaged differently,
  so his values are matched only where the load path is nearly linear in Θ: at n = 0,
  within 1 % (measured +0.7 %). For n > 0 the fitted slope lies above his and the gap grows
  with n (measured +15 % at n = 10): asserted as that trend, not as a band.
"""

import numpy as np
import pytest

from exubrush.models.howell import HOWELL_TABLE
from exubrush.reference import howell_fit
from exubrush.reference.howell_fit import fit_prb_parameters


def _load_residual(n: float, k_theta: float) -> float:
    """Σ (K_Θ Θ - exact perpendicular load index)² over the fitted range at ``n``."""
    fit = fit_prb_parameters(n)
    alphas, tips = howell_fit.exact_tip_path(n)
    theta = howell_fit._pseudo_angle(tips, fit.gamma)
    inside = theta <= fit.angle_range
    perpendicular = (alphas * np.sin(howell_fit._load_angle(n))
                     * (np.cos(theta) + n * np.sin(theta)))
    return float(np.sum((k_theta * theta[inside] - perpendicular[inside]) ** 2))


def _check_against_table(n, gamma_table):
    fit = fit_prb_parameters(n)
    assert fit.gamma == pytest.approx(gamma_table, abs=0.003)
    # least squares: a slope 1 % off either way fits the exact load worse
    best = _load_residual(n, fit.stiffness_coefficient)
    for factor in (0.99, 1.01):
        assert best < _load_residual(n, factor * fit.stiffness_coefficient)
    return fit


@pytest.mark.slow  # about 12 s: a fit to the exact elastica
def test_pure_transverse_load_matches_howell():
    n, gamma_table, k_table = HOWELL_TABLE[0]
    fit = _check_against_table(float(n), gamma_table)
    assert fit.stiffness_coefficient == pytest.approx(k_table, rel=0.01)
    # Howell (2001): for n = 0 the model stays within 0.5 % up to Θ = 64.3°
    assert np.degrees(fit.angle_range) == pytest.approx(64.3, abs=0.3)


@pytest.mark.slow
@pytest.mark.parametrize("n, gamma_table, k_table", HOWELL_TABLE[1:].tolist())
def test_fitted_gamma_matches_howells_table(n, gamma_table, k_table):
    _check_against_table(n, gamma_table)


@pytest.mark.slow
def test_fitted_k_theta_drifts_above_howells_with_n():
    ratios = [fit_prb_parameters(float(n)).stiffness_coefficient / k
              for n, _, k in HOWELL_TABLE]
    assert ratios[0] == pytest.approx(1.0, abs=0.01)
    assert np.all(np.diff(ratios) > 0.0), ratios
