"""Case parameters: defaults, TOML round trip, overrides and refused input."""

import tomllib

import pytest

from exubrush.parameters.case import Case
from exubrush.parameters.catalogue import orthogonal_case, parallel_case
from exubrush.parameters.fields import build, dotted_keys, to_toml
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


def test_replace_gives_a_validated_copy():
    case = orthogonal_case()
    changed = case.replace(solver=case.solver.replace(step_size=1e-3, modified_newton=False))
    assert changed.solver.step_size == 1e-3 and changed.solver.modified_newton is False
    assert case.solver.step_size == 2e-3  # the original is untouched (frozen)
    assert changed.head == case.head


@pytest.mark.parametrize("change, message", [
    (lambda c: c.solver.replace(step_size=-1.0), "Solver.step_size: -1.0 must be > 0 ms"),
    (lambda c: c.solver.replace(modified_newton="yes"), "expected true or false, got 'yes'"),
    (lambda c: c.solver.replace(newton_iterations=12.5), "expected a whole number"),
    (lambda c: c.solver.replace(step_size="2 ms"), "expected a number in s"),
    (lambda c: c.solver.replace(minimum_step_size=1.0), "must not exceed step_size"),
    (lambda c: c.solver.replace(user_functions="builtin"), "renamed contact.backend"),
    (lambda c: c.solver.replace(stepsize=1e-3), "Solver.stepsize: unknown"),
    (lambda c: c.contact.replace(backend="fast"), "'fast' is not one of"),
    (lambda c: c.replace(solver=c.head), "expected Solver, got Head"),
    (lambda c: c.head.replace(bristles=[]), "expected a tuple of BristleEntry"),
    (lambda c: c.replace(solver=c.solver.replace(threads=2, partition="coupled")),
     "needs contact.backend 'exudyn-builtin'"),
])
def test_replace_refuses_what_a_case_file_would(change, message):
    from exubrush.parameters.fields import ParameterError

    with pytest.raises(ParameterError, match=message.replace("(", r"\(").replace(".", r"\.")):
        change(orthogonal_case())
