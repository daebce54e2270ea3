"""The fit of Howell's γ(n) and K_Θ(n) to the exact elastica (exubrush.reference.howell_fit)
off Howell's table: in tension, out of its range, and at a case's own load ratio.

A file apart from test_howell_fit.py (the table's ten fits), so that the other worker takes
these two fits (about 12 s each).
"""

import pytest

from exubrush.reference.howell_fit import fit_prb_parameters


@pytest.mark.slow  # about 11 s: a fit to the exact elastica
def test_tension_is_fitted_and_out_of_range_refused():
    assert 0.85 < fit_prb_parameters(-1.0).gamma < 0.9  # γ grows as the load pulls
    with pytest.raises(ValueError, match="outside the fitted range"):
        fit_prb_parameters(11.0)


@pytest.mark.slow
def test_a_case_can_take_its_prb_parameters_from_the_fit():
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prb_parameters

    fitted = load_case("parallel", ["model.kind='prb'", "model.prb_parameters='fitted'"])
    table = load_case("parallel", ["model.kind='prb'"])
    assert fitted.load_ratio() == pytest.approx(1 / 0.76, rel=1e-15)
    # the same n: γ agrees with the interpolated table to the fit's accuracy (0.003)
    assert prb_parameters(fitted).gamma == pytest.approx(prb_parameters(table).gamma, abs=0.003)
    other = load_case("parallel", ["model.kind='prb'", "model.prb_parameters='fitted'",
                                   "model.prb_load_ratio='-1'"])
    assert prb_parameters(other).gamma == pytest.approx(fit_prb_parameters(-1.0).gamma)
