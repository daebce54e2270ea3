"""Compiled kernels of the contact between bristles (numba; mm-N-s).

One pair of segments at a time, in scalar code: the geometry and the law of
exubrush.contact.between (whose module docstring states them) for each pair, then loops
over pairs that gather the corner points from a group's coordinates and scatter the forces
and their derivatives back. Exudyn calls the group's force function at every Newton
iteration and its Jacobian function at every Jacobian update, a few dozen touching pairs
each time: array code paid numpy's per-call overhead dozens of times per pair (0.5 ms a
force call, 2-3 ms a Jacobian call on a 7-filament tuft), scalar compiled code pays it
once per call (docs/decisions/0011).

``error_model="numpy"``: a division by zero gives inf or nan as numpy's would (a segment of
zero length, never built), not an exception inside Exudyn's call.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

# angles between two segments [rad] below which they count as parallel, above which as
# crossing; blended in between (segment_contact)
PARALLEL = (0.02, 0.1)
_SINE2_LOW = math.sin(PARALLEL[0]) ** 2
_SINE2_HIGH = math.sin(PARALLEL[1]) ** 2
# depth over which the normal force grows from zero slope to the penalty's, as a share of
# the two radii: filaments of a tuft touch all along at rest, and a kink in the force at
# zero overlap there kept Newton from converging (docs/tufts.md)
SOFT_DEPTH = 0.01
# the side-by-side ends' shares are in proportion to their overlaps, smoothed over this
# share of the soft depth (_soft_positive): equal halves where both ends barely touch (the
# filaments of a tuft at rest), none to an end with a gap. An overlap plus a tenth of the
# soft depth put 41 % of a light tip-to-tip contact at the far end of the stretch, where
# the filaments did not touch (a contact force 5 % above beam theory's); plus 1e-4 of it
# fixed that but made the shares of barely touching filaments swing, and a 7-filament tuft
# took twice the Jacobians (docs/decisions/0011, third session)
SHARE_SCALE = 0.1
# a crossing contact near a joint of a chain belongs to whichever of the two segments that
# meet there is closer to the other bristle, shared smoothly where their distances differ
# by less than this many soft depths (_owned): counting a contact found at a joint as a half
# on each segment and a whole elsewhere made the force jump by half its size wherever a
# contact passed a joint of a bent chain, and lie 1.5 times too high beside a joint
JOINT_TIE = 0.5
# positions beyond this [mm] are a diverged Newton iterate (a head is centimetres wide)
DIVERGED = 1e6
# forward-difference steps of the contact's derivatives: position [mm] and velocity [mm/s]
# (forward, not central: half the kernel's work for a Jacobian as good for Newton, 3.5 %
# fewer Jacobians on a 7-filament tuft's window; decisions/0001)
# (the damping is small beside the elastic force: a velocity step as small as the position
# step lost the damping's slope in rounding)
POSITION_STEP = 1e-8
VELOCITY_STEP = 1e-5

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}

# The law array the kernels take (exubrush.contact.between.law_vector): the
# BristleContactLaw field of each entry, and the entry's index by name, which the kernel
# reads (``law[FRICTION]``, numba folds the module's integers into constants). A new
# parameter of the law is one name in each list.
LAW_FIELDS = ("stiffness", "damping", "friction", "friction_velocity")
STIFFNESS, DAMPING, FRICTION, FRICTION_VELOCITY = range(len(LAW_FIELDS))


@njit(inline="always")
def _clip01(value):
    # np.clip's answer for nan too (nan stays nan: max and min keep their first argument
    # unless the second compares greater or smaller); min and max rather than branches,
    # which numba's inlining copied into every caller's blocks (compile 12.0 -> 9.8 s)
    return min(max(value, 0.0), 1.0)


@njit(inline="always")
def _smoothstep(value):
    u = _clip01(value)
    return u * u * (3.0 - 2.0 * u)


@njit(inline="always")
def _closest(a, b, c, e, f, denom):
    """Closest points (s, t) of two segments from Ericson's (2005, §5.1.9) products."""
    s = _clip01((b * f - c * e) / denom if denom > 0.0 else 0.0)
    t = (b * s + f) / e
    if t < 0.0:
        t = 0.0
        s = _clip01(-c / a)
    elif t > 1.0:
        t = 1.0
        s = _clip01((b - c) / a)
    return s, t


