"""Contact between bristles (exubrush.contact.between) against geometry and the law."""

import numpy as np
import pytest

from exubrush.contact.between import (
    PARALLEL,
    SOFT_DEPTH,
    Chains,
    candidate_pairs,
    contact_parameters,
    law_vector,
    pair_corner_forces,
    pair_corners,
)
from exubrush.contact.between_kernel import (
    POSITION_STEP,
    VELOCITY_STEP,
    group_forces,
    group_jacobian,
)
from exubrush.parameters.case import BristleContactLaw

LAW = BristleContactLaw()
FRICTIONLESS = LAW.replace(friction=0.0)
R = 0.1  # mm, a filament's radius


def _group_forces(chains, points, pairs, law, velocities=None):
    """The compiled group forces [N] on each of ``points`` (3 coordinates each, q = 0)."""
    count = len(points)
    out = np.zeros(3 * count)
    corners, radii, inner, far = pair_corners(chains, pairs)
    velocities = np.zeros(3 * count) if velocities is None else velocities.ravel()
    group_forces(np.zeros(3 * count), velocities, points, np.arange(3 * count).reshape(-1, 3),
                 corners, radii, inner, far, law_vector(law), out)
    return out.reshape(-1, 3)


def _segment_distance_brute(a0, a1, b0, b1, samples=1001):
    s = np.linspace(0.0, 1.0, samples)
    pa = a0 + s[:, None] * (a1 - a0)
    pb = b0 + s[:, None] * (b1 - b0)
    return np.min(np.linalg.norm(pa[:, None] - pb[None], axis=2))


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_crossing_segments_touch_at_their_closest_points():
    rng = np.random.default_rng(3)
    for _ in range(60):
        a0, a1, b0, b1 = rng.normal(size=(4, 3))
        points, weight = contact_parameters(a0, a1, b0, b1)
        s, t = points[0]
        found = np.linalg.norm((b0 + t * (b1 - b0)) - (a0 + s * (a1 - a0)))
        # the brute force samples the segments every 1/2000: its minimum lies above the
        # exact one by at most the sampling's error, of order (1/1000)² for smooth minima
        assert found <= _segment_distance_brute(a0, a1, b0, b1) + 1e-9


def _side_by_side(angle, gap=0.0, length=1.0):
    """Segment a along x, segment b beside it at 2R + gap in y, turned by angle about z."""
    a0, a1 = np.zeros(3), np.array([length, 0.0, 0.0])
    b0 = np.array([0.0, 2 * R + gap, 0.0])
    b1 = b0 + length * np.array([np.cos(angle), np.sin(angle), 0.0])
    return a0, a1, b0, b1


def test_side_by_side_segments_share_the_load_between_the_ends_of_their_common_stretch():
    a0, a1, b0, b1 = _side_by_side(0.0, gap=-0.001)
    points, weight = contact_parameters(a0, a1, b0, b1)
    assert weight == 0.0
    np.testing.assert_allclose(points[1:], [[0.0, 0.0], [1.0, 1.0]], atol=1e-12)


def test_the_force_stays_continuous_as_segments_turn_from_side_by_side_to_crossing():
    # b turns about the y axis through the point across a's middle: the lines stay 2R − δ
    # apart at every angle, so the total force is that of the overlap, carried by the
    # crossing point or, side by side, in proportion to the stretch a and b share (cos of
    # the angle over most of it)
    angles = np.linspace(0.0, 3 * PARALLEL[1], 301)
    forces = []
    for angle in angles:
        direction = 0.5 * np.array([np.cos(angle), 0.0, np.sin(angle)])
        centre = np.array([0.5, 2 * R - 0.004, 0.0])
        x = np.array([[[0, 0, 0], [1, 0, 0], centre - direction, centre + direction]], float)
        f, _ = pair_corner_forces(x, np.zeros_like(x), np.array([[R, R]]),
                                  np.zeros((1, 4), bool), FRICTIONLESS)
        forces.append(f[0])
    forces = np.array(forces)
    soft = SOFT_DEPTH * 2 * R
    expected = FRICTIONLESS.stiffness * (0.004 - 0.5 * soft)
    # within the blend (angles up to 0.1 rad) the shared stretch is cos(angle) >= 0.995
    np.testing.assert_allclose(forces[:, 2:, 1].sum(axis=1), expected, rtol=0.005)
    # the split between b's ends changes smoothly: no jump between angles 1e-3 rad apart
    # larger than 1 % of the force
    assert np.abs(np.diff(forces, axis=0)).max() < 0.01 * expected


