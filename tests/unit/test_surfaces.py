"""Surface geometry against brute force: signed distances and normals of every analytic
surface, on random points, against the nearest of many points sampled on the surface."""

import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

from exubrush.output.cleaning import contact_geometry
from exubrush.parameters.case import Surface
from exubrush.util.float_math import FLOAT_MATH
from exubrush.world.surfaces import (
    Choice,
    Feature,
    features,
    flat_top_clearance,
    fold,
    height,
    orientation,
    resolve,
    taken,
    to_surface_frame,
)

CYLINDER = Surface(kind="cylinder", radius=4.0)
SPHERE = Surface(kind="sphere", radius=4.0)
TEETH = Surface(kind="tooth-row", tooth_width=7.0, gap_width=1.0, gap_depth=2.0,
                edge_radius=0.5)
SPACING = 2e-4  # [mm] between sampled surface points


def _profile_samples(surface: Surface, x_range) -> np.ndarray:
    """Points (x, z) on the boundary of a 2D profile (cylinder: its circle; tooth row:
    tops, roundings, walls and floor), spaced SPACING apart."""
    if surface.kind == "cylinder":
        r = surface.radius
        angle = np.arange(0.0, 2 * np.pi, SPACING / r)
        return np.stack([r * np.sin(angle), r * np.cos(angle) - r], axis=1)
    pieces = []
    w, g, h, rho = (surface.tooth_width, surface.gap_width, surface.gap_depth,
                    surface.edge_radius)
    pitch = w + g
    for k in range(math.floor(x_range[0] / pitch) - 1, math.ceil(x_range[1] / pitch) + 2):
        c = k * pitch
        top = np.arange(c - w / 2 + rho, c + w / 2 - rho, SPACING)
        pieces.append(np.stack([top, np.zeros_like(top)], axis=1))
        angle = np.arange(0.0, np.pi / 2, SPACING / max(rho, SPACING))
        for side in (-1.0, 1.0):
            centre = np.array([c + side * (w / 2 - rho), -rho])
            pieces.append(centre + rho * np.stack([side * np.sin(angle), np.cos(angle)], axis=1))
            wall = np.arange(-h, -rho, SPACING)
            pieces.append(np.stack([np.full_like(wall, c + side * w / 2), wall], axis=1))
        floor = np.arange(c + w / 2, c + w / 2 + g, SPACING)
        pieces.append(np.stack([floor, np.full_like(floor, -h)], axis=1))
    return np.concatenate(pieces)


def _nearest(samples: np.ndarray, points: np.ndarray):
    """Distance to the nearest sample and the unit vector from it to each point."""
    _, nearest = cKDTree(samples).query(points)
    offset = points - samples[nearest]
    length = np.linalg.norm(offset, axis=1)
    return length, offset / length[:, None]


def _closest_feature(surface: Surface, points3: np.ndarray, radius: float = 0.4):
    """Signed distance and normal of the nearest feature at each point (unplaced surfaces:
    the surface frame is the head frame), as the cleaning metrics find them."""
    _, normals, distances, _ = contact_geometry(surface, points3[:, None, :],
                                                np.array([radius]))
    return distances[:, 0], normals[:, 0]


def _outside_profile(surface: Surface, xz: np.ndarray) -> np.ndarray:
    """Mask of profile points that lie outside the solid, by the top envelope."""
    return xz[:, 1] > height(surface, xz[:, 0], 0.0)


@pytest.mark.parametrize("surface", [CYLINDER, TEETH], ids=["cylinder", "tooth-row"])
def test_profile_distance_and_normal_against_brute_force(surface):
    rng = np.random.default_rng(7)
    xz = np.stack([rng.uniform(-9.0, 9.0, 1500), rng.uniform(-2.5, 1.0, 1500)], axis=1)
    xz = xz[_outside_profile(surface, xz)]
    brute_distance, brute_normal = _nearest(_profile_samples(surface, (-9.0, 9.0)), xz)
    points = np.stack([xz[:, 0], rng.uniform(-5, 5, len(xz)), xz[:, 1]], axis=1)
    distance, normal = _closest_feature(surface, points)
    assert len(xz) > 300
    # the nearest sample lies at most s = SPACING/2 along the surface from the true closest
    # point and is never nearer than it: a point at d from a boundary of curvature radius
    # R sees it s²/2 (1/d + 1/R) further (R = ∞ on flat pieces; the smallest R is 0.5 mm)
    excess = brute_distance - distance
    curvature_radius = 0.5
    assert np.all(excess >= -1e-12)
    assert np.all(excess <= (SPACING / 2) ** 2 / 2 * (1 / distance + 1 / curvature_radius)
                  + 1e-12)
    far = brute_distance > 0.01  # the direction is only resolved well away from the surface
    np.testing.assert_allclose(normal[far][:, [0, 2]], brute_normal[far], atol=0.02)
    np.testing.assert_allclose(normal[:, 1], 0.0)


