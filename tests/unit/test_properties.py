"""Property-based tests (hypothesis): the contact laws and parameter validation hold for
any valid input, not only for the paper's values."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exubrush.contact.laws import friction_coefficient, sphere_plane_force
from exubrush.parameters.case import ContactLaw
from exubrush.parameters.fields import MAGNITUDE, ParameterError
from exubrush.parameters.io import load_case
from exubrush.util.units import UnitError

positive = st.floats(1e-3, 1e3, allow_nan=False)
speed = st.floats(0.0, 1e3, allow_nan=False)
signed = st.floats(-1e3, 1e3, allow_nan=False)


@st.composite
def laws(draw):
    static_velocity = draw(st.floats(1e-3, 10.0))
    return ContactLaw(
        stiffness=draw(positive),
        stiffness_exponent=draw(st.floats(1.0, 2.0)),
        damping=draw(st.floats(0.0, 10.0)),
        damping_rate_exponent=draw(st.floats(1.0, 2.0)),
        damping_depth_exponent=draw(st.floats(1.0, 3.0)),
        static_friction=draw(st.floats(0.0, 1.5, allow_subnormal=False)),
        dynamic_friction=draw(st.floats(0.0, 1.5, allow_subnormal=False)),
        static_velocity=static_velocity,
        dynamic_velocity=static_velocity * draw(st.floats(1.01, 10.0)),
    )


def _max_slope(law):
    """Largest |dμ/dv| of the two cubic blends: 1.5 Δμ/Δv each."""
    return max(1.5 * law.static_friction / law.static_velocity,
               1.5 * abs(law.dynamic_friction - law.static_friction)
               / (law.dynamic_velocity - law.static_velocity))


@given(laws(), st.floats(0.0, 0.5), st.lists(signed, min_size=3, max_size=3),
       st.lists(signed, min_size=3, max_size=3))
def test_contact_force_is_finite_pushes_and_friction_opposes_slip(law, depth, velocity, omega):
    radius = 0.4
    force = sphere_plane_force(law, radius, [1.0, 2.0, radius - depth], velocity, omega)
    assert all(math.isfinite(f) for f in force)
    assert force[2] >= 0.0
    slip = (velocity[0] - radius * omega[1], velocity[1] + radius * omega[0])
    # friction does no positive work on the slip
    assert force[0] * slip[0] + force[1] * slip[1] <= 1e-12 * (1 + force[2])
    # and stays below the largest coefficient times the normal force (rounding: 1e-12)
    tangential = math.hypot(force[0], force[1])
    assert tangential <= max(law.static_friction, law.dynamic_friction) * force[2] * (1 + 1e-12)


@given(laws(), st.floats(0.0, 10.0), st.lists(signed, min_size=3, max_size=3))
def test_no_force_without_penetration(law, gap, velocity):
    force = sphere_plane_force(law, 0.4, [0.0, 0.0, 0.4 + gap], velocity, [0.0, 0.0, 0.0])
    assert force == [0.0] * 6 or all(f == 0.0 for f in force)


@given(laws(), speed, st.floats(1e-9, 1e-3))
def test_friction_coefficient_is_lipschitz_continuous(law, v, dv):
    # a cubic blend 3ξ² - 2ξ³ has its steepest slope 1.5 Δμ/Δv; allow rounding (1e-12)
    change = abs(friction_coefficient(law, v + dv) - friction_coefficient(law, v))
    assert change <= _max_slope(law) * dv * (1 + 1e-9) + 1e-12


@given(laws(), speed)
def test_friction_coefficient_limits(law, v):
    mu = friction_coefficient(law, v)
    assert 0.0 <= mu <= max(law.static_friction, law.dynamic_friction) + 1e-15
    if v >= law.dynamic_velocity:  # h0 + (h1 - h0)·1 rounds to h1 within 1e-15
        assert math.isclose(mu, law.dynamic_friction, rel_tol=1e-14, abs_tol=1e-15)


LENGTH_UNITS = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "um": 1e-3}


@settings(max_examples=50, deadline=None)
@given(st.floats(4.0, 50.0), st.sampled_from(sorted(LENGTH_UNITS)))
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_any_positive_length_in_any_unit_is_read_in_mm(length, unit):
    # lengths from 4 mm: the tip (r = 0.4 mm) must reach the plane at d = 4.2 mm
    value = length / LENGTH_UNITS[unit]
    case = load_case("orthogonal", [f"head.bristle.length='{value!r} {unit}'"])
    assert math.isclose(case.head.bristle.length, length, rel_tol=1e-12)


@settings(max_examples=50, deadline=None)
@given(st.floats(-1e3, 0.0))
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_non_positive_lengths_are_refused_by_name(value):
    try:
        load_case("orthogonal", [f"head.bristle.length='{value!r} mm'"])
    except ParameterError as err:
        assert str(err).startswith("head.bristle.length:")
    else:
        raise AssertionError("a non-positive length was accepted")


@settings(max_examples=50, deadline=None)
@given(st.floats(-2.0, 2.0))
def test_poisson_ratio_range(nu):
    # accepted: 0 <= ν < 0.5, and 0 or at least 1e-20 (MAGNITUDE: smaller numbers are refused
    # everywhere, so that products of parameters stay finite)
    valid = 0.0 <= nu < 0.5 and (nu == 0.0 or nu >= MAGNITUDE[0])
    try:
        case = load_case("orthogonal", [f"head.material.poisson_ratio={nu!r}"])
    except ParameterError as err:
        assert not valid and "poisson_ratio" in str(err)
    else:
        assert valid and case.head.material.poisson_ratio == nu


@settings(max_examples=100, deadline=None)
@given(st.text(max_size=30))
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_arbitrary_text_for_a_quantity_gives_a_parameter_error_or_a_value(text):
    try:
        case = load_case("orthogonal", [f"head.material.youngs_modulus={text!r}"])
    except (ParameterError, UnitError) as err:
        assert "\n" not in str(err)
    else:
        assert case.head.material.youngs_modulus > 0.0
