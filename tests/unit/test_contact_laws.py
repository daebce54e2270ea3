"""Contact and friction laws against their formulas (the paper's eq. 14 and its friction law)."""

import math

import numpy as np
import pytest

from exubrush.contact.laws import (
    builtin_contact_parameters,
    drop_can_lag,
    drop_ratios,
    feature_slip,
    friction_coefficient,
    friction_drop,
    friction_per_speed,
    friction_rise,
    normal_force,
    sphere_feature_force,
    sphere_plane_force,
    sphere_surface_force,
)
from exubrush.parameters.case import ContactLaw, Surface
from exubrush.world.surfaces import Choice, Feature, features, resolve

LAW = ContactLaw()  # paper table 2


def test_defaults_are_the_papers_table_2():
    assert (LAW.stiffness, LAW.stiffness_exponent, LAW.damping) == (100.0, 1.3, 0.2)
    assert (LAW.damping_rate_exponent, LAW.damping_depth_exponent) == (1.0, 2.0)
    assert (LAW.static_friction, LAW.dynamic_friction) == (0.8, 0.76)
    assert (LAW.static_velocity, LAW.dynamic_velocity) == (1.2, 1.5)


def test_normal_force_values():
    # k δ^1.3 + c δ' δ²: δ = 0.01 mm, δ' = 2 mm/s -> 100·0.01^1.3 + 0.2·2·1e-4
    expected = 100 * 0.01**1.3 + 0.2 * 2 * 0.01**2
    assert normal_force(LAW, 0.01, 2.0) == pytest.approx(expected, rel=1e-14)
    assert normal_force(LAW, 0.01, -2.0) == pytest.approx(100 * 0.01**1.3 - 0.2 * 2 * 1e-4,
                                                          rel=1e-14)


def test_no_force_without_penetration_and_no_pull():
    assert normal_force(LAW, 0.0, -5.0) == 0.0
    assert normal_force(LAW, -0.1, 3.0) == 0.0
    # leaving fast: the damping term exceeds the elastic one, clamped at zero
    assert normal_force(LAW, 0.001, -1e6) == 0.0


def test_unit_conversion_of_the_paper_coefficients():
    # k = 100 N/mm^1.3 is 100·1000^1.3 N/m^1.3 and c = 0.2 N·s/mm³ is 0.2e9 N·s/m³: the same
    # force comes out in SI for the same physical state
    from exubrush.util.units import to_internal

    k_si = to_internal("100 N/mm^1.3", "N/m^1.3")
    c_si = to_internal("0.2 N*s/mm^3", "N*s/m^3")
    assert k_si == pytest.approx(100 * 1000**1.3, rel=1e-12)
    assert c_si == pytest.approx(0.2e9, rel=1e-12)
    delta_m, rate_m = 0.05e-3, 3e-3  # 0.05 mm, 3 mm/s
    force_si = k_si * delta_m**1.3 + c_si * rate_m * delta_m**2
    assert normal_force(LAW, 0.05, 3.0) == pytest.approx(force_si, rel=1e-12)
    assert k_si != pytest.approx(100 * 1000)  # not a plain N/mm conversion


def test_friction_coefficient_key_values():
    assert friction_coefficient(LAW, 0.0) == 0.0
    assert friction_coefficient(LAW, 1.2) == pytest.approx(0.8, abs=1e-15)
    assert friction_coefficient(LAW, 1.5) == pytest.approx(0.76, abs=1e-15)
    assert friction_coefficient(LAW, 100.0) == pytest.approx(0.76, abs=1e-15)
    # odd cubic step from -μ_s at -v_s to μ_s at v_s: slope 1.5 μ_s / v_s at zero
    assert friction_coefficient(LAW, 1e-6) / 1e-6 == pytest.approx(1.5 * 0.8 / 1.2, rel=1e-5)


def test_friction_coefficient_is_continuous_with_continuous_slope():
    speeds = np.linspace(0.0, 3.0, 30001)
    mu = np.array([friction_coefficient(LAW, v) for v in speeds])
    h = speeds[1] - speeds[0]
    # largest jump between neighbours bounded by max slope · h (slope <= 1.5 μ_s/v_s = 1)
    assert np.max(np.abs(np.diff(mu))) <= 1.0 * h * 1.0001
    slope = np.diff(mu) / h
    # slope changes by at most (max curvature · h); a kink would show a jump of order 1
    assert np.max(np.abs(np.diff(slope))) < 0.01
    assert np.all(np.diff(mu[speeds <= 1.2]) >= 0)  # rising to μ_s


