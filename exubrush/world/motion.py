"""Prescribed motion of the brush head (pure, mm-s units).

The head first approaches the surface along the surface normal, then slides along one
axis. Both parts give position, velocity and acceleration consistently, so the Exudyn
drive and the inertia correction of the handle force use the same motion.

Approach (exubrush's choice; the paper does not describe one): the head starts with its
lowest tip sphere ``clearance`` above the surface and moves down to the interaction distance
d along a quintic smooth step 10τ³ - 15τ⁴ + 6τ⁵ (zero velocity and acceleration at both
ends), then holds for ``hold`` seconds before sliding starts. The slide's profiles are in
:mod:`exubrush.world.slide`, the pose terms in :mod:`exubrush.world.pose`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol

import numpy as np

from exubrush.world.pose import HeadPose, SineTerm, TableTerm, read_pose_csv
from exubrush.world.slide import (
    RestingSlide,
    SineSlide,
    TabulatedSlide,
    read_slide_csv,
    smooth_step,
)

if TYPE_CHECKING:
    from exubrush.parameters.case import Case, Motion


class Reaching(Protocol):
    """What the start height needs of a bristle (an
    :class:`exubrush.models.geometry.BristleGeometry`, which sits above this module)."""

    @property
    def lowest_reach(self) -> float:
        """Z of the tip sphere's lowest point relative to the roots' surface, upright [mm]."""
        ...


@dataclass(frozen=True)
class HeadMotion:
    """Approach, hold, then slide of the head, and the pose terms added to them.

    Attributes
    ----------
    approach_distance : float
        Distance the head travels towards the surface [mm].
    approach_duration : float
        Time of the approach [s].
    hold_duration : float
        Rest between approach and slide [s].
    slide : SineSlide, TabulatedSlide or RestingSlide
        The sliding profile, started at ``slide_start``.
    pose : HeadPose or None
        Sine and tabulated terms on the head's six pose coordinates, about a pivot given in
        the head frame (its origin: the roots' surface at the head's centre at t = 0),
        their times absolute; None where there are none (the paper's rig). Added by
        :func:`with_pose`.
    """

    approach_distance: float
    approach_duration: float
    hold_duration: float
    slide: SineSlide | TabulatedSlide | RestingSlide
    pose: HeadPose | None = None

    @property
    def slide_start(self) -> float:
        """Time at which sliding starts [s]."""
        return self.approach_duration + self.hold_duration

    @property
    def end_time(self) -> float:
        """Total simulated time [s]."""
        return self.slide_start + self.slide.duration

    def descent(self, t: float) -> tuple[float, float, float]:
        """Distance moved towards the surface [mm], its rate [mm/s] and acceleration [mm/s²]."""
        s, ds, dds = smooth_step(t / self.approach_duration)
        D, T = self.approach_distance, self.approach_duration
        return D * s, D * ds / T, D * dds / T**2

    def sliding_faster_throughout(self, speed: float, window: float, resolution: float):
        """A predicate ``fast(t)``: whether the head slides at ``speed`` [mm/s] or faster
        all through [t, t + ``window``] [s] (never at or before the slide's start), its
        speed sampled every ``resolution`` [s] from the slide's start, the samples that
        bracket the interval included (a slower stretch shorter than ``resolution``
        between two samples can be missed). Looking at both ends only would miss a
        reversal between them. Sampled to the slide's end and a sample past it, whatever
        ``window`` (the run ends there): a window reaching beyond is judged by the samples
        in it up to there."""
        start, duration = self.slide_start, self.slide.duration
        count = math.ceil(duration / resolution) + 2
        taus = np.arange(count) * resolution
        slow = np.abs(self.slide.velocities(taus)) < speed
        slow_before = np.concatenate([[0], np.cumsum(slow)])  # slow samples before index

        def fast(t: float) -> bool:
            if t <= start:
                return False
            last = min(math.ceil((t + window - start) / resolution), count - 1)
            first = min(int((t - start) / resolution), last)
            return bool(slow_before[last + 1] == slow_before[first])

        return fast

    def sliding(self, t: float) -> tuple[float, float, float]:
        """Slider position [mm], velocity [mm/s] and acceleration [mm/s²] at time t [s]."""
        if t <= self.slide_start:
            return 0.0, 0.0, 0.0
        return self.slide.evaluate(t - self.slide_start)


def start_height(case: Case, bristles: Sequence[Reaching]) -> float:
    """Height of the roots' surface above the plane at t = 0 [mm].

    The approach starts with the lowest tip ``motion.approach_clearance`` above the plane.
    A head with pose terms (``case.motion.posed``) whose bristles cannot touch from the
    interaction distance d moves in the air: it starts at d and the approach stands still.

    Raises ValueError if the interaction distance is not below that start height, i.e. no
    bristle would ever touch the surface, and no pose term moves the head.
    """
    m = case.motion
    height = m.approach_clearance - min(b.lowest_reach for b in bristles)
    if height > m.interaction_distance:
        return height
    if m.posed:
        return m.interaction_distance
    raise ValueError(
        f"motion.interaction_distance ({m.interaction_distance:g} mm) is not below the "
        f"start height of the roots ({height:g} mm): no bristle would touch; "
        "reduce it below the bristle length plus tip radius, or add pose terms "
        "(motion.sine, motion.pose_csv) for a head that moves in the air"
    )


def head_motion(case: Case, bristles: Sequence[Reaching]) -> tuple[HeadMotion, float]:
    """The head's motion and the start height of the roots' surface above the plane [mm]."""
    m = case.motion
    height = start_height(case, bristles)
    slide: SineSlide | TabulatedSlide | RestingSlide
    if m.profile == "csv":
        slide = read_slide_csv(m.csv_file)
    elif m.profile == "none":
        slide = RestingSlide(m.period * m.periods)
    else:
        slide = SineSlide(m.amplitude, m.period, m.periods)
    motion = HeadMotion(
        approach_distance=height - m.interaction_distance,
        approach_duration=m.approach_duration,
        hold_duration=m.hold_duration,
        slide=slide,
    )
    return motion, height


def with_pose(head: HeadMotion, motion: Motion) -> HeadMotion:
    """``head`` with the pose terms of a case's ``[motion]`` (``sine`` entries and
    ``pose_csv``) added, their times counted from the slide's start, about
    ``motion.pivot`` (head frame, mm); ``head`` itself where there are none.

    Raises ValueError naming the pose CSV if it cannot be read.
    """
    if not motion.posed:
        return head
    terms: list[SineTerm | TableTerm] = []
    for entry in motion.sine:
        start = head.slide_start + entry.start
        terms.append(SineTerm(
            axis=entry.axis, amplitude=entry.size, frequency=entry.frequency,
            phase=entry.phase, start=start,
            end=start + entry.duration if entry.duration else math.inf,
            ramp=entry.ramp_cycles / entry.frequency,
        ))
    if motion.pose_csv:
        terms.append(read_pose_csv(motion.pose_csv, head.slide_start + motion.pose_csv_start))
    return replace(head, pose=HeadPose(terms, motion.pivot))
