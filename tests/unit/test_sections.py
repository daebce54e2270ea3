"""Section properties against closed forms and published tables."""

import math

import pytest

from exubrush.models.sections import rectangle_torsion_constant, section_properties


def test_rectangle_area_and_second_moments():
    s = section_properties("rectangle", 0.6, 0.9)
    assert s.area == pytest.approx(0.54, rel=1e-15)
    assert s.second_moment_y == pytest.approx(0.6 * 0.9**3 / 12, rel=1e-15)
    assert s.second_moment_z == pytest.approx(0.9 * 0.6**3 / 12, rel=1e-15)
    assert s.shear_coefficient == pytest.approx(5 / 6)


@pytest.mark.parametrize(
    "ratio, coefficient",
    # Timoshenko & Goodier, Theory of Elasticity, table in §109: J = k a b³ (a long side),
    # printed to three digits, hence half a unit of the third digit as tolerance
    [(1.0, 0.141), (1.5, 0.196), (2.0, 0.229), (3.0, 0.263), (10.0, 0.312)],
)
def test_rectangle_torsion_constant_matches_published_table(ratio, coefficient):
    a, b = ratio, 1.0
    assert rectangle_torsion_constant(a, b) / (a * b**3) == pytest.approx(coefficient, abs=5e-4)


def test_thin_rectangle_torsion_tends_to_one_third():
    # a/b -> infinity: J -> a b³/3 (1 - 0.630 b/a); at a/b = 100 within 1e-4 of that form
    a, b = 100.0, 1.0
    assert rectangle_torsion_constant(a, b) == pytest.approx(a * b**3 / 3 * (1 - 0.630 / 100),
                                                             rel=1e-4)


def test_circle_torsion_equals_polar_moment():
    d = 0.2
    s = section_properties("circle", d, d)
    assert s.area == pytest.approx(math.pi * d**2 / 4, rel=1e-15)
    assert s.torsion_constant == pytest.approx(math.pi * d**4 / 32, rel=1e-14)
    assert s.polar_moment == pytest.approx(math.pi * d**4 / 32, rel=1e-14)


def test_ellipse_second_moments():
    s = section_properties("ellipse", 0.6, 0.9)
    assert s.second_moment_y == pytest.approx(math.pi * 0.3 * 0.45**3 / 4, rel=1e-15)
    assert s.second_moment_z == pytest.approx(math.pi * 0.45 * 0.3**3 / 4, rel=1e-15)


@pytest.mark.parametrize("shape, width, height", [
    ("hexagon", 1, 1), ("rectangle", 0, 1), ("ellipse", 1, -1), ("circle", 1, 2),
])
def test_bad_sections_are_refused(shape, width, height):
    with pytest.raises(ValueError):
        section_properties(shape, width, height)


def test_every_shape_a_case_accepts_is_implemented():
    from exubrush.parameters.choices import SECTION_SHAPES

    for shape in SECTION_SHAPES:
        assert section_properties(shape, 0.5, 0.5).area > 0.0
