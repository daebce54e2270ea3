"""The physical bound on the head's normal force."""

import pytest

from exubrush.models.geometry import head_bristles
from exubrush.parameters.io import load_case
from exubrush.sanity import normal_force_bound


def test_bound_of_one_default_bristle_by_hand():
    case = load_case("orthogonal", ["head.rows=1", "head.columns=1"])
    # 2 · E A δ / l with E = 7.5 MPa, A = 0.6·0.9 mm², δ = 5 + 0.4 - 4.2 mm, l = 5 mm
    expected = 2 * 7.5 * 0.54 * 1.2 / 5.0
    assert normal_force_bound(case, head_bristles(case.head)) == pytest.approx(expected, rel=1e-12)


def test_bristles_that_cannot_reach_add_nothing(tmp_path):
    path = tmp_path / "two.toml"
    path.write_text('[head]\nlayout = "list"\n[[head.bristles]]\nx = "0 mm"\ny = "0 mm"\n'
                    '[[head.bristles]]\nx = "2 mm"\ny = "0 mm"\nlength = "3 mm"\n')
    case = load_case(str(path))
    one = load_case("orthogonal", ["head.rows=1", "head.columns=1"])
    assert normal_force_bound(case, head_bristles(case.head)) == pytest.approx(
        normal_force_bound(one, head_bristles(one.head)), rel=1e-12)
