"""Contact between bristles (pure numpy, mm-N-s).

Geometry. Each bristle is a chain of capsules along its centreline: the polyline through
its points (root, then the nodes of its model), every segment swept by a sphere of the
bristle's contact radius. Two segments of different bristles touch where the distance
between their contact points (contact_parameters) is below the sum of the radii; the
overlap is that difference.

Law (docs/tufts.md, "Contact between bristles"). Along the normal n from the first
segment's contact point to the second's, a penalty with damping that never pulls,
f_n = max(k·g(overlap) − c·h(overlap)·(n·v_rel), 0), where g grows as overlap²/(2δ) up to
the depth δ = SOFT_DEPTH·(r_a + r_b) and as overlap − δ/2 beyond it (so the force starts
with zero slope) and h = min(overlap/δ, 1); and Coulomb friction against the tangential relative
velocity v_t, regularised below the speed v_r: f_t = −μ f_n v_t / max(|v_t|, v_r). The
force acts at the two closest points with opposite signs and is handed to each segment's
end points in proportion to the closest point's position on it ((1 − s), s), which keeps
its resultant and its moment about any point. A crossing contact at a joint of a chain is
found by both segments that meet there; each then counts half. Side-by-side segments count
in proportion to the stretch they share.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from exubrush.parameters.case import BristleContactLaw

# angles between two segments [rad] below which they count as parallel, above which as
# crossing; blended in between (contact_parameters)
PARALLEL = (0.02, 0.1)
# depth over which the normal force grows from zero slope to the penalty's, as a share of
# the two radii: filaments of a tuft touch all along at rest, and a kink in the force at
# zero overlap there kept Newton from converging (docs/tufts.md)
SOFT_DEPTH = 0.01


@dataclass(frozen=True)
class Chains:
    """The capsule chains of a group of bristles.

    Attributes
    ----------
    starts, ends : ndarray (m,) of int
        Point indices of each segment's ends (into the group's point array).
    bristle : ndarray (m,) of int
        The bristle each segment belongs to (segments of one bristle never touch).
    radius : ndarray (m,)
        Contact radius of each segment [mm].
    inner_start, inner_end : ndarray (m,) of bool
        Whether the segment's start (end) is a joint shared with the next segment of its
        chain (a contact found there counts half).
    """

    starts: np.ndarray
    ends: np.ndarray
    bristle: np.ndarray
    radius: np.ndarray
    inner_start: np.ndarray
    inner_end: np.ndarray

    @classmethod
    def from_polylines(cls, polylines: list[list[int]], radii: list[float]) -> Chains:
        """Chains from each bristle's point indices, root first, and its contact radius."""
        starts, ends, owner, radius, inner_start, inner_end = [], [], [], [], [], []
        for index, (points, r) in enumerate(zip(polylines, radii, strict=True)):
            count = len(points) - 1
            for k in range(count):
                starts.append(points[k])
                ends.append(points[k + 1])
                owner.append(index)
                radius.append(r)
                inner_start.append(k > 0)
                inner_end.append(k < count - 1)
        return cls(np.array(starts, int), np.array(ends, int), np.array(owner, int),
                   np.array(radius, float), np.array(inner_start), np.array(inner_end))


