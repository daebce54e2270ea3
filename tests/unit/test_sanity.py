"""The physical bound on the head's normal force."""

import pytest

from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare


def test_bound_of_one_default_bristle_by_hand():
    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1"]))
    # 2 · E A δ / l with E = 7.5 MPa, A = 0.6·0.9 mm², δ = 5 + 0.4 - 4.2 mm, l = 5 mm
    expected = 2 * 7.5 * 0.54 * 1.2 / 5.0
    assert prepared.force_bound() == pytest.approx(expected, rel=1e-12)


def test_bristles_that_cannot_reach_add_nothing(tmp_path):
    path = tmp_path / "two.toml"
    path.write_text('[head]\nlayout = "list"\n[[head.bristles]]\nx = "0 mm"\ny = "0 mm"\n'
                    '[[head.bristles]]\nx = "2 mm"\ny = "0 mm"\nlength = "3 mm"\n')
    two = prepare(load_case(str(path)))
    one = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1"]))
    assert two.force_limits[1] == 0.0
    assert two.force_bound() == pytest.approx(one.force_bound(), rel=1e-12)


def test_a_group_is_bounded_by_its_own_bristles():
    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=3"]))
    # three equal bristles: each group of one carries a third of the head's bound
    assert prepared.force_bound((1,)) == pytest.approx(prepared.force_bound() / 3, rel=1e-12)