def test_a_pressed_pair_pushes_apart_with_equal_and_opposite_forces_and_no_moment():
    x = np.array([_side_by_side(-0.3, gap=-0.004)])
    v = np.random.default_rng(1).normal(size=x.shape)
    f, overlap = pair_corner_forces(x, v, np.array([[R, R]]), np.zeros((1, 4), bool),
                                    FRICTIONLESS)
    assert overlap[0] > 0
    np.testing.assert_allclose(f[0].sum(axis=0), 0.0, atol=1e-15)
    moment = np.cross(x[0], f[0]).sum(axis=0)
    np.testing.assert_allclose(moment, 0.0, atol=1e-15)  # the force acts along the normal
    assert f[0, 2:, 1].sum() > 0  # b (at larger y) is pushed towards +y


def test_the_normal_force_follows_the_penalty_beyond_the_soft_depth():
    # two crossing segments, b above a by 2R − depth: f = k (depth − δ/2) with δ = soft depth
    depth = 0.01
    x = np.array([[[-1, 0, 0], [1, 0, 0], [0, -1, 2 * R - depth], [0, 1, 2 * R - depth]]],
                 float)
    f, overlap = pair_corner_forces(x, np.zeros_like(x), np.array([[R, R]]),
                                    np.zeros((1, 4), bool), LAW)
    soft = SOFT_DEPTH * 2 * R
    assert overlap[0] == pytest.approx(depth, rel=1e-12)
    assert f[0, 2:, 2].sum() == pytest.approx(LAW.stiffness * (depth - 0.5 * soft), rel=1e-12)
    # centred crossing: each end of each segment takes half
    np.testing.assert_allclose(f[0, :, 2], np.array([-1, -1, 1, 1]) * f[0, 3, 2], rtol=1e-12)


@pytest.mark.parametrize("speed", [0.3, 5.0, 500.0])
def test_friction_opposes_sliding_and_approaches_mu_times_the_normal_force(speed):
    x = np.array([[[-1, 0, 0], [1, 0, 0], [0, -1, 2 * R - 0.01], [0, 1, 2 * R - 0.01]]],
                 float)
    v = np.zeros_like(x)
    v[0, 2:, 0] = speed  # b slides along +x [mm/s]
    f, _ = pair_corner_forces(x, v, np.array([[R, R]]), np.zeros((1, 4), bool), LAW)
    on_b = f[0, 2:].sum(axis=0)
    regularised = speed / np.hypot(speed, LAW.friction_velocity)
    assert on_b[0] == pytest.approx(-LAW.friction * regularised * on_b[2], rel=1e-12)
    if speed > 100 * LAW.friction_velocity:  # Coulomb's μ f_n well above v_r
        assert on_b[0] == pytest.approx(-LAW.friction * on_b[2], rel=1e-4)


def test_a_contact_at_a_joint_counts_once():
    # chain a: three points along x with a joint at the origin; b crosses above the joint
    chains = Chains.from_polylines([[0, 1, 2], [3, 4]], [R, R])
    points = np.array([[-1, 0, 0], [0, 0, 0], [1, 0, 0], [0, -1, 0.19], [0, 1, 0.19]], float)
    pairs = candidate_pairs(chains, points)
    assert sorted(map(tuple, pairs)) == [(0, 2), (1, 2)]
    total_on_b = _group_forces(chains, points, pairs, LAW)[3:].sum(axis=0)
    soft = SOFT_DEPTH * 2 * R
    assert total_on_b[2] == pytest.approx(LAW.stiffness * (0.01 - 0.5 * soft), rel=1e-9)