def contact_parameters(a0, a1, b0, b1):
    """Where two segments of non-zero length touch; arrays (..., 3).

    Segments at more than PARALLEL[1] rad to each other touch at their closest points
    (Ericson 2005, §5.1.9). Near-parallel segments touch along a line, where the closest
    points jump from one end to the other at the slightest turn; there the contact acts at
    both ends of the stretch over which they lie side by side (pair_corner_forces shares
    it between them). Between PARALLEL[0] and PARALLEL[1] the two are blended smoothly, so
    that the force and its derivatives stay continuous for the Newton solver.

    Returns
    -------
    points : ndarray (3, 2, ...)
        Parameters (s, t) of the crossing contact and of the two side-by-side ends: the
        points a0 + s (a1 − a0) and b0 + t (b1 − b0).
    weight : ndarray (...)
        Share of the crossing contact (1 − weight goes to the side-by-side pair).
    """
    d1, d2, r = a1 - a0, b1 - b0, a0 - b0
    a = np.einsum("...i,...i", d1, d1)
    e = np.einsum("...i,...i", d2, d2)
    f = np.einsum("...i,...i", d2, r)
    c = np.einsum("...i,...i", d1, r)
    b = np.einsum("...i,...i", d1, d2)
    denom = a * e - b * b  # |d1|² |d2|² sin² of the angle between them
    sine2 = np.clip(denom / (a * e), 0.0, 1.0)
    crossing = np.clip((b * f - c * e) / np.where(denom > 0.0, denom, 1.0), 0.0, 1.0)
    t = (b * crossing + f) / e
    s_crossing = np.where(t < 0.0, np.clip(-c / a, 0.0, 1.0),
                          np.where(t > 1.0, np.clip((b - c) / a, 0.0, 1.0), crossing))
    t_crossing = np.clip(t, 0.0, 1.0)
    # side by side: the ends of b's shadow on a, and the points of b across from them
    shadow = np.stack([-c / a, (b - c) / a])
    s_low = np.clip(shadow.min(axis=0), 0.0, 1.0)
    s_high = np.clip(shadow.max(axis=0), 0.0, 1.0)
    t_low = np.clip((b * s_low + f) / e, 0.0, 1.0)
    t_high = np.clip((b * s_high + f) / e, 0.0, 1.0)
    low, high = np.sin(PARALLEL[0]) ** 2, np.sin(PARALLEL[1]) ** 2
    x = np.clip((sine2 - low) / (high - low), 0.0, 1.0)
    weight = x * x * (3.0 - 2.0 * x)  # smoothstep: 0 side by side, 1 crossing
    points = np.stack([np.stack([s_crossing, t_crossing]), np.stack([s_low, t_low]),
                       np.stack([s_high, t_high])])
    return points, weight


def candidate_pairs(chains: Chains, points: np.ndarray, margin: float = 0.0) -> np.ndarray:
    """Segment pairs (k, 2) of different bristles whose capsules come within ``margin``
    [mm] of each other: bounding spheres from a k-d tree first, then the segments'
    closest distance."""
    a, b = points[chains.starts], points[chains.ends]
    centre = 0.5 * (a + b)
    bound = 0.5 * np.linalg.norm(b - a, axis=1) + chains.radius
    pairs = cKDTree(centre).query_pairs(2.0 * bound.max() + margin, output_type="ndarray")
    if not len(pairs):
        return np.zeros((0, 2), int)
    i, j = pairs[:, 0], pairs[:, 1]
    near = np.linalg.norm(centre[i] - centre[j], axis=1) <= bound[i] + bound[j] + margin
    pairs = pairs[near & (chains.bristle[i] != chains.bristle[j])]
    i, j = pairs[:, 0], pairs[:, 1]
    points_ij, _ = contact_parameters(a[i], b[i], a[j], b[j])
    s, t = points_ij[0]
    gap = np.linalg.norm((a[j] + t[:, None] * (b[j] - a[j])) - (a[i] + s[:, None] * (b[i] - a[i])),
                         axis=1) - chains.radius[i] - chains.radius[j]
    return pairs[gap <= margin]


@dataclass(frozen=True)
class Contacts:
    """Touching segment pairs and the forces on their end points.

    Attributes
    ----------
    pairs : ndarray (m, 2) of int
        Segment indices (first, second).
    corners : ndarray (m, 4) of int
        Point indices of the first segment's start and end, then the second's.
    overlap : ndarray (m,)
        Overlap of the two capsules [mm] (> 0).
    corner_forces : ndarray (m, 4, 3)
        Force on each corner point [N] (joint halving included).
    """

    pairs: np.ndarray
    corners: np.ndarray
    overlap: np.ndarray
    corner_forces: np.ndarray