@njit(inline="always")
def _products(p0, p1, q0, q1):
    """Ericson's (2005, §5.1.9) dot products of the segments p0-p1 and q0-q1 ((3,)
    arrays): a = d1·d1, b = d1·d2, c = d1·r, e = d2·d2, f = d2·r with d1 = p1 − p0,
    d2 = q1 − q0, r = p0 − q0; then d1, d2 and r."""
    d1x, d1y, d1z = p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]
    d2x, d2y, d2z = q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]
    rx, ry, rz = p0[0] - q0[0], p0[1] - q0[1], p0[2] - q0[2]
    a = d1x * d1x + d1y * d1y + d1z * d1z
    b = d1x * d2x + d1y * d2y + d1z * d2z
    c = d1x * rx + d1y * ry + d1z * rz
    e = d2x * d2x + d2y * d2y + d2z * d2z
    f = d2x * rx + d2y * ry + d2z * rz
    return a, b, c, e, f, d1x, d1y, d1z, d2x, d2y, d2z, rx, ry, rz


@njit(**_JIT)
def segment_contact(x):
    """Contact parameters of the segments x[0]-x[1] and x[2]-x[3] (x: (4, 3) [mm]).

    Returns (s, t) of their closest points (Ericson 2005, §5.1.9), (s, t) of both ends of
    the stretch the segments share side by side, and the crossing contact's weight (a
    smoothstep in sin² of their angle between PARALLEL[0] and [1]).
    """
    a, b, c, e, f = _products(x[0], x[1], x[2], x[3])[:5]
    denom = a * e - b * b  # |d1|² |d2|² sin² of the angle between them
    sine2 = _clip01(denom / (a * e))
    s_closest, t_closest = _closest(a, b, c, e, f, denom)
    # side by side: the ends of b's shadow on a, and the points of b across from them
    first, second = -c / a, (b - c) / a
    s_low = _clip01(min(first, second))
    s_high = _clip01(max(first, second))
    t_low = _clip01((b * s_low + f) / e)
    t_high = _clip01((b * s_high + f) / e)
    weight = _smoothstep((sine2 - _SINE2_LOW) / (_SINE2_HIGH - _SINE2_LOW))  # 1 crossing
    return s_closest, t_closest, s_low, t_low, s_high, t_high, weight


@njit(inline="always")
def _distance(p0, p1, q0, q1):
    """Distance [mm] between the segments p0-p1 and q0-q1 ((3,) arrays)."""
    a, b, c, e, f, d1x, d1y, d1z, d2x, d2y, d2z, rx, ry, rz = _products(p0, p1, q0, q1)
    s, t = _closest(a, b, c, e, f, a * e - b * b)
    dx, dy, dz = rx + s * d1x - t * d2x, ry + s * d1y - t * d2y, rz + s * d1z - t * d2z
    return math.sqrt(dx * dx + dy * dy + dz * dz)


@njit(inline="always")
def _soft_positive(depth, scale):
    """scale · ln(1 + exp(depth / scale)) [mm]: the depth where it is well above ``scale``,
    scale · ln 2 at zero, vanishing exponentially into a gap."""
    ratio = depth / scale
    if ratio > 30.0:
        return depth
    return scale * math.log1p(math.exp(ratio))


@njit(inline="always")
def _preferred(margin, tie):
    """Share of a contact that a segment keeps against a neighbour ``margin`` [mm] farther
    from the other segment than itself: 1/2 at a tie, rising smoothly to 1 at ``tie``
    farther and falling to 0 at ``tie`` closer (the neighbour's share is the rest)."""
    return _smoothstep((margin + tie) / (2.0 * tie))


@njit(inline="always")
def _owned(x, far, inner, distance, tie):
    """Share of a crossing contact at ``distance`` [mm] that the pair x (4, 3) owns: the
    product of _preferred against each segment's neighbours across its inner ends (far:
    the neighbours' other ends, a's before and after, then b's)."""
    share = 1.0
    if inner[0]:
        share *= _preferred(_distance(far[0], x[0], x[2], x[3]) - distance, tie)
    if inner[1]:
        share *= _preferred(_distance(x[1], far[1], x[2], x[3]) - distance, tie)
    if inner[2]:
        share *= _preferred(_distance(x[0], x[1], far[2], x[2]) - distance, tie)
    if inner[3]:
        share *= _preferred(_distance(x[0], x[1], x[3], far[3]) - distance, tie)
    return share