def test_sphere_distance_and_normal_against_brute_force():
    rng = np.random.default_rng(3)
    direction = rng.normal(size=(200, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    centre = np.array([0.0, 0.0, -SPHERE.radius])
    gap = rng.uniform(-0.1, 2.0, 200)  # a few points inside
    points = centre + (SPHERE.radius + gap)[:, None] * direction
    distance, normal = _closest_feature(SPHERE, points)
    np.testing.assert_allclose(distance, gap, atol=1e-12)
    np.testing.assert_allclose(normal, direction, atol=1e-12)


def test_features_penetrated_slightly_give_the_depth_below_the_surface():
    # just below a tooth's top (d = −0.01), above the floor (0.01), inside the rounding
    for x, z, expected in ((0.0, -0.01, -0.01), (4.0, -1.99, 0.01),
                           (3.0 + 0.49 * math.sin(0.6), -0.5 + 0.49 * math.cos(0.6), -0.01)):
        distance, _ = _closest_feature(TEETH, np.array([[x, 0.0, z]]))
        assert distance[0] == pytest.approx(expected, abs=1e-12)


def test_fold_is_relative_to_the_nearest_tooth():
    pitch = TEETH.tooth_width + TEETH.gap_width
    for x in (-17.0, -4.0001, -3.9999, 0.0, 3.9999, 4.0001, 12.5, 40.0):
        u = fold(TEETH, x)
        assert -pitch / 2 <= u < pitch / 2
        assert (x - u) / pitch == pytest.approx(round((x - u) / pitch), abs=1e-12)


def test_neighbour_tooth_only_for_a_sphere_wider_than_the_gap():
    narrow, wide = features(TEETH, (3.9, 0.0, -1.0), 0.45), features(TEETH, (3.9, 0.0, -1.0),
                                                                     0.55)
    assert len(narrow) == 2 and len(wide) == 3  # tooth (+ neighbour) + floor
    # the sphere in the middle of the gap at r = 0.55 touches both walls by 0.05 mm
    middle = [resolve(f) for f in features(TEETH, (4.0, 0.0, -1.0), 0.55)]
    walls = sorted(f.distance for f in middle[:2])
    assert walls == pytest.approx([0.5, 0.5])
    assert {f.normal[0] for f in middle[:2]} == {1.0, -1.0}


def test_height_is_the_top_of_each_surface():
    assert height(Surface(), 3.0, -2.0) == 0.0
    assert height(CYLINDER, 4.0, 7.0) == pytest.approx(-4.0)
    assert height(CYLINDER, 2.0, 0.0) == pytest.approx(math.sqrt(12.0) - 4.0)
    assert height(SPHERE, 1.0, 1.0) == pytest.approx(math.sqrt(14.0) - 4.0)
    assert height(TEETH, [0.0, 3.0, 3.5, 3.9, 8.0], 0.0) == pytest.approx([0.0, 0.0, -0.5,
                                                                          -2.0, 0.0])
    # on the rounding, the height is the circle's
    assert height(TEETH, 3.3, 0.0) == pytest.approx(math.sqrt(0.25 - 0.09) - 0.5)


def test_choice_takes_the_branch_of_its_condition():
    up, side = Feature((0.0, 0.0, 1.0), 0.3), Feature((1.0, 0.0, 0.0), 0.7)
    assert resolve(Choice(True, up, side)) == up
    assert resolve(Choice(False, up, side), FLOAT_MATH) == side


@pytest.mark.parametrize("gap", [1.0, 0.5])
def test_taken_gives_the_feature_resolve_gives_on_floats(gap):
    # the pre-step hooks follow the taken branch instead of resolving every branch
    row = Surface(kind="tooth-row", gap_width=gap)
    rng = np.random.default_rng(7)
    for x, z in rng.uniform([-4.0, -1.2], [4.0, 0.6], size=(300, 2)):
        for feature in features(row, (x, 0.0, z), 0.4):
            assert taken(feature) == resolve(feature)


def test_flat_top_clearance_is_where_the_top_plane_is_the_closest_feature():
    rng = np.random.default_rng(3)
    top = (0.0, 0.0, 1.0)
    for x, z in rng.uniform([-12.0, -1.0], [12.0, 0.8], size=(2000, 2)):
        clearance = flat_top_clearance(TEETH, x, z)
        nearest = taken(features(TEETH, (x, 0.0, z), 0.1)[0])
        if clearance > 0.0:  # over the flat part of a top: the top plane, at height z
            assert nearest.normal == top and nearest.distance == z
        elif z >= 0.0:  # above a rounding or a gap: a rounding's normal leans over
            assert nearest.normal != top
        # the top's height (its own formula) stays 0 for the clearance, outwards, and
        # falls just beyond it
        if clearance > 0.0:
            outwards = 1.0 if fold(TEETH, x) >= 0.0 else -1.0
            assert height(TEETH, x + outwards * 0.999 * clearance, 0.0) == 0.0
            assert height(TEETH, x + outwards * (clearance + 0.01), 0.0) < 0.0
    assert flat_top_clearance(TEETH, 0.0, -0.1) == -math.inf  # a centre below the tops


def test_placement_turns_and_shifts_into_the_surface_frame():
    placed = Surface(kind="cylinder", x=1.0, y=2.0, yaw=math.radians(90.0))
    local = to_surface_frame(placed, [[1.0, 5.0, 0.3], [4.0, 2.0, -1.0]])
    np.testing.assert_allclose(local, [[3.0, 0.0, 0.3], [0.0, -3.0, -1.0]], atol=1e-12)
    turn = orientation(placed)
    np.testing.assert_allclose(turn @ local[0] + [1.0, 2.0, 0.0], [1.0, 5.0, 0.3], atol=1e-12)