def _crossing_over_a_joint(x, kink):
    """Force [N] along z on a segment b (along y) pressed 10 µm into a chain a at x [mm]
    along it; a's second segment rises by ``kink`` [mm] over its 1 mm."""
    chains = Chains.from_polylines([[0, 1, 2], [3, 4]], [R, R])
    height = 2 * R - 0.01 + (kink * x if x > 0 else 0.0)
    points = np.array([[-1, 0, 0], [0, 0, 0], [1, 0, kink], [x, -1, height], [x, 1, height]])
    pairs = candidate_pairs(chains, points)
    return _group_forces(chains, points, pairs, LAW)[3:].sum(axis=0)[2]


def test_a_contact_moving_over_a_joint_keeps_its_force():
    from exubrush.contact.between import JOINT_TIE

    soft = SOFT_DEPTH * 2 * R
    pressed = LAW.stiffness * (0.01 - 0.5 * soft)
    across = np.linspace(-0.3, 0.3, 241)
    # a straight chain: the segment closer to b carries the contact; where the two are
    # within JOINT_TIE soft depths of each other it is shared with the one whose overlap is
    # at most that much smaller, so the force dips by at most k·JOINT_TIE·soft
    straight = np.array([_crossing_over_a_joint(x, 0.0) for x in across])
    assert straight.max() <= pressed * (1 + 1e-12)
    assert straight.min() >= pressed - LAW.stiffness * JOINT_TIE * soft
    assert straight[0] == pytest.approx(pressed, rel=1e-12)
    # a bent chain (1.1° at the joint, as a bristle's chain bends): no jump. Half-counting
    # at the joint made the force jump by up to a half of it here; now the largest change
    # between samples 2.5 µm apart stays below 2 % of the force
    for kink in (0.02, -0.02):
        bent = np.array([_crossing_over_a_joint(x, kink) for x in across])
        assert np.abs(np.diff(bent)).max() < 0.02 * pressed


def test_a_contact_on_the_outer_side_of_a_bent_joint_acts_whole():
    # chain a bends 20° away from b at its joint: both segments find the joint itself, each
    # takes half (a share that followed each segment's own line lost this contact)
    chains = Chains.from_polylines([[0, 1, 2], [3, 4]], [R, R])
    drop = np.tan(np.radians(20.0))
    points = np.array([[-1, 0, -drop], [0, 0, 0], [1, 0, -drop], [0, -1, 0.19], [0, 1, 0.19]])
    total_on_b = _group_forces(chains, points, candidate_pairs(chains, points), LAW)[3:]
    soft = SOFT_DEPTH * 2 * R
    assert total_on_b.sum(axis=0)[2] == pytest.approx(LAW.stiffness * (0.01 - 0.5 * soft),
                                                      rel=1e-9)


def test_segments_of_one_bristle_are_never_candidates():
    chains = Chains.from_polylines([[0, 1, 2, 3]], [R])
    points = np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.05, 0], [0, 0.05, 0]], float)
    assert len(candidate_pairs(chains, points)) == 0


def test_derivatives_match_the_stiffness_of_the_law():
    x = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 2 * R - 0.01], [0, 1, 2 * R - 0.01]], float)
    chains = Chains.from_polylines([[0, 1], [2, 3]], [R, R])
    corners, radii, inner, far = pair_corners(chains, np.array([[0, 1]]))

    def matrix(f_position, f_velocity):
        triplets = group_jacobian(np.zeros(12), np.zeros(12), x, np.arange(12).reshape(4, 3),
                                  corners, radii, inner, far, law_vector(FRICTIONLESS),
                                  f_position,
                                  f_velocity, POSITION_STEP, VELOCITY_STEP)
        result = np.zeros((12, 12))
        np.add.at(result, (triplets[:, 0].astype(int), triplets[:, 1].astype(int)),
                  triplets[:, 2])
        return result

    # lifting b's two points by dz lowers the overlap by dz: b's z force drops by k dz (the
    # Jacobian is that of the left-hand side, −∂f/∂q)
    lift_b = matrix(1.0, 0.0)[np.ix_([8, 11], [8, 11])].sum()
    assert lift_b == pytest.approx(FRICTIONLESS.stiffness, rel=1e-6)
    # central differences of a linear term: exact but for rounding
    assert matrix(0.0, 1.0)[np.ix_([8, 11], [8, 11])].sum() == pytest.approx(
        FRICTIONLESS.damping, rel=1e-6)


