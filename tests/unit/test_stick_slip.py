"""The stick/slip friction law (exubrush.contact.stick_slip) against hand-computed forces,
its state's commit rules, and its rolling track against the rotation's exact rates."""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from exubrush.contact.stick_slip import (
    ANCHOR_X,
    DROP,
    committed_state,
    rolling_matrix,
    stick_slip_plane_force,
    stretch,
)
from exubrush.parameters.case import ContactLaw

LAW = ContactLaw(friction_model="stick-slip")  # k 100 N/mm^1.3, mu_s 0.8, mu_d 0.76, s_e 1 um
RADIUS = 0.4  # mm
DEPTH = 0.01  # mm: F_n = 100 * 0.01^1.3 N at rest
NORMAL = 100.0 * DEPTH**1.3
AT_REST = (0.0, 0.0, 0.0)


def _state_at(centre, rotation=AT_REST, velocity=AT_REST, omega=AT_REST):
    """The state committed for a tip that touches down at ``centre``: zero stretch."""
    lifted = (centre[0], centre[1], RADIUS + 1.0)
    return committed_state(LAW, RADIUS, lifted, rotation, velocity, omega, [0.0] * 5 + [1.0])


def test_a_sticking_tip_is_held_by_a_spring_of_mu_s_f_n_per_stick_stretch():
    state = _state_at((1.0, 2.0, 0.0))
    # moved 0.3 um along x and 0.4 um along y: |u| = 0.5 um, half the stick stretch
    centre = (1.0 + 3e-4, 2.0 + 4e-4, RADIUS - DEPTH)
    load = stick_slip_plane_force(LAW, RADIUS, centre, AT_REST, AT_REST, AT_REST, state)
    assert load[2] == pytest.approx(NORMAL, rel=1e-12)
    spring = 0.8 * NORMAL / 1e-3  # mu_s F_n / s_e [N/mm]
    assert load[0] == pytest.approx(-spring * 3e-4, rel=1e-9)
    assert load[1] == pytest.approx(-spring * 4e-4, rel=1e-9)
    # the friction acts at the contact point r below the centre
    assert load[3:] == pytest.approx([RADIUS * load[1], -RADIUS * load[0], 0.0], rel=1e-12)


def test_a_sticking_tip_has_a_damper_beside_its_spring():
    state = _state_at((0.0, 0.0, 0.0))
    centre = (2e-4, 0.0, RADIUS - DEPTH)
    # the contact point slips at 10 mm/s along y: v - r w_y along x, v + r w_x along y
    velocity, omega = (0.0, 30.0, 0.0), (-50.0, 0.0, 0.0)
    load = stick_slip_plane_force(LAW, RADIUS, centre, AT_REST, velocity, omega, state)
    spring = 0.8 * NORMAL / 1e-3  # N/mm; tau = 10 us: the damper as 0.1 um of stretch
    assert (load[0], load[1]) == pytest.approx((-spring * 2e-4, -spring * 1e-5 * 10.0),
                                               rel=1e-9)


def test_a_tip_pulled_beyond_the_stick_stretch_slides_at_mu_times_the_drop():
    state = _state_at((0.0, 0.0, 0.0))
    state[DROP] = 0.76 / 0.8  # a sliding tip's drop ratio: mu = mu_d
    centre = (-0.03, 0.04, RADIUS - DEPTH)  # 50 um away, along (-0.6, 0.8)
    load = stick_slip_plane_force(LAW, RADIUS, centre, AT_REST, AT_REST, AT_REST, state)
    assert math.hypot(load[0], load[1]) == pytest.approx(0.76 * NORMAL, rel=1e-12)
    assert (load[0], load[1]) == pytest.approx((0.6 * 0.76 * NORMAL, -0.8 * 0.76 * NORMAL),
                                               rel=1e-12)


def test_a_tip_off_the_plane_feels_nothing():
    state = _state_at((0.0, 0.0, 0.0))
    load = stick_slip_plane_force(LAW, RADIUS, (0.5, 0.0, RADIUS + 0.01), AT_REST, AT_REST,
                                  AT_REST, state)
    assert load == [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]


def test_rolling_without_slip_leaves_the_spring_unstretched():
    # a sphere rolling along +x turns about +y: its centre advances r per radian
    state = _state_at((0.0, 0.0, 0.0))
    turned = (0.0, 0.2, 0.0)
    centre = (RADIUS * 0.2, 0.0, RADIUS - DEPTH)
    assert stretch(RADIUS, centre, turned, state) == pytest.approx((0.0, 0.0), abs=1e-15)
    # along +y it turns about -x
    assert stretch(RADIUS, (0.0, RADIUS * 0.3, 0.0), (-0.3, 0.0, 0.0), state) == pytest.approx(
        (0.0, 0.0), abs=1e-15)