def pair_corner_forces(x: np.ndarray, v: np.ndarray, radii: np.ndarray, inner: np.ndarray,
                       law: BristleContactLaw) -> tuple[np.ndarray, np.ndarray]:
    """Forces on the four corner points of segment pairs (module docstring).

    The force's size and direction come from the segments' closest points (their overlap
    and common normal, continuous however the segments turn); where it acts follows
    :func:`contact_parameters`: at the closest points of crossing segments, and shared
    between the two ends of the common stretch of side-by-side ones, in proportion to
    their own overlaps (equal halves when both or neither overlap).

    Parameters
    ----------
    x, v : ndarray (m, 4, 3)
        Positions [mm] and velocities [mm/s] of the first segment's start and end, then
        the second's.
    radii : ndarray (m, 2)
        Contact radii of the two segments [mm].
    inner : ndarray (m, 4) of bool
        Whether each corner is a joint shared with the next segment of its chain.

    Returns
    -------
    forces : ndarray (m, 4, 3)
        [N]; zero for pairs that do not touch.
    overlap : ndarray (m,)
        Sum of the radii less the segments' distance [mm] (negative: a gap).
    """
    points, crossing = contact_parameters(x[:, 0], x[:, 1], x[:, 2], x[:, 3])
    reach = radii.sum(axis=1)
    soft = SOFT_DEPTH * reach
    gaps = [_between(x, s, t) for s, t in points]
    delta, distance = gaps[0]
    overlap = reach - distance
    normal = delta / np.where(distance > 0.0, distance, 1.0)[:, None]
    # the side-by-side ends' shares, from their own overlaps
    depth_low, depth_high = (np.maximum(reach - d, 0.0) + 0.1 * soft for _, d in gaps[1:])
    low_share = depth_low / (depth_low + depth_high)
    # a side-by-side contact counts in proportion to the stretch the two segments share
    # (the mean of its share of each): chains side by side then count each stretch once,
    # however their joints fall, and a pair that shares a joint only counts nothing
    (s_low, t_low), (s_high, t_high) = points[1], points[2]
    side = (1.0 - crossing) * 0.5 * (np.abs(s_high - s_low) + np.abs(t_high - t_low))
    shares = (crossing, side * low_share, side * (1.0 - low_share))
    relative = sum(share[:, None] * _relative_velocity(v, s, t)
                   for (s, t), share in zip(points, shares, strict=True))
    force = _law_force(overlap, normal, relative, soft, law)
    touching = (overlap > 0.0) & (distance > 0.0)
    force = np.where(touching[:, None], force, 0.0)
    forces = np.zeros(x.shape)
    for index, ((s, t), share) in enumerate(zip(points, shares, strict=True)):
        weight = share if index else share * (_joint_weight(s, inner[:, 0], inner[:, 1])
                                              * _joint_weight(t, inner[:, 2], inner[:, 3]))
        corner_shares = np.column_stack([-(1.0 - s), -s, 1.0 - t, t]) * weight[:, None]
        forces += corner_shares[:, :, None] * force[:, None, :]
    return forces, overlap


def _between(x, s, t):
    """Vector and distance [mm] from the first segment's point s to the second's point t."""
    a0, a1, b0, b1 = x[:, 0], x[:, 1], x[:, 2], x[:, 3]
    delta = (b0 + t[:, None] * (b1 - b0)) - (a0 + s[:, None] * (a1 - a0))
    return delta, np.linalg.norm(delta, axis=1)


def _relative_velocity(v, s, t):
    """Velocity of the second segment's point t relative to the first's point s [mm/s]."""
    return ((1.0 - t)[:, None] * v[:, 2] + t[:, None] * v[:, 3]
            - (1.0 - s)[:, None] * v[:, 0] - s[:, None] * v[:, 1])


def _law_force(overlap, normal, relative, soft, law: BristleContactLaw):
    """Force on the second segment [N] (module docstring), zero slope at first touch."""
    approach = np.einsum("ij,ij->i", normal, relative)
    depth = np.maximum(overlap, 0.0)
    elastic = law.stiffness * np.where(depth < soft, 0.5 * depth**2 / soft, depth - 0.5 * soft)
    damping = law.damping * np.minimum(depth / soft, 1.0) * approach
    normal_force = np.maximum(elastic - damping, 0.0)
    sliding = relative - approach[:, None] * normal
    speed = np.linalg.norm(sliding, axis=1)
    friction = -(law.friction * normal_force / np.maximum(speed, law.friction_velocity)
                 )[:, None] * sliding
    return normal_force[:, None] * normal + friction


def _joint_weight(parameter, inner_start, inner_end):
    """1/2 where the contact point is a joint shared with the chain's next segment (both
    segments find it). A weight rising smoothly from 1/2 over a tenth of the segment was
    tried: a 7-filament tuft then took 1,515 steps and 4,130 Jacobians for 1.55 s instead
    of 910 and 1,209 (3.3x the wall time), so the step stays."""
    at_joint = ((parameter == 0.0) & inner_start) | ((parameter == 1.0) & inner_end)
    return np.where(at_joint, 0.5, 1.0)


def _corners(chains: Chains, pairs: np.ndarray):
    """Corner point indices (m, 4), radii (m, 2) and joint flags (m, 4) of segment pairs."""
    first, second = pairs[:, 0], pairs[:, 1]
    corners = np.column_stack([chains.starts[first], chains.ends[first],
                               chains.starts[second], chains.ends[second]])
    radii = np.column_stack([chains.radius[first], chains.radius[second]])
    inner = np.column_stack([chains.inner_start[first], chains.inner_end[first],
                             chains.inner_start[second], chains.inner_end[second]])
    return corners, radii, inner