def test_a_contact_is_located_halfway_between_the_closest_points():
    from exubrush.contact.between import contact_locations

    chains = Chains.from_polylines([[0, 1], [2, 3]], [R, R])
    points = np.array([[-1, 0, 0], [1, 0, 0], [0.25, -1, 0.15], [0.25, 1, 0.15]], float)
    np.testing.assert_allclose(contact_locations(chains, points, LAW), [[0.25, 0.0, 0.075]],
                               atol=1e-12)
    apart = points + np.array([0.0, 0.0, 1.0]) * np.array([[0], [0], [1], [1]])
    assert contact_locations(chains, apart, LAW).shape == (0, 3)


def test_a_groups_compiled_jacobian_is_the_slope_of_its_compiled_forces():
    from exubrush.contact.between import law_vector, pair_corners
    from exubrush.contact.between_kernel import group_forces, group_jacobian

    # three side-by-side chains of 4 points pressed together, points scattered by 5 µm; q
    # holds each point's displacement (3 coordinates) after 2 unused entries
    rng = np.random.default_rng(7)
    chains = Chains.from_polylines([[0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11]], [R, R, R])
    base = np.array([[x, 0.0, z] for x in (0.0, 0.198, 0.396) for z in (0, 1, 2, 3)], float)
    coordinates = 2 + np.arange(36).reshape(12, 3)
    q = np.zeros(38)
    q[2:] = rng.uniform(-0.005, 0.005, 36)
    q_t = rng.uniform(-2.0, 2.0, 38)
    corners, radii, inner, far = pair_corners(
        chains, candidate_pairs(chains, base + q[coordinates], margin=0.05))
    law = law_vector(LAW)

    def forces(q, q_t):
        out = np.zeros(38)
        group_forces(q, q_t, base, coordinates, corners, radii, inner, far, law, out)
        return out

    assert np.abs(forces(q, q_t)).max() > 0.01  # they press: a test of something
    for f_position, f_velocity, step in ((1.0, 0.0, 1e-7), (0.0, 1.0, 1e-4)):
        triplets = group_jacobian(q, q_t, base, coordinates, corners, radii, inner, far, law,
                                  f_position, f_velocity, 1e-8, 1e-5)
        jacobian = np.zeros((38, 38))
        np.add.at(jacobian, (triplets[:, 0].astype(int), triplets[:, 1].astype(int)),
                  triplets[:, 2])
        slope = np.zeros((38, 38))
        for column in range(38):
            move = np.zeros(38)
            move[column] = step
            if f_position:
                slope[:, column] = -(forces(q + move, q_t) - forces(q - move, q_t)) / (2 * step)
            else:
                slope[:, column] = -(forces(q, q_t + move) - forces(q, q_t - move)) / (2 * step)
        # the kernel's forward differences (steps 1e-8 mm, 1e-5 mm/s) against central ones:
        # they agree to the forward difference's truncation error, the law's curvature
        # times half its step (in the soft zone k/δ ≈ 1.25e4 N/mm² times 5e-9 mm, 1e-6 of
        # the 50 N/mm stiffness; measured 1e-5 of the largest slope where two terms add up)
        np.testing.assert_allclose(jacobian, slope, atol=3e-5 * np.abs(slope).max())


def _upright_tuft(columns: int, rows: int, spacing: float, segments: int = 3):
    """Chains of ``columns`` x ``rows`` upright filaments 1.5 mm long, ``spacing`` [mm]
    between neighbours' axes, and their points (root first)."""
    polylines, points = [], []
    for column in range(columns):
        for row in range(rows):
            polylines.append(list(range(len(points), len(points) + segments + 1)))
            points += [[column * spacing, row * spacing, 0.5 * k] for k in range(segments + 1)]
    return Chains.from_polylines(polylines, [R] * len(polylines)), np.array(points, float)


