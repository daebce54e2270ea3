"""Howell's γ(n) and K_Θ(n) fitted from the project's own elastica, against his table."""

import numpy as np
import pytest

from exubrush.models.howell import HOWELL_TABLE
from exubrush.reference.howell_fit import fit_prb_parameters


@pytest.mark.parametrize("n, gamma_table, k_table", HOWELL_TABLE.tolist())
def test_fitted_gamma_matches_howells_table(n, gamma_table, k_table):
    fit = fit_prb_parameters(n)
    # issue #3 target 0.003; the table has 4 digits and our γ grid is 2e-4 (measured ≤ 2e-4)
    assert fit.gamma == pytest.approx(gamma_table, abs=0.003)
    # K_Θ is a least-squares slope over the fitted range; Howell's averaging differs, and
    # the fitted K_Θ drifts above his with n (measured: +0.7 % at n = 0, +15 % at n = 10)
    assert 0.95 * k_table < fit.stiffness_coefficient < 1.2 * k_table


def test_pure_transverse_load_range_is_howells_64_degrees():
    # Howell (2001): for n = 0 the model stays within 0.5 % up to Θ = 64.3°
    assert np.degrees(fit_prb_parameters(0.0).angle_range) == pytest.approx(64.3, abs=0.3)


def test_tension_is_fitted_and_out_of_range_refused():
    assert 0.85 < fit_prb_parameters(-1.0).gamma < 0.9  # γ grows as the load pulls
    with pytest.raises(ValueError, match="outside the fitted range"):
        fit_prb_parameters(11.0)


def test_a_case_can_take_its_prb_parameters_from_the_fit():
    from exubrush.parameters.io import load_case
    from exubrush.scene import prb_parameters

    fitted = load_case("parallel", ["model.kind='prb'", "model.prb_parameters='fitted'"])
    table = load_case("parallel", ["model.kind='prb'"])
    assert fitted.load_ratio() == pytest.approx(1 / 0.76, rel=1e-15)
    # the same n: γ agrees with the interpolated table to the fit's accuracy (0.003)
    assert prb_parameters(fitted)[0] == pytest.approx(prb_parameters(table)[0], abs=0.003)
    other = load_case("parallel", ["model.kind='prb'", "model.prb_parameters='fitted'",
                                   "model.prb_load_ratio='-1'"])
    assert prb_parameters(other)[0] == pytest.approx(fit_prb_parameters(-1.0).gamma)