def contact_forces(chains: Chains, points: np.ndarray, velocities: np.ndarray,
                   pairs: np.ndarray, law: BristleContactLaw) -> Contacts:
    """The touching pairs among the candidate segment ``pairs`` at the given point
    positions [mm] and velocities [mm/s], and their corner forces."""
    corners, radii, inner = _corners(chains, pairs)
    forces, overlap = pair_corner_forces(points[corners], velocities[corners], radii, inner,
                                         law)
    touching = overlap > 0.0
    return Contacts(pairs[touching], corners[touching], overlap[touching], forces[touching])


def point_forces(contacts: Contacts, count: int) -> np.ndarray:
    """Forces on the ``count`` points of the group [N], shape (count, 3)."""
    forces = np.zeros((count, 3))
    np.add.at(forces, contacts.corners.ravel(), contacts.corner_forces.reshape(-1, 3))
    return forces


def point_force_derivatives(chains: Chains, points: np.ndarray, velocities: np.ndarray,
                            contacts: Contacts, law: BristleContactLaw,
                            step: float = 1e-8, velocity_step: float = 1e-5):
    """Derivatives of the touching pairs' corner forces with respect to their corners'
    positions and velocities, by central differences of :func:`pair_corner_forces` (each
    pair moved on its own, all pairs at once) with steps ``step`` [mm] and
    ``velocity_step`` [mm/s] (the damping is small beside the elastic force: a velocity
    step as small as the position step lost the damping's slope in rounding).

    Returns
    -------
    rows, columns : ndarray of int
        Point-coordinate indices (3 · point + axis) of the force and of the coordinate;
        repeated entries add up.
    by_position, by_velocity : ndarray
        ∂f/∂x [N/mm] and ∂f/∂v [N·s/mm] at (rows, columns).
    """
    corners, radii, inner = _corners(chains, contacts.pairs)
    x, v = points[corners], velocities[corners]
    count = len(corners)
    # every pair moved along each of its 24 coordinates (12 positions, 12 velocities), both
    # ways, in one call: 48 copies of each pair
    moves = np.zeros((48, 2, 4, 3))
    for k in range(24):
        kind, corner, axis = divmod(k, 12)[0], (k % 12) // 3, k % 3
        size = (step, velocity_step)[kind]
        moves[2 * k, kind, corner, axis] = size
        moves[2 * k + 1, kind, corner, axis] = -size
    moved_x = (x[None] + moves[:, 0, None]).reshape(-1, 4, 3)
    moved_v = (v[None] + moves[:, 1, None]).reshape(-1, 4, 3)
    forces, _ = pair_corner_forces(moved_x, moved_v, np.tile(radii, (48, 1)),
                                   np.tile(inner, (48, 1)), law)
    forces = forces.reshape(24, 2, count, 4, 3)
    sizes = np.repeat([step, velocity_step], 12)[:, None, None, None]
    slopes = (forces[:, 0] - forces[:, 1]) / (2.0 * sizes)  # (24, m, 4, 3)
    # (m, 4, 3, 4, 3): force corner/axis by moved corner/axis
    by_position = slopes[:12].reshape(4, 3, count, 4, 3).transpose(2, 3, 4, 0, 1)
    by_velocity = slopes[12:].reshape(4, 3, count, 4, 3).transpose(2, 3, 4, 0, 1)
    coordinate = 3 * corners[:, :, None] + np.arange(3)  # (m, 4, 3)
    rows = np.broadcast_to(coordinate[:, :, :, None, None], by_position.shape)
    columns = np.broadcast_to(coordinate[:, None, None, :, :], by_position.shape)
    return rows.ravel(), columns.ravel(), by_position.ravel(), by_velocity.ravel()


def contact_locations(chains: Chains, points: np.ndarray, law: BristleContactLaw) -> np.ndarray:
    """Where the bristles touch at the given point positions [mm]: the midpoint of each
    touching pair's closest points, shape (m, 3) (for drawing)."""
    contacts = contact_forces(chains, points, np.zeros_like(points),
                              candidate_pairs(chains, points), law)
    if not len(contacts.pairs):
        return np.zeros((0, 3))
    x = points[contacts.corners]
    s, t = contact_parameters(x[:, 0], x[:, 1], x[:, 2], x[:, 3])[0][0]
    return 0.5 * ((x[:, 0] + s[:, None] * (x[:, 1] - x[:, 0]))
                  + (x[:, 2] + t[:, None] * (x[:, 3] - x[:, 2])))