@njit(inline="always")
def _between(x, s, t):
    """Vector and distance [mm] from the first segment's point s to the second's point t."""
    dx = (x[2, 0] + t * (x[3, 0] - x[2, 0])) - (x[0, 0] + s * (x[1, 0] - x[0, 0]))
    dy = (x[2, 1] + t * (x[3, 1] - x[2, 1])) - (x[0, 1] + s * (x[1, 1] - x[0, 1]))
    dz = (x[2, 2] + t * (x[3, 2] - x[2, 2])) - (x[0, 2] + s * (x[1, 2] - x[0, 2]))
    return dx, dy, dz, math.sqrt(dx * dx + dy * dy + dz * dz)


@njit(inline="always")
def _relative_velocity(v, s, t, axis):
    """Velocity of the second segment's point t relative to the first's point s [mm/s]."""
    return ((1.0 - t) * v[2, axis] + t * v[3, axis]
            - (1.0 - s) * v[0, axis] - s * v[1, axis])


@njit(inline="always")
def _side_velocity(v, s1, t1, s2, t2, share1, share2, axis):
    """A side-by-side contact's relative velocity [mm/s]: its two ends', by their shares."""
    return (share1 * _relative_velocity(v, s1, t1, axis)
            + share2 * _relative_velocity(v, s2, t2, axis))


@njit(inline="always")
def _law(law, soft, overlap, nx, ny, nz, rx, ry, rz):
    """The force [N] on the second segment of a contact of ``overlap`` [mm] > 0 along the
    unit normal n, the second's velocity relative to the first being r [mm/s]: a penalty
    with zero slope at first touch, damping that never pulls, regularised friction."""
    stiffness, damping = law[STIFFNESS], law[DAMPING]
    friction, friction_velocity = law[FRICTION], law[FRICTION_VELOCITY]
    approach = nx * rx + ny * ry + nz * rz
    if overlap < soft:
        elastic = stiffness * 0.5 * overlap * overlap / soft
    else:
        elastic = stiffness * (overlap - 0.5 * soft)
    normal_force = max(elastic - damping * min(overlap / soft, 1.0) * approach, 0.0)
    sx, sy, sz = rx - approach * nx, ry - approach * ny, rz - approach * nz
    speed = math.sqrt(sx * sx + sy * sy + sz * sz)
    # smooth regularisation: with max(speed, v_r) instead, the kink at v_r cost a 7-filament
    # tuft 14 % more steps and 19 % more Jacobians (approach and 0.1 period)
    slip = friction * normal_force / math.sqrt(speed * speed
                                               + friction_velocity * friction_velocity)
    return (normal_force * nx - slip * sx, normal_force * ny - slip * sy,
            normal_force * nz - slip * sz)


@njit(inline="always")
def _hand_to_corners(out, s, t, weight, fx, fy, fz):
    """Add the force f [N] on the second segment's point t (and −f on the first's point s),
    times ``weight``, to the four corners in proportion to where the points lie."""
    shares = (-(1.0 - s) * weight, -s * weight, (1.0 - t) * weight, t * weight)
    for corner in range(4):
        out[corner, 0] += shares[corner] * fx
        out[corner, 1] += shares[corner] * fy
        out[corner, 2] += shares[corner] * fz


