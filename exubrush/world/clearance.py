"""Where a posed head goes over a run, checked before anything is solved (pure, mm-s-rad).

The head's motion is prescribed, so whether its roots pass through the surface, or its
Tait-Bryan angles reach their singularity, is known before the run. Both are checked by
sampling the motion, refined where a sample comes close, so that a violation is never
missed by more than a stated margin:

A function f(t) that changes at most ``rate`` per second has, between two samples a and
b = a + h, no value below (f(a) + f(b)) / 2 - rate h / 2. :func:`lowest_below` starts
with :data:`COARSE_SAMPLES` samples over the window and halves every interval whose lower
bound is more than ``margin`` below min(0, the lowest sample), until none is: f then never
falls below -``margin`` unless a sample is below 0, and where one is, f's true minimum is
within ``margin`` of the lowest sample, which is what is reported.

For the roots, f is the lowest root's height above the plane, z. A root's height changes
at most at the rate of the descent's, the pose's z translation's and of the turn's:
|d(A r)_z/dt| <= |ω| |r| with |ω| = |G θ̇| <= |θ̇x| + |θ̇y| + |θ̇z| (G's columns are unit
vectors), r the root's arm from the pivot; a head turned about z alone (no rx, ry term)
keeps every root's height. :func:`vertical_rate` is that bound.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from exubrush.parameters.surface_kinds import PLANE, TOOTH_ROW
from exubrush.world.kinematics import DOWN, SLIDE_AXES
from exubrush.world.motion import HeadMotion

if TYPE_CHECKING:
    from exubrush.parameters.case import Case

COARSE_SAMPLES = 65  # first samples over a window, before refinement
MOST_SAMPLES = 200_000  # a check needing more samples is refused (a head that grazes)
ROOT_MARGIN = 0.01  # [mm]: a root deeper than this below the plane is never missed
# [mm]: the roots' closest approach is taken this much below the lowest sample (a bristle
# within it of reaching gets a contact element it may not need; a finer margin would
# sample a head held at its lowest for long finely all along)
REACH_MARGIN = 0.1
# |ry| of the Tait-Bryan angles kept this far from 90° [rad]: the moment is recovered from
# the drive through G⁻ᵀ, whose norm grows as 1 / cos ry (1/cos 80° = 5.8: the drive's
# moment error amplified at most about six times; 89.9°: 573 times, and at 90° G is
# singular: a moment of -1.8e8 N·mm in forces.csv beside samples of 1e-7)
RY_LIMIT = math.radians(80.0)
RY_MARGIN = math.radians(0.1)  # [rad]: an excursion this far beyond RY_LIMIT is never missed


class Unchecked(ValueError):
    """A check that would need more than :data:`MOST_SAMPLES` samples; ``lower`` is what
    the samples taken so far guarantee: f stays at or above it."""

    def __init__(self, message: str, lower: float):
        super().__init__(message)
        self.lower = lower


def least(f: Callable[[float], float], t0: float, t1: float, rate: float, margin: float,
          floor: float = math.inf) -> tuple[float, float]:
    """The time [s] and value of f's lowest sample on [t0, t1], refined (see module
    docstring) until f's true least is within ``margin`` below it, or known to stay above
    ``floor`` - ``margin``. f changes at most ``rate`` per second. Raises
    :class:`Unchecked` if that would take more than :data:`MOST_SAMPLES` evaluations (f
    stays within ``margin`` of its least over a long stretch)."""
    times = list(np.linspace(t0, t1, COARSE_SAMPLES)) if t1 > t0 else [t0]
    values = [f(t) for t in times]
    while True:
        threshold = min(floor, min(values)) - margin
        refined_times, refined_values = [times[0]], [values[0]]
        for a, b, fa, fb in zip(times[:-1], times[1:], values[:-1], values[1:], strict=True):
            if 0.5 * (fa + fb) - 0.5 * rate * (b - a) < threshold:
                middle = 0.5 * (a + b)
                refined_times.append(middle)
                refined_values.append(f(middle))
            refined_times.append(b)
            refined_values.append(fb)
        if len(refined_times) == len(times):
            worst = int(np.argmin(values))
            return times[worst], values[worst]
        times, values = refined_times, refined_values
        if len(times) > MOST_SAMPLES:
            t, v = np.array(times), np.array(values)
            lower = float(np.min(0.5 * (v[:-1] + v[1:]) - 0.5 * rate * np.diff(t)))
            raise Unchecked(f"more than {MOST_SAMPLES:,} samples", min(lower, v.min()))


def lowest_below(f: Callable[[float], float], t0: float, t1: float, rate: float,
                 margin: float) -> tuple[float, float] | None:
    """The time [s] and value of f's lowest sample on [t0, t1] if it is below 0, else None:
    every excursion of f below -``margin`` is found, and its lowest value is within
    ``margin`` of the one returned (:func:`least` with a floor of 0)."""
    when, value = least(f, t0, t1, rate, margin, floor=0.0)
    return (when, value) if value < 0.0 else None


def pose_window(motion: HeadMotion) -> tuple[float, float]:
    """From the first pose term's start to the run's end [s]: before it the head only
    descends to the interaction distance and slides along the surface."""
    start = min(term.start for term in motion.pose.terms)
    return min(max(start, 0.0), motion.end_time), motion.end_time


def vertical_rate(motion: HeadMotion, points: np.ndarray, t0: float) -> float:
    """Bound of how fast any of ``points`` (head frame at t = 0, the roots' surface at
    z = 0) changes height from t0 [s] on [mm/s] (see module docstring)."""
    rates = motion.pose.peak_rate
    descent = (15.0 / 8.0 * abs(motion.approach_distance) / motion.approach_duration
               if t0 < motion.approach_duration else 0.0)
    turn = 0.0
    if np.any(rates[3:5] > 0.0):
        arm = float(np.max(np.linalg.norm(points - motion.pose.pivot, axis=1)))
        turn = float(np.sum(rates[3:])) * arm
    return descent + float(rates[2]) + turn


def positions(motion: HeadMotion, direction: str, start_height: float, points: np.ndarray,
              t: float) -> np.ndarray:
    """Positions (n, 3) [mm] at t [s] of ``points`` fixed to the head (head frame at t = 0,
    the roots' surface at z = 0), in the head frame fixed to the surface: the start
    height, the slide, the descent and the pose (exubrush.world.kinematics)."""
    moved = points if motion.pose is None else motion.pose.point_position(points, t)
    slide = motion.sliding(t)[0] * SLIDE_AXES[direction]
    return moved + slide + motion.descent(t)[0] * DOWN + np.array([0.0, 0.0, start_height])


def outermost(points: np.ndarray) -> np.ndarray:
    """The vertices of the convex hull of ``points`` (n, 3) [mm] (all of them where they
    span no hull): under any rigid motion the lowest of the points is one of these, so the
    plane's checks need only them (the sonic head's 1,480 roots: 8)."""
    if len(points) <= 8:
        return points
    from scipy.spatial import ConvexHull, QhullError  # 0.1 s of import: posed heads only

    flat = np.ptp(points[:, 2]) == 0.0  # roots on one level: their hull in the plane
    try:
        return points[ConvexHull(points[:, :2] if flat else points).vertices]
    except QhullError:  # on a line (or fewer than 4 points off one level)
        return points


def _root_clearance(motion: HeadMotion, direction: str, start_height: float,
                    roots: np.ndarray, height: Callable[[np.ndarray], np.ndarray] | None):
    """f(t): the lowest root's height above the surface's top [mm] at t [s]."""
    def clearance(t: float) -> float:
        where = positions(motion, direction, start_height, roots, t)
        top = 0.0 if height is None else height(where)
        return float(np.min(where[:, 2] - top))
    return clearance


def lowest_root(motion: HeadMotion, direction: str, start_height: float, roots: np.ndarray,
                height: Callable[[np.ndarray], np.ndarray] | None = None
                ) -> tuple[float, float] | None:
    """The time [s] and depth [mm] at which the deepest sampled root is below the
    surface, or None if none ever is: a root deeper than :data:`ROOT_MARGIN` under the
    plane is never missed, and the depth is within ROOT_MARGIN of the deepest.

    ``height`` gives the surface's top under head-frame points (n, 3) [mm]; None: the
    plane z = 0. A head without pose terms is not sampled: it only descends to the
    interaction distance and slides along the surface.
    """
    if motion.pose is None:
        return None
    t0, t1 = pose_window(motion)
    found = lowest_below(_root_clearance(motion, direction, start_height, roots, height),
                         t0, t1, vertical_rate(motion, roots, t0), ROOT_MARGIN)
    return None if found is None else (found[0], -found[1])


def closest_approach(motion: HeadMotion, direction: str, start_height: float,
                     roots: np.ndarray, interaction_distance: float) -> float:
    """How close to the plane the roots come [mm]: the interaction distance, or where pose
    terms bring a root lower, REACH_MARGIN less than the lowest sample where they move up
    and down (which is within
    REACH_MARGIN of the true least: this is at or below it). What a bristle must reach
    past to touch the plane, and how far it can be compressed."""
    if motion.pose is None:
        return interaction_distance
    t0, t1 = pose_window(motion)
    rate = vertical_rate(motion, roots, t0)
    try:
        _, lowest = least(_root_clearance(motion, direction, start_height, roots, None), t0,
                          t1, rate, REACH_MARGIN)
    except Unchecked as err:  # a long stretch at its least: what the samples guarantee
        return min(interaction_distance, err.lower)
    # roots that never change height (slides, shifts, turns about z) are where sampled
    return min(interaction_distance, lowest - (REACH_MARGIN if rate > 0.0 else 0.0))


def largest_tilt(motion: HeadMotion) -> tuple[float, float] | None:
    """The time [s] and |ry| [rad] of the sample where |ry| is largest beyond
    :data:`RY_LIMIT`, or None if it stays within it (an excursion beyond RY_LIMIT +
    :data:`RY_MARGIN` is never missed; the largest is within RY_MARGIN of the one
    returned)."""
    if motion.pose is None or motion.pose.peak_rate[4] == 0.0:
        return None
    t0, t1 = pose_window(motion)
    found = lowest_below(lambda t: RY_LIMIT - abs(motion.pose.evaluate(t)[0][4]), t0, t1,
                        float(motion.pose.peak_rate[4]), RY_MARGIN)
    return None if found is None else (found[0], RY_LIMIT - found[1])


def largest_acceleration(motion: HeadMotion, points: np.ndarray) -> float:
    """Upper bound of the acceleration [mm/s²] of the head's ``points`` (head frame at
    t = 0) and its origin over the run: the descent's largest (10/√3 D / T², the quintic
    step's largest curvature), the slide's, and the pose's. A point at arm r from the pivot
    accelerates by ü + α × r + ω × (ω × r), so at most |ü| + (|α| + |ω|²) |r|, with
    |ω| <= Σ|θ̇| (G's columns are unit vectors) and |α| = |G θ̈ + Ġ θ̇| <= Σ|θ̈| + (Σ|θ̇|)²
    (the twice-turned columns turn at most at Σ|θ̇|); each from the terms' peaks
    (``HeadPose.peak_rate``, ``peak_acceleration``)."""
    descent = 10.0 / math.sqrt(3.0) * abs(motion.approach_distance) / motion.approach_duration**2
    rigid = descent + motion.slide.peak_acceleration
    if motion.pose is None:
        return rigid
    pose = motion.pose
    rates, accelerations = pose.peak_rate, pose.peak_acceleration
    turn_rate = float(np.sum(rates[3:]))
    arm = float(np.max(np.linalg.norm(np.vstack([np.zeros((1, 3)), points]) - pose.pivot,
                                      axis=1)))
    return (rigid + float(np.linalg.norm(accelerations[:3]))
            + (float(np.sum(accelerations[3:])) + 2.0 * turn_rate**2) * arm)


def root_distances(case: Case, roots: np.ndarray, motion: HeadMotion,
                   closest: float | None = None) -> np.ndarray:
    """Per root (n, 3) [mm, head frame], how close it comes to the level of the surface's
    top [mm]: the interaction distance plus its own height over the roots' surface (not 0
    for a misaligned head), and where pose terms move the head, at most the roots'
    ``closest`` approach (:func:`closest_approach`, over every root: a turn
    may bring any of them that low)."""
    own = case.motion.interaction_distance + roots[:, 2]
    return own if closest is None or motion.pose is None else np.minimum(own, closest)


# the surfaces whose top is level (z = 0) wherever the slide carries a root: a root at or
# below that level is inside the surface (a tooth row's gaps are too narrow to hold a
# stroke's worth of roots); a cylinder, a sphere and a mesh fall away from their top, and a
# root below it may pass beside them: not checked (docs/model.md)
LEVEL_TOPS = {PLANE: "the plane", TOOTH_ROW: "the tooth tops"}


def sunken_roots(case: Case, distances: np.ndarray) -> list[str]:
    """A misaligned head whose lowest root stands on or below a level surface's top after
    the approach (``distances`` from :func:`root_distances`; :data:`LEVEL_TOPS`), as one
    line; other surfaces' roots are not checked (as a posed head's on a mesh:
    docs/motion.md)."""
    lowest = float(np.min(distances))
    if case.surface.kind not in LEVEL_TOPS or lowest > 0.0:
        return []
    return [f"head.misalign_x, head.misalign_y: the misaligned head's lowest root comes "
            f"{-lowest:.4g} mm below {LEVEL_TOPS[case.surface.kind]} at "
            f"motion.interaction_distance = "
            f"{case.motion.interaction_distance:g} mm; reduce the misalignment or raise the "
            "interaction distance"]
