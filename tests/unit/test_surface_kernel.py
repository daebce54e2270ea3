"""The compiled tip-surface contact (exubrush.contact.surface_kernel) against the generic
law over the surface's features (exubrush.contact.laws.sphere_surface_force)."""

import numpy as np
import pytest

from exubrush.contact.laws import sphere_surface_force
from exubrush.contact.surface_kernel import (
    MAX_FEATURES,
    law_numbers,
    node_jacobian,
    node_load,
    surface_load,
    surface_numbers,
)
from exubrush.parameters.case import ContactLaw, Surface
from exubrush.world.surfaces import features

LAW = ContactLaw()
SURFACES = [
    Surface(kind="plane"),
    Surface(kind="cylinder", radius=4.0),
    Surface(kind="sphere", radius=4.0),
    Surface(kind="tooth-row"),
    Surface(kind="tooth-row", gap_width=0.5),  # narrower than the sphere: both teeth
]


def _kernel(surface, radius, centre, velocity, omega, scale, drops):
    kind, params = surface_numbers(surface)
    lagged = np.full(MAX_FEATURES, -1.0)
    if drops is not None:
        lagged[:len(drops)] = drops
    out = np.zeros(6)
    surface_load(kind, params, law_numbers(LAW), radius, np.asarray(centre, float),
                 np.asarray(velocity, float), np.asarray(omega, float), scale, lagged, out)
    return out


@pytest.mark.parametrize("surface", SURFACES, ids=lambda s: f"{s.kind}-{s.gap_width}")
@pytest.mark.parametrize("lagged", [False, True])
def test_the_kernel_is_the_generic_law(surface, lagged):
    rng = np.random.default_rng(3)
    radius = 0.4
    touched = 0
    for _ in range(400):
        # centres around the surface's top and, on a tooth row, inside a gap
        centre = [rng.uniform(-5.0, 5.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.6, 0.5)]
        velocity = rng.normal(scale=rng.choice([0.5, 3.0, 40.0]), size=3)
        omega = rng.normal(scale=20.0, size=3)
        scale = rng.choice([1.0, 0.37])
        found = features(surface, centre, radius)
        drops = rng.uniform(0.9, 1.0, size=len(found)).tolist() if lagged else None
        expected = sphere_surface_force(LAW, radius, found, velocity.tolist(), omega.tolist(),
                                        friction_scale=scale, drops=drops)
        got = _kernel(surface, radius, centre, velocity, omega, scale, drops)
        # rounding: the same operations, summed in the same order
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-15)
        touched += bool(np.any(np.asarray(expected) != 0.0))
    assert touched > 40  # the states reach the surface often enough to test the law


def _rotation(yaw):
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _g_matrix(e):
    e0, e1, e2, e3 = e
    return 2.0 * np.array([[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]])


def test_node_load_turns_the_law_into_the_nodes_generalized_forces():
    # a placed, turned tooth row; the node's state by hand: centre, velocity and ω turned
    # into the surface frame, the force and moment back, the moment as Gᵀ M
    surface = Surface(kind="tooth-row", x=0.7, y=-0.4, yaw=np.radians(90.0))
    kind, params = surface_numbers(surface)
    turn, origin = _rotation(surface.yaw), np.array([surface.x, surface.y, 0.0])
    rng = np.random.default_rng(11)
    reference = np.array([0.2, -0.1, 0.3, 1.0, 0.0, 0.0, 0.0])
    drops = np.full(MAX_FEATURES, -1.0)
    checked = 0
    for _ in range(200):
        q = np.concatenate([rng.uniform(-3.0, 3.0, 3), rng.normal(scale=0.3, size=4)])
        e = reference[3:] + q[3:]
        q[3:] = e / np.linalg.norm(e) - reference[3:]  # unit Euler parameters
        q_t = np.concatenate([rng.normal(scale=5.0, size=3), rng.normal(scale=2.0, size=4)])
        e = reference[3:] + q[3:]
        omega = _g_matrix(e) @ q_t[3:]
        local = np.zeros(6)
        centre = turn.T @ (reference[:3] + q[:3] - origin)
        surface_load(kind, params, law_numbers(LAW), 0.4, centre, turn.T @ q_t[:3],
                     turn.T @ omega, 1.0, drops, local)
        expected = np.concatenate([turn @ local[:3], _g_matrix(e).T @ (turn @ local[3:])])
        out, scratch = np.zeros(7), np.zeros(6)
        node_load(q, q_t, reference, turn, origin, kind, params, law_numbers(LAW), 0.4, 1.0,
                  drops, out, scratch)
        np.testing.assert_allclose(out, expected, rtol=1e-12, atol=1e-14)
        checked += bool(np.any(local != 0.0))
    assert checked > 20


def test_node_jacobian_is_the_derivative_of_node_load():
    surface = Surface(kind="cylinder", radius=4.0)
    kind, params = surface_numbers(surface)
    turn, origin = np.eye(3), np.zeros(3)
    reference = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    q = np.array([0.3, 0.1, 0.35, 0.0, 0.05, -0.02, 0.0])
    q_t = np.array([4.0, -1.0, -0.5, 0.1, 0.3, -0.2, 0.05])
    drops = np.full(MAX_FEATURES, -1.0)
    args = (reference, turn, origin, kind, params, law_numbers(LAW), 0.4, 1.0, drops)

    def load(position, velocity):
        out = np.zeros(7)
        node_load(position, velocity, *args, out, np.zeros(6))
        return out

    assert np.linalg.norm(load(q, q_t)) > 0.01  # in contact
    triplets = np.zeros((49, 3))
    node_jacobian(q, q_t, *args, 0.7, 0.3, triplets)  # f_position 0.7, f_velocity 0.3
    jacobian = np.zeros((7, 7))
    jacobian[triplets[:, 0].astype(int), triplets[:, 1].astype(int)] = triplets[:, 2]
    expected = np.zeros((7, 7))
    for column in range(7):  # numpy's own central differences, a larger step
        step = np.zeros(7)
        step[column] = 1e-6
        expected[:, column] = -(0.7 * (load(q + step, q_t) - load(q - step, q_t))
                                + 0.3 * (load(q, q_t + step) - load(q, q_t - step))) / 2e-6
    # 1e-5 of the largest entry: the two steps' truncation and rounding
    np.testing.assert_allclose(jacobian, expected, rtol=0, atol=1e-5 * np.abs(expected).max())