def test_sphere_on_plane_force_and_moment():
    r = 0.4
    centre, velocity, omega = [0.0, 0.0, 0.35], [3.0, 0.0, -1.0], [0.0, 0.0, 0.0]
    f = sphere_plane_force(LAW, r, centre, velocity, omega)
    fn = normal_force(LAW, 0.05, 1.0)
    assert f[2] == pytest.approx(fn, rel=1e-14)
    assert f[0] == pytest.approx(-0.76 * fn, rel=1e-9)  # opposes +x slip, μ_d at 3 mm/s
    assert f[1] == 0.0
    # moment of the friction force at (0, 0, -r): (-r e_z) × (f_x, 0, 0) = (0, -r f_x, 0)
    assert f[3] == pytest.approx(0.0, abs=1e-15)
    assert f[4] == pytest.approx(-r * f[0], rel=1e-14)


def test_rolling_without_slip_gives_no_friction():
    # v_x = 2, ω_y = 5 (= v/r): the contact point is at rest
    r = 0.4
    f = sphere_plane_force(LAW, r, [0, 0, 0.38], [2.0, 0.0, 0.0], [0.0, 2.0 / r, 0.0])
    assert abs(f[0]) < 1e-6 * f[2]


def test_friction_opposes_slip_in_any_direction():
    for angle in np.linspace(0, 2 * math.pi, 13):
        v = [2 * math.cos(angle), 2 * math.sin(angle), 0.0]
        f = sphere_plane_force(LAW, 0.4, [0, 0, 0.39], v, [0, 0, 0])
        assert f[0] * v[0] + f[1] * v[1] < 0


def test_law_checks_velocity_order():
    with pytest.raises(ValueError, match="static_velocity"):
        ContactLaw(static_velocity=2.0, dynamic_velocity=1.0).check()


def test_friction_scale_switches_only_the_tangential_force():
    state = ([0.0, 0.0, 0.38], [2.0, 1.0, -0.5], [0.1, 0.0, 0.0])
    full = sphere_plane_force(LAW, 0.4, *state)
    none = sphere_plane_force(LAW, 0.4, *state, friction_scale=0.0)
    half = sphere_plane_force(LAW, 0.4, *state, friction_scale=0.5)
    assert none[2] == full[2] and none[0] == none[1] == 0.0
    assert half[0] == pytest.approx(0.5 * full[0], rel=1e-14)
    assert half[4] == pytest.approx(0.5 * full[4], rel=1e-14)


def test_builtin_contact_parameters_match_the_law_where_they_can():
    fitted = builtin_contact_parameters(LAW, reference_force=0.05)
    assert fitted["contactStiffness"] == LAW.stiffness
    assert fitted["contactStiffnessExponent"] == LAW.stiffness_exponent
    assert fitted["dynamicFriction"] == LAW.dynamic_friction
    # same slope of μ at zero slip: μ_d / v_r = 1.5 μ_s / v_s = 1 s/mm
    slope = fitted["dynamicFriction"] / fitted["frictionProportionalZone"]
    assert slope == pytest.approx(friction_coefficient(LAW, 1e-7) / 1e-7, rel=1e-6)
    # linear damping = the law's damping term at the depth where k δ^m1 = 0.05 N, 1 mm/s
    depth = (0.05 / 100.0) ** (1 / 1.3)
    damping_term = normal_force(LAW, depth, 1.0) - normal_force(LAW, depth, 0.0)
    assert fitted["contactDamping"] * 1.0 == pytest.approx(damping_term, rel=1e-9)


def test_builtin_contact_without_friction_keeps_a_valid_regularisation():
    fitted = builtin_contact_parameters(ContactLaw(static_friction=0.0, dynamic_friction=0.0),
                                        reference_force=0.05)
    assert fitted["dynamicFriction"] == 0.0
    assert fitted["frictionProportionalZone"] > 0.0


def _rotation(axis, angle):
    """Rotation matrix about a unit axis (Rodrigues)."""
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    cross = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * cross + (1 - math.cos(angle)) * cross @ cross