@njit(**_JIT)
def pair_force(x, v, radius_a, radius_b, inner, far, law, out):
    """Forces [N] on the four corners of one segment pair into ``out`` (4, 3); returns the
    overlap [mm] (negative: a gap). exubrush.contact.between.pair_corner_forces says
    where the force acts; ``inner`` (4,) whether each corner is a joint with the chain's
    next segment, ``far`` (4, 3) those neighbours' other ends (a's before and after, then
    b's); ``law`` the law array (LAW_FIELDS)."""
    s0, t0, s1, t1, s2, t2, crossing = segment_contact(x)
    reach = radius_a + radius_b
    soft = SOFT_DEPTH * reach
    for corner in range(4):
        for axis in range(3):
            out[corner, axis] = 0.0
    nx, ny, nz, distance = _between(x, s0, t0)
    overlap = reach - distance
    if not (overlap > 0.0 and distance > 0.0):
        return overlap
    nx, ny, nz = nx / distance, ny / distance, nz / distance
    # side by side: along the common normal, acting at both ends of the common stretch in
    # proportion to the stretch and to the ends' own overlaps
    side = (1.0 - crossing) * 0.5 * (abs(s2 - s1) + abs(t2 - t1))
    if side > 0.0:
        scale = SHARE_SCALE * soft
        depth_low = _soft_positive(reach - _between(x, s1, t1)[3], scale)
        depth_high = _soft_positive(reach - _between(x, s2, t2)[3], scale)
        low_share = depth_low / (depth_low + depth_high)
        share1, share2 = side * low_share, side * (1.0 - low_share)
        fx, fy, fz = _law(law, soft, overlap, nx, ny, nz,
                          _side_velocity(v, s1, t1, s2, t2, share1, share2, 0),
                          _side_velocity(v, s1, t1, s2, t2, share1, share2, 1),
                          _side_velocity(v, s1, t1, s2, t2, share1, share2, 2))
        _hand_to_corners(out, s1, t1, share1, fx, fy, fz)
        _hand_to_corners(out, s2, t2, share2, fx, fy, fz)
    # crossing: at the closest points, shared with a neighbour across a joint
    if crossing > 0.0:
        weight = crossing * _owned(x, far, inner, distance, JOINT_TIE * soft)
        fx, fy, fz = _law(law, soft, overlap, nx, ny, nz, _relative_velocity(v, s0, t0, 0),
                          _relative_velocity(v, s0, t0, 1), _relative_velocity(v, s0, t0, 2))
        _hand_to_corners(out, s0, t0, weight, fx, fy, fz)
    return overlap


@njit(**_JIT)
def pairs_forces(x, v, radii, inner, far, law):
    """pair_force for every pair: x, v (m, 4, 3), radii (m, 2), inner (m, 4), far (m, 4,
    3); returns the forces (m, 4, 3) [N] and overlaps (m,) [mm]."""
    count = x.shape[0]
    forces = np.zeros((count, 4, 3))
    overlap = np.empty(count)
    for k in range(count):
        overlap[k] = pair_force(x[k], v[k], radii[k, 0], radii[k, 1], inner[k], far[k], law,
                                forces[k])
    return forces, overlap


@njit(**_JIT)
def pairs_derivatives(x, v, radii, inner, far, law, step, velocity_step):
    """Forward differences of pair_force with respect to each pair's 12 corner positions
    (step [mm]) and 12 velocities (velocity_step [mm/s]); returns ∂f/∂x [N/mm] and ∂f/∂v
    [N·s/mm], each (m, 4, 3, 4, 3): force corner and axis by moved corner and axis. The
    neighbours' far ends stay put: a joint's share (_owned) follows the pair's own corners,
    not the far end of the neighbour it is compared with."""
    count = x.shape[0]
    by_position = np.empty((count, 4, 3, 4, 3))
    by_velocity = np.empty((count, 4, 3, 4, 3))
    plus, minus = np.empty((4, 3)), np.empty((4, 3))
    for k in range(count):
        xk, vk = x[k].copy(), v[k].copy()
        pair_force(xk, vk, radii[k, 0], radii[k, 1], inner[k], far[k], law, minus)
        for kind in range(2):
            moved = xk if kind == 0 else vk
            size = step if kind == 0 else velocity_step
            target = by_position if kind == 0 else by_velocity
            for corner in range(4):
                for axis in range(3):
                    held = moved[corner, axis]
                    moved[corner, axis] = held + size
                    pair_force(xk, vk, radii[k, 0], radii[k, 1], inner[k], far[k], law, plus)
                    moved[corner, axis] = held
                    for row in range(4):
                        for column in range(3):
                            target[k, row, column, corner, axis] = (
                                (plus[row, column] - minus[row, column]) / size)
    return by_position, by_velocity


@njit(**_JIT)
def segments_contact(a0, a1, b0, b1):
    """segment_contact for segments given as (n, 3) end arrays; returns (n, 7)."""
    count = a0.shape[0]
    result = np.empty((count, 7))
    x = np.empty((4, 3))
    for k in range(count):
        for axis in range(3):  # scalar copies: a row assignment compiles numba's broadcasting
            x[0, axis] = a0[k, axis]
            x[1, axis] = a1[k, axis]
            x[2, axis] = b0[k, axis]
            x[3, axis] = b1[k, axis]
        parameters = segment_contact(x)
        for column in range(7):
            result[k, column] = parameters[column]
    return result