def test_candidate_pairs_are_sorted_so_a_wider_search_gives_the_same_forces():
    # the forces add up in the list's order: a list searched with another reach, or at
    # another moment, must give the touching pairs' forces to the last bit
    chains, points = _upright_tuft(4, 4, 2 * R - 0.002)
    points[:, :2] += 0.02 * np.sin(np.arange(points.size).reshape(points.shape))[:, :2]
    narrow, wide = candidate_pairs(chains, points), candidate_pairs(chains, points, 1.0)
    for pairs in (narrow, wide):
        assert np.array_equal(pairs, pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))])
    assert len(wide) > 2 * len(narrow) > 0
    assert np.array_equal(_group_forces(chains, points, narrow, LAW),
                          _group_forces(chains, points, wide, LAW))


class _SystemData:
    """What BristleContact and contact_refresh read of ``mbs.systemData``: the state at a
    step attempt's start (time ``start`` [s], the object's coordinates and velocities)."""

    def __init__(self, q, q_t, start):
        self.q, self.q_t, self.start = q, q_t, start

    def GetODE2Coordinates(self, *configuration):  # noqa: N802 (Exudyn's names)
        return self.q

    def GetODE2Coordinates_t(self, *configuration):  # noqa: N802
        return self.q_t

    def GetTime(self, *configuration):  # noqa: N802
        return self.start


def _contact_of(chains, points):
    from exubrush.contact.exudyn_between import BristleContact

    size = points.size
    return BristleContact(chains=chains, law=LAW, coordinates=np.arange(size).reshape(-1, 3),
                          base=points, size=size, system_indices=np.arange(size))


def _bristles_paired(contact):
    """The bristle pairs (lower index first) that the candidate list holds."""
    corners = contact.candidate_corners[0]
    owner = np.zeros(len(contact.base), int)
    owner[contact.chains.starts] = contact.chains.bristle
    owner[contact.chains.ends] = contact.chains.bristle
    return {tuple(sorted(pair)) for pair in owner[corners[:, [0, 2]]].tolist()}


@pytest.mark.parametrize("closing", [0.0, 100.0])
def test_candidates_are_sized_by_the_attempts_step_and_speeds_relative_to_the_slide(closing):
    # three filaments in a row, the first two touching, the third 0.3 mm from the second,
    # all sliding at 100 mm/s along the row (the head's slide), a 2 ms attempt: the slide
    # brings no pair closer, so the third is no candidate (with the slide's speed and a
    # 10 ms step it was); closing it at 100 mm/s within the attempt (0.2 mm each way)
    # makes it one
    from exubrush.contact.exudyn_between import contact_refresh

    chains, points = _upright_tuft(3, 1, 2 * R)
    points[8:, 0] += 0.3
    velocities = np.zeros_like(points)
    velocities[:, 0] = 100.0
    velocities[8:, 0] -= closing
    contact = _contact_of(chains, points)

    class System:
        systemData = _SystemData(np.zeros(points.size), velocities.ravel(), 1.0)
        sys = {}

    contact_refresh(contact)(System, 1.002)
    expected = {(0, 1)} | ({(1, 2)} if closing else set())
    assert _bristles_paired(contact) == expected


def test_a_candidate_list_searched_for_a_far_reach_is_searched_again_for_a_near_one():
    # a list searched while a filament moved fast holds pairs that a slow step cannot
    # bring together: the next refresh that needs less than two skins less searches again
    chains, points = _upright_tuft(3, 1, 2 * R)
    points[8:, 0] += 0.3
    contact = _contact_of(chains, points)

    class System:
        systemData = _SystemData(np.zeros(points.size), np.zeros(points.size), 0.0)

    contact.refresh(System, 1.0)
    assert _bristles_paired(contact) == {(0, 1), (1, 2), (0, 2)}
    contact.refresh(System, 0.1)
    assert _bristles_paired(contact) == {(0, 1)}