def test_commit_keeps_a_stick_pulls_a_slip_back_to_the_stick_stretch_and_is_idempotent():
    state = _state_at((0.0, 0.0, 0.0))
    inside = committed_state(LAW, RADIUS, (5e-4, 0.0, RADIUS - DEPTH), AT_REST, AT_REST,
                             AT_REST, state)
    assert inside[ANCHOR_X] == pytest.approx(state[ANCHOR_X], abs=1e-15)  # still sticks
    slid = committed_state(LAW, RADIUS, (0.05, 0.0, RADIUS - DEPTH), AT_REST, AT_REST,
                           AT_REST, state)
    assert stretch(RADIUS, (0.05, 0.0, 0.0), AT_REST, slid) == pytest.approx((1e-3, 0.0),
                                                                             rel=1e-12)
    again = committed_state(LAW, RADIUS, (0.05, 0.0, RADIUS - DEPTH), AT_REST, AT_REST,
                            AT_REST, slid)
    assert again == pytest.approx(slid, abs=1e-15)


def test_commit_renews_the_rolling_matrix_without_moving_the_stretch():
    state = _state_at((0.0, 0.0, 0.0), rotation=(0.4, -0.3, 0.2))
    # turned on by 1 mrad about each axis and moved: a stretch within the stick's 1 um
    turned, centre = (0.401, -0.299, 0.201), (2e-4, -3e-4, RADIUS - DEPTH)
    before = stretch(RADIUS, centre, turned, state)
    assert 0.0 < math.hypot(*before) < LAW.stick_stretch
    renewed = committed_state(LAW, RADIUS, centre, turned, AT_REST, AT_REST, state)
    assert renewed[2:5] == pytest.approx(rolling_matrix(RADIUS, turned), rel=1e-15)
    assert stretch(RADIUS, centre, turned, renewed) == pytest.approx(before, abs=1e-15)


@pytest.mark.parametrize(("speed", "ratio"), [(0.0, 1.0), (1.2, 1.0), (1.5, 0.95), (40.0, 0.95)])
def test_commit_takes_the_drop_ratio_at_the_slip_of_the_steps_start(speed, ratio):
    # slip of the contact point v + w x (-r e_z): here all of it from the centre's velocity
    state = committed_state(LAW, RADIUS, (0.0, 0.0, RADIUS - DEPTH), AT_REST, (0.0, speed, 0.0),
                            AT_REST, _state_at((0.0, 0.0, 0.0)))
    assert state[DROP] == pytest.approx(ratio, rel=1e-12)  # mu_d / mu_s = 0.95 above v_d


def test_the_rolling_matrix_gives_the_contact_points_travel_of_the_exact_rotation():
    rng = np.random.default_rng(7)
    for _ in range(20):
        angles = rng.uniform(-1.2, 1.2, 3)
        rates = rng.uniform(-1.0, 1.0, 3)
        dt = 1e-7
        # omega in the plane's frame from two rotation matrices dt apart (Tait-Bryan x, y, z)
        now = Rotation.from_euler("XYZ", angles).as_matrix()
        later = Rotation.from_euler("XYZ", angles + dt * rates).as_matrix()
        spin = (later - now) / dt @ now.T
        omega = np.array([spin[2, 1], spin[0, 2], spin[1, 0]])
        j_xy, j_xz, j_yz = rolling_matrix(RADIUS, angles)
        travel = (j_xy * rates[1] + j_xz * rates[2], RADIUS * rates[0] + j_yz * rates[2])
        # finite difference over 1e-7 s: agreement to ~1e-6 of the rates
        assert travel == pytest.approx((-RADIUS * omega[1], RADIUS * omega[0]), abs=1e-6)


def test_a_friction_that_rises_with_speed_is_taken_at_the_current_slip_not_lagged():
    # mu_s 0.6 < mu_d 0.76: a lagged rise made a light tip swing from step to step (one
    # bristle of the paper's head: 41,234 Jacobians against 133 for the paper's law)
    rising = ContactLaw(friction_model="stick-slip", static_friction=0.6)
    state = _state_at((0.0, 0.0, 0.0))
    state[DROP] = 1.0  # what a tip at rest at the step's start would have
    centre = (0.05, 0.0, RADIUS - DEPTH)
    load = stick_slip_plane_force(rising, RADIUS, centre, AT_REST, (20.0, 0.0, 0.0), AT_REST,
                                  state)
    assert -load[0] == pytest.approx(0.76 * NORMAL, rel=1e-12)  # mu_d at 20 mm/s > v_d
    slow = stick_slip_plane_force(rising, RADIUS, centre, AT_REST, (1.0, 0.0, 0.0), AT_REST,
                                  state)
    assert -slow[0] == pytest.approx(0.6 * NORMAL, rel=1e-12)  # mu_s below v_s