@njit(**_JIT)
def _gather(q, base, coordinates, corners, k, x):
    for corner in range(4):
        point = corners[k, corner]
        for axis in range(3):
            x[corner, axis] = base[point, axis] + q[coordinates[point, axis]]


@njit(**_JIT)
def _sane(q, q_t, base, coordinates):
    """Whether the state is one to evaluate (not a diverged Newton iterate)."""
    for point in range(coordinates.shape[0]):
        for axis in range(3):
            index = coordinates[point, axis]
            if not (abs(base[point, axis] + q[index]) < DIVERGED and math.isfinite(q_t[index])):
                return False
    return True


@njit(**_JIT)
def group_forces(q, q_t, base, coordinates, corners, radii, inner, far, law, out):
    """Add the contact forces of the candidate pairs to ``out`` (the group object's
    generalised forces [N]); q, q_t its coordinates [mm] and velocities [mm/s], base the
    points at q = 0, coordinates (points, 3) each point's entries in q, corners (m, 4) the
    candidate pairs' corner points, far (m, 4) their neighbours' far ends (pair_force).
    Returns the number of touching pairs (-1: a diverged state, no forces)."""
    if not _sane(q, q_t, base, coordinates):
        return -1
    x, v, forces = np.empty((4, 3)), np.empty((4, 3)), np.empty((4, 3))
    beyond = np.empty((4, 3))
    zero = np.zeros(base.shape)
    touching = 0
    for k in range(corners.shape[0]):
        _gather(q, base, coordinates, corners, k, x)
        _gather(q_t, zero, coordinates, corners, k, v)
        _gather(q, base, coordinates, far, k, beyond)
        if pair_force(x, v, radii[k, 0], radii[k, 1], inner[k], beyond, law, forces) > 0.0:
            touching += 1
            for corner in range(4):
                for axis in range(3):
                    out[coordinates[corners[k, corner], axis]] += forces[corner, axis]
    return touching


@njit(**_JIT)
def group_jacobian(q, q_t, base, coordinates, corners, radii, inner, far, law, f_position,
                   f_velocity, step, velocity_step):
    """Sparse triplets (row, column, value) of −(∂f/∂q · f_position + ∂f/∂q_t ·
    f_velocity) of the touching candidate pairs (group_forces' arguments), in the group
    object's coordinates: 144 entries a touching pair, repeated entries add up."""
    if not _sane(q, q_t, base, coordinates):
        return np.zeros((0, 3))
    count = corners.shape[0]
    x, v, beyond = np.empty((count, 4, 3)), np.empty((count, 4, 3)), np.empty((count, 4, 3))
    forces = np.empty((4, 3))
    zero = np.zeros(base.shape)
    touching = np.zeros(count, np.bool_)
    for k in range(count):
        _gather(q, base, coordinates, corners, k, x[k])
        _gather(q_t, zero, coordinates, corners, k, v[k])
        _gather(q, base, coordinates, far, k, beyond[k])
        touching[k] = pair_force(x[k], v[k], radii[k, 0], radii[k, 1], inner[k], beyond[k],
                                 law, forces) > 0.0
    chosen = np.nonzero(touching)[0]
    by_position, by_velocity = pairs_derivatives(x[chosen], v[chosen], radii[chosen],
                                                 inner[chosen], beyond[chosen], law, step,
                                                 velocity_step)
    triplets = np.empty((144 * len(chosen), 3))
    entry = 0
    for n in range(len(chosen)):
        k = chosen[n]
        for row_corner in range(4):
            for row_axis in range(3):
                row = coordinates[corners[k, row_corner], row_axis]
                for column_corner in range(4):
                    for column_axis in range(3):
                        triplets[entry, 0] = row
                        triplets[entry, 1] = coordinates[corners[k, column_corner],
                                                         column_axis]
                        triplets[entry, 2] = -(
                            by_position[n, row_corner, row_axis, column_corner, column_axis]
                            * f_position
                            + by_velocity[n, row_corner, row_axis, column_corner, column_axis]
                            * f_velocity)
                        entry += 1
    return triplets
