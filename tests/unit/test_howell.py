"""Howell's PRB parameters (Howell 2001, table 5.1)."""

import pytest

from exubrush.models.howell import howell_parameters


def test_paper_values_at_n_equal_one_over_mu_d():
    gamma, k_theta = howell_parameters(1 / 0.76)
    # the paper prints 4 and 5 significant digits: half a unit of the last digit
    assert gamma == pytest.approx(0.8329, abs=5e-5)
    assert k_theta == pytest.approx(2.6001, abs=5e-5)


@pytest.mark.parametrize("n, gamma, k_theta", [(0.0, 0.8517, 2.67617), (10.0, 0.8156, 2.56597),
                                                (2.0, 0.8276, 2.59707)])
def test_table_nodes_are_reproduced(n, gamma, k_theta):
    assert howell_parameters(n) == pytest.approx((gamma, k_theta), abs=1e-12)


@pytest.mark.parametrize("n", [-0.1, 10.5])
def test_outside_the_table_is_refused(n):
    with pytest.raises(ValueError, match="outside Howell's table"):
        howell_parameters(n)
