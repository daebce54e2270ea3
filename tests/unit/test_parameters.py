"""Case parameters: defaults, TOML round trip, overrides and refused input."""

import tomllib

import pytest

from exubrush.parameters.case import Case, orthogonal_case, parallel_case
from exubrush.parameters.fields import ParameterError, build, dotted_keys, to_toml
from exubrush.parameters.io import load_case


def test_paper_case_values():
    o, p = orthogonal_case(), parallel_case()
    assert (o.motion.amplitude, o.motion.period, o.motion.direction) == (15.0, 12.0, "orthogonal")
    assert (p.motion.amplitude, p.motion.period, p.motion.direction) == (30.0, 24.0, "parallel")
    assert o.head.material.youngs_modulus == 7.5
    assert o.motion.interaction_distance == 4.2
    assert o.head.rows * o.head.columns == 48


@pytest.mark.parametrize("factory", [orthogonal_case, parallel_case])
def test_toml_round_trip(factory):
    case = factory()
    text = to_toml(case)
    again = build(Case, tomllib.loads(text))
    assert to_toml(again) == text
    # 12 significant digits are written: values agree to 1e-12 relative
    assert again.head.material.density == pytest.approx(case.head.material.density, rel=1e-12)
    assert again.head.root_tilt == pytest.approx(case.head.root_tilt, rel=1e-12)


def test_every_dimensional_value_carries_its_unit_in_toml():
    text = to_toml(orthogonal_case())
    assert 'youngs_modulus = "7.5 MPa"' in text
    assert 'density = "1100 kg/m^3"' in text
    assert 'stiffness = "100 N/mm^1.3"' in text
    assert 'root_tilt = "0.5 deg"' in text


def test_unit_conversion_on_input():
    case = load_case("orthogonal", ["head.material.youngs_modulus='3 GPa'",
                                    "head.bristle.length='0.6 cm'",
                                    "head.root_tilt='1 deg'"])
    assert case.head.material.youngs_modulus == pytest.approx(3000.0)
    assert case.head.bristle.length == pytest.approx(6.0)
    assert case.head.root_tilt == pytest.approx(0.017453292519943295)


def test_case_file(tmp_path):
    path = tmp_path / "soft.toml"
    path.write_text('name = "soft"\n[head.material]\nyoungs_modulus = "2 MPa"\n')
    case = load_case(str(path))
    assert case.name == "soft" and case.head.material.youngs_modulus == 2.0
    assert case.head.bristle == orthogonal_case().head.bristle  # defaults fill the rest


def test_list_layout(tmp_path):
    path = tmp_path / "two.toml"
    path.write_text('[head]\nlayout = "list"\n[[head.bristles]]\nx = "0 mm"\ny = "0 mm"\n'
                    '[[head.bristles]]\nx = "2 mm"\ny = "0 mm"\nlength = "6 mm"\n')
    case = load_case(str(path))
    assert [b.length for b in case.head.bristles] == [5.0, 6.0]


def test_dotted_keys_cover_nested_tables():
    keys = dotted_keys(Case)
    assert "head.material.youngs_modulus" in keys and "contact.stiffness" in keys


# (override or file text, part of the message it must produce)
BAD_INPUT = [
    (["head.bristle.length='-1 mm'"], "head.bristle.length: -1 mm must be > 0 mm"),
    (["head.bristle.length='0 mm'"], "must be > 0 mm"),
    (["head.bristle.length=5"], "head.bristle.length: 5 has no unit"),
    (["head.material.youngs_modulus='5 mm'"], "cannot be converted to 'MPa'"),
    (["head.material.poisson_ratio=0.5"], "head.material.poisson_ratio: 0.5 must be < 0.5"),
    (["head.material.poisson_ratio=-0.1"], "must be >= 0"),
    (["contact.dynamic_friction=-0.2"], "contact.dynamic_friction: -0.2 must be >= 0"),
    (["contact.static_velocity='2 mm/s'"], "static_velocity (2 mm/s) must be below"),
    (["model.kind='beam'"], "model.kind: 'beam' is not one of 'dfm', 'prb'"),
    (["model.segments=0"], "model.segments: 0 must be > 0"),
    (["model.segments=2.5"], "model.segments: expected a whole number"),
    (["head.bristle.lenght='5 mm'"], "--set head.bristle.lenght: unknown parameter"),
    (["length='5 mm'"], "did you mean head.bristle.length"),
    (["head.rows"], "expected KEY=VALUE"),
    (["motion.profile='csv'"], "profile 'csv' needs csv_file"),
    (["head.bristle.width='abc'"], "cannot read 'abc' as a quantity"),
    (["solver.spectral_radius=1.5"], "spectral_radius 1.5 must be <= 1"),
]


@pytest.mark.parametrize("overrides, message", BAD_INPUT)
def test_bad_input_is_refused_with_a_clear_message(overrides, message):
    with pytest.raises(ParameterError) as info:
        load_case("orthogonal", overrides)
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_unknown_case_and_bad_files(tmp_path):
    with pytest.raises(ParameterError, match="unknown case 'diagonal'"):
        load_case("diagonal")
    broken = tmp_path / "broken.toml"
    broken.write_text("[head\nrows = 2\n")
    with pytest.raises(ParameterError, match="not valid TOML"):
        load_case(str(broken))
    unknown = tmp_path / "unknown.toml"
    unknown.write_text("[head]\ncolour = 'red'\n")
    with pytest.raises(ParameterError, match="head.colour: unknown key"):
        load_case(str(unknown))