@pytest.mark.parametrize("seed", range(6))
def test_feature_law_is_the_plane_law_turned_to_the_normal(seed):
    # a face with normal n = R e_z acts on a turned state as the plane acts on the state
    # itself, turned: F(R p, R v, R ω; n) = R F_plane(p, v, ω)
    rng = np.random.default_rng(seed)
    turn = _rotation(rng.normal(size=3), rng.uniform(0.1, 3.0))
    depth = rng.uniform(0.0, 0.05)
    velocity, omega = rng.normal(scale=2.0, size=3), rng.normal(scale=2.0, size=3)
    plane = np.array(sphere_plane_force(LAW, 0.4, [0.0, 0.0, 0.4 - depth], velocity.tolist(),
                                        omega.tolist()))
    normal = tuple(float(c) for c in turn[:, 2])
    turned = np.array(sphere_feature_force(LAW, 0.4, normal, 0.4 - depth,
                                           (turn @ velocity).tolist(), (turn @ omega).tolist()))
    np.testing.assert_allclose(turned[:3], turn @ plane[:3], rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(turned[3:], turn @ plane[3:], rtol=1e-10, atol=1e-14)


def test_feature_law_along_z_is_the_plane_law():
    state = ([0.0, 0.0, 0.37], [1.0, -0.5, -2.0], [0.3, 0.1, 0.2])
    plane = sphere_plane_force(LAW, 0.4, *state)
    face = sphere_feature_force(LAW, 0.4, (0.0, 0.0, 1.0), 0.37, state[1], state[2])
    # the face law computes μ(v)/v in one expression (friction_per_speed) where the plane
    # law divides μ(v) by v: the same function, rounded differently
    np.testing.assert_allclose(face, plane, rtol=1e-12, atol=1e-17)


@pytest.mark.parametrize("speed", [0.0, 1e-7, 0.3, 1.19999, 1.2, 1.2001, 1.35, 1.5, 1.6, 40.0])
def test_friction_per_speed_is_the_coefficient_over_the_speed(speed):
    per_speed = friction_per_speed(LAW, speed**2)
    if speed == 0.0:
        assert per_speed == pytest.approx(1.5 * LAW.static_friction / LAW.static_velocity)
    else:
        assert per_speed * speed == pytest.approx(friction_coefficient(LAW, speed), rel=1e-12)


def test_surface_law_sums_the_touched_features_only():
    velocity, omega = [0.0, 1.0, -0.5], [0.0, 0.0, 0.0]
    floor = Feature((0.0, 0.0, 1.0), 0.38)
    wall = Feature((1.0, 0.0, 0.0), 0.39)
    away = Feature((-1.0, 0.0, 0.0), 0.41)  # 0.01 mm beyond the sphere: no force
    both = sphere_surface_force(LAW, 0.4, [floor, wall, away], velocity, omega)
    expected = (np.array(sphere_feature_force(LAW, 0.4, floor.normal, 0.38, velocity, omega))
                + sphere_feature_force(LAW, 0.4, wall.normal, 0.39, velocity, omega))
    np.testing.assert_allclose(both, expected, rtol=1e-15)
    assert both[0] > 0.0 and both[2] > 0.0  # pushed away from the wall and up from the floor
    chosen = sphere_surface_force(LAW, 0.4, [Choice(False, away, wall)], velocity, omega)
    np.testing.assert_allclose(
        chosen, sphere_feature_force(LAW, 0.4, wall.normal, 0.39, velocity, omega), rtol=1e-15)


def test_a_diverged_state_gives_loads_not_an_exception():
    # a diverging Newton iterate can hand the Python user function a huge state: the law
    # must return numbers (Exudyn then cuts the step), never raise (x**2 of a float raises
    # OverflowError where x * x gives inf)
    from exubrush.parameters.case import Surface
    from exubrush.world.surfaces import features

    load = sphere_feature_force(LAW, 0.4, (0.6, 0.0, 0.8), 0.39, [1e200, 0.0, 0.0],
                                [0.0, 0.0, 0.0])
    assert len(load) == 6 and all(isinstance(c, float) for c in load)
    far = features(Surface(kind="tooth-row"), (3.2, 0.0, 1e200), 0.4)
    assert far  # no OverflowError from the geometry either


SPEEDS = [0.0, 1e-7, 0.3, 1.19999, 1.2, 1.2001, 1.35, 1.4999, 1.5, 1.6, 40.0]


@pytest.mark.parametrize("speed", SPEEDS)
def test_coefficient_is_the_rise_times_the_drop(speed):
    # μ(v) = μ_rise(v) r(v) for the paper's law and for a steeper drop
    steep = LAW.replace(static_friction=0.9, dynamic_friction=0.3, dynamic_velocity=2.0)
    for law in (LAW, steep):
        assert friction_rise(law, speed) * friction_drop(law, speed) == pytest.approx(
            friction_coefficient(law, speed), rel=1e-14, abs=1e-300)


def test_rise_is_monotone_and_drop_runs_from_one_to_the_dynamic_ratio():
    # the part left inside Newton must never fall (a falling μ makes the step's equations
    # non-monotone in the slip): sampled densely across the Stribeck band
    speeds = np.linspace(0.0, 3.0, 3001)
    rise = np.array([friction_rise(LAW, v) for v in speeds])
    assert np.all(np.diff(rise) >= 0.0)
    assert friction_drop(LAW, 1.2) == 1.0 and friction_drop(LAW, 0.0) == 1.0
    assert friction_drop(LAW, 1.5) == pytest.approx(0.76 / 0.8, rel=1e-15)
    assert friction_drop(LAW, 9.0) == pytest.approx(0.76 / 0.8, rel=1e-15)


def test_only_a_falling_friction_can_lag():
    assert drop_can_lag(LAW)
    assert not drop_can_lag(LAW.replace(static_friction=0.76))  # flat: nothing falls
    assert not drop_can_lag(LAW.replace(static_friction=0.0))  # rising from zero


@pytest.mark.parametrize("speed", SPEEDS)
def test_forces_with_the_drop_at_the_current_slip_are_the_laws(speed):
    # a lagged step that happens to lag by nothing reproduces the implicit law: the
    # plane, a turned face and friction_per_speed
    slip = (0.6 * speed, -0.8 * speed)
    velocity, omega = [slip[0], slip[1], -0.5], [0.0, 0.0, 0.0]
    drop = drop_ratios(LAW, 0.4, None, [0.0, 0.0, 0.37], velocity, omega)
    assert len(drop) == 1
    np.testing.assert_allclose(
        sphere_plane_force(LAW, 0.4, [0.0, 0.0, 0.37], velocity, omega, drop=drop[0]),
        sphere_plane_force(LAW, 0.4, [0.0, 0.0, 0.37], velocity, omega), rtol=1e-12,
        atol=1e-18)
    assert friction_per_speed(LAW, speed**2, drop=friction_drop(LAW, speed)) == pytest.approx(
        friction_per_speed(LAW, speed**2), rel=1e-12)


SURFACES_WITH_FEATURES = [
    Surface(kind="tooth-row"),
    Surface(kind="tooth-row", gap_width=0.5),  # narrower than the sphere: both teeth
    Surface(kind="cylinder"),
    Surface(kind="sphere"),
]


@pytest.mark.parametrize("row", SURFACES_WITH_FEATURES, ids=lambda s: f"{s.kind}-{s.gap_width}")
@pytest.mark.parametrize("seed", range(12))
def test_drop_ratios_follow_each_features_own_slip(seed, row):
    # a sphere near a tooth's edge sees up to three features, each with its own normal:
    # the ratio of each is r at that feature's slip (computed by the generic helpers, which
    # also record the law into Exudyn's expressions: the hook's plain arithmetic must give
    # the same numbers exactly), and the surface law given them equals the implicit law
    rng = np.random.default_rng(seed)
    centre = [rng.uniform(-4.0, 4.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.2, 0.6)]
    velocity = rng.normal(scale=1.3, size=3).tolist()
    omega = rng.normal(scale=2.0, size=3).tolist()
    found = features(row, centre, 0.4)
    ratios = drop_ratios(LAW, 0.4, row, centre, velocity, omega)
    assert len(ratios) == len(found)
    for feature, ratio in zip(found, ratios, strict=True):
        _, slip = feature_slip(0.4, resolve(feature).normal, velocity, omega)
        assert ratio == friction_drop(LAW, math.sqrt(sum(c * c for c in slip)))
    np.testing.assert_allclose(
        sphere_surface_force(LAW, 0.4, found, velocity, omega, drops=ratios),
        sphere_surface_force(LAW, 0.4, found, velocity, omega), rtol=1e-12, atol=1e-18)
