"""The inertia of the bristles' root pieces, which ride on the handle in no body of the
system (exubrush.models.inertia), and what moving them costs the head
(exubrush.world.kinematics.carried_wrench)."""

import numpy as np
import pytest
from exudyn.rigidBodyUtilities import RigidBodyInertia

from exubrush.models.geometry import BristleGeometry, rotation_about
from exubrush.models.inertia import dfm_root_piece, prb_root_piece, root_piece_inertia
from exubrush.models.sections import section_properties
from exubrush.world.kinematics import CarriedLoad, carried_wrench
from exubrush.world.pose import angular_velocity, rotation_matrix


def test_the_root_pieces_are_what_the_models_leave_to_the_handle():
    # DFM: half of one of N segments; PRB: the stub below the pivot at γl from the tip
    assert dfm_root_piece(10.5, 6) == pytest.approx(10.5 / 12, rel=1e-15)
    assert prb_root_piece(10.5, 0.85) == pytest.approx(0.15 * 10.5, rel=1e-14)


def test_a_root_piece_s_inertia_is_exudyn_s_slice_turned_and_moved():
    # Exudyn's own RigidBodyInertia (parallel axes, rotation) as the independent route
    section = section_properties("rectangle", 0.6, 0.9)
    frame = rotation_about([0.3, -1.0, 0.2], 0.4) @ np.array(
        [[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])
    bristle = BristleGeometry(root=np.array([1.5, -2.0, 0.0]), frame=frame, length=5.0,
                              tip_radius=0.4, section=section, width=0.6, height=0.9,
                              shape="rectangle")
    density, length = 1.1e-9, 1.25
    mass, first_moment, inertia = root_piece_inertia(bristle, density, length)
    m = density * section.area * length
    about_centre = np.diag([density * length * section.polar_moment,
                            density * length * section.second_moment_y + m * length**2 / 12,
                            density * length * section.second_moment_z + m * length**2 / 12])
    exudyn = RigidBodyInertia(mass=m, inertiaTensor=about_centre, inertiaTensorAtCOM=True)
    exudyn = exudyn.Rotated(frame).Translated(bristle.root + 0.5 * length * frame[:, 0])
    assert mass == pytest.approx(m, rel=1e-15)
    np.testing.assert_allclose(first_moment, m * exudyn.COM(), rtol=1e-13)
    np.testing.assert_allclose(inertia, exudyn.Inertia(), rtol=1e-12,
                               atol=1e-14 * np.abs(exudyn.Inertia()).max())


def _pose(t):
    """A handle moved and turned about three axes: its node's position [mm] and its
    Tait-Bryan angles [rad], rates and accelerations at t [s]."""
    w = np.array([2 * np.pi * 30, 2 * np.pi * 47, 2 * np.pi * 19])
    size = np.array([0.4, 0.25, 0.6])
    angles = size * np.sin(w * t + [0.2, 1.0, -0.5])
    rates = size * w * np.cos(w * t + [0.2, 1.0, -0.5])
    turning = -size * w**2 * np.sin(w * t + [0.2, 1.0, -0.5])
    position = np.array([1.5 * np.sin(2 * np.pi * 60 * t), 0.3 * t**2, -np.cos(90 * t)])
    return position, angles, rates, turning


def test_the_carried_wrench_is_the_rate_of_the_load_s_momenta():
    # a rigid body on the handle, centre c (body frame) off the node, inertia J about c.
    # Independently of the formula: its centre's acceleration and the rate of its angular
    # momentum about the centre, A J Aᵀ ω, by central differences of the prescribed
    # motion; about the node, the moment is that rate plus (A c) × m a_c
    mass, centre = 2e-6, np.array([0.7, -1.2, 3.0])
    turn = rotation_about([1.0, 2.0, -0.5], 0.7)
    about_centre = turn @ np.diag([3e-6, 5e-6, 4e-6]) @ turn.T
    about_node = about_centre + mass * (centre @ centre * np.eye(3) - np.outer(centre, centre))
    load = CarriedLoad(mass, mass * centre, about_node)
    h = 1e-6  # s
    times = np.linspace(0.0, 0.05, 7)

    def centre_position(t):
        position, angles, _, _ = _pose(t)
        return position + rotation_matrix(angles) @ centre

    def spin(t):
        _, angles, rates, _ = _pose(t)
        a = rotation_matrix(angles)
        return a @ about_centre @ a.T @ angular_velocity(angles, rates)

    for t in times:
        expected_force = mass * (centre_position(t + h) - 2 * centre_position(t)
                                 + centre_position(t - h)) / h**2
        expected_moment = ((spin(t + h) - spin(t - h)) / (2 * h)
                           + np.cross(centre_position(t) - _pose(t)[0], expected_force))
        position_rows = [_pose(t + d)[0] for d in (-h, 0.0, h)]
        node_acceleration = (position_rows[2] - 2 * position_rows[1] + position_rows[0]) / h**2
        _, angles, rates, turning = _pose(t)
        force, moment = carried_wrench(load, node_acceleration[None], angles[None],
                                       rates[None], turning[None])
        # the second differences' round-off, ε |x| / h² ~ 2e-16 × 3 mm / 1e-12 s² = 6e-4
        # mm/s² of accelerations near 1e5 (their truncation, h² x⁗ / 12, is less):
        # measured up to 2e-7 of the largest component; a moment about the centre where
        # the node's is due is off by 0.7 and more
        np.testing.assert_allclose(force[0], expected_force,
                                   atol=1e-5 * np.abs(expected_force).max())
        np.testing.assert_allclose(moment[0], expected_moment,
                                   atol=1e-5 * np.abs(expected_moment).max())


def test_a_load_at_the_node_costs_m_a_and_no_moment_while_the_head_does_not_turn():
    load = CarriedLoad(3e-6, np.zeros(3), np.diag([1e-6, 2e-6, 3e-6]))
    acceleration = np.array([[1.0, -2.0, 4.0], [0.0, 5.0, 0.0]])
    still = np.zeros((2, 3))
    force, moment = carried_wrench(load, acceleration, still, still, still)
    np.testing.assert_array_equal(force, 3e-6 * acceleration)
    np.testing.assert_array_equal(moment, np.zeros((2, 3)))
