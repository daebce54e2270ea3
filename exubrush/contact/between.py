"""Contact between bristles (mm-N-s).

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
velocity v_t, regularised below the speed v_r: f_t = −μ f_n v_t / √(|v_t|² + v_r²). The
force acts at the two closest points with opposite signs and is handed to each segment's
end points in proportion to the closest point's position on it ((1 − s), s), which keeps
its resultant and its moment about any point. A crossing contact near a joint of a chain
is found by both segments that meet there; it belongs to the one closer to the other
bristle, shared between them with shares that add up to one where their distances differ
by less than JOINT_TIE soft depths (at a joint's outer side, where both find the joint,
half each). Side-by-side segments count in proportion to the stretch they share.

The per-pair arithmetic is compiled (exubrush.contact.between_kernel); this module holds the
chains, the broad phase and the array interface.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exubrush.contact.between_kernel import (  # noqa: F401  (the law's constants)
    JOINT_TIE,
    LAW_FIELDS,
    PARALLEL,
    SOFT_DEPTH,
    pairs_forces,
    segments_contact,
)
from exubrush.parameters.case import BristleContactLaw
from exubrush.util.pair_search import pairs_within


def law_vector(law: BristleContactLaw) -> np.ndarray:
    """The law's numbers as the kernels take them (between_kernel.LAW_FIELDS): stiffness
    [N/mm], damping [N·s/mm], friction coefficient, friction velocity [mm/s]."""
    return np.array([getattr(law, name) for name in LAW_FIELDS], float)


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
        chain (a crossing contact is shared with it there).
    before, after : ndarray (m,) of int
        Point index of the far end of the chain's segment before (after) this one; the
        segment's own start (end) where there is none.
    """

    starts: np.ndarray
    ends: np.ndarray
    bristle: np.ndarray
    radius: np.ndarray
    inner_start: np.ndarray
    inner_end: np.ndarray
    before: np.ndarray
    after: np.ndarray

    @classmethod
    def from_polylines(cls, polylines: list[list[int]], radii: list[float]) -> Chains:
        """Chains from each bristle's point indices, root first, and its contact radius."""
        starts, ends, owner, radius, inner_start, inner_end = [], [], [], [], [], []
        before, after = [], []
        for index, (points, r) in enumerate(zip(polylines, radii, strict=True)):
            count = len(points) - 1
            for k in range(count):
                starts.append(points[k])
                ends.append(points[k + 1])
                owner.append(index)
                radius.append(r)
                inner_start.append(k > 0)
                inner_end.append(k < count - 1)
                before.append(points[k - 1] if k > 0 else points[k])
                after.append(points[k + 2] if k < count - 1 else points[k + 1])
        return cls(np.array(starts, int), np.array(ends, int), np.array(owner, int),
                   np.array(radius, float), np.array(inner_start), np.array(inner_end),
                   np.array(before, int), np.array(after, int))


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
        Parameters (s, t) of the closest points (the crossing contact) and of the two
        side-by-side ends: the points a0 + s (a1 − a0) and b0 + t (b1 − b0).
    weight : ndarray (...)
        Share of the crossing contact (1 − weight goes to the side-by-side pair).
    """
    shape = np.broadcast_shapes(*(np.shape(p) for p in (a0, a1, b0, b1)))
    ends = [np.ascontiguousarray(np.broadcast_to(p, shape), float).reshape(-1, 3)
            for p in (a0, a1, b0, b1)]
    found = segments_contact(*ends).T.reshape(7, *shape[:-1])
    return found[:6].reshape(3, 2, *shape[:-1]), found[6]


def candidate_pairs(chains: Chains, points: np.ndarray, margin: float = 0.0) -> np.ndarray:
    """Segment pairs (k, 2) of different bristles whose capsules come within ``margin``
    [mm] of each other: bounding spheres from a k-d tree first, then the segments'
    closest distance. Sorted by the first segment, then the second: the forces of the
    pairs add up in this order, so a search with another margin, or at another moment,
    that finds the same touching pairs gives the same forces to the last bit."""
    a, b = points[chains.starts], points[chains.ends]
    centre = 0.5 * (a + b)
    bound = 0.5 * np.linalg.norm(b - a, axis=1) + chains.radius
    pairs = pairs_within(centre, 2.0 * bound.max() + margin)
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
    pairs = pairs[gap <= margin]
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


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
                       law: BristleContactLaw,
                       far: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
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
    far : ndarray (m, 4, 3), optional
        The far ends of those next segments [mm] (a's before and after, then b's); needed
        where ``inner`` has a joint.

    Returns
    -------
    forces : ndarray (m, 4, 3)
        [N]; zero for pairs that do not touch.
    overlap : ndarray (m,)
        Sum of the radii less the segments' distance [mm] (negative: a gap).
    """
    x = np.ascontiguousarray(x, float)
    far = x.copy() if far is None else np.ascontiguousarray(far, float)
    return pairs_forces(x, np.ascontiguousarray(v, float), np.ascontiguousarray(radii, float),
                        np.ascontiguousarray(inner, bool), far, law_vector(law))


def pair_corners(chains: Chains, pairs: np.ndarray):
    """Corner point indices (m, 4), radii (m, 2), joint flags (m, 4) and the joints'
    neighbours' far ends (m, 4) of segment pairs."""
    first, second = pairs[:, 0], pairs[:, 1]
    corners = np.column_stack([chains.starts[first], chains.ends[first],
                               chains.starts[second], chains.ends[second]])
    radii = np.column_stack([chains.radius[first], chains.radius[second]])
    inner = np.column_stack([chains.inner_start[first], chains.inner_end[first],
                             chains.inner_start[second], chains.inner_end[second]])
    far = np.column_stack([chains.before[first], chains.after[first], chains.before[second],
                           chains.after[second]])
    return corners, radii, inner, far


def contact_forces(chains: Chains, points: np.ndarray, velocities: np.ndarray,
                   pairs: np.ndarray, law: BristleContactLaw) -> Contacts:
    """The touching pairs among the candidate segment ``pairs`` at the given point
    positions [mm] and velocities [mm/s], and their corner forces."""
    corners, radii, inner, far = pair_corners(chains, pairs)
    forces, overlap = pair_corner_forces(points[corners], velocities[corners], radii, inner,
                                         law, points[far])
    touching = overlap > 0.0
    return Contacts(pairs[touching], corners[touching], overlap[touching], forces[touching])


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
