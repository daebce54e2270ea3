"""When the step may grow in the middle of a stroke (solver.sliding_step_factor).

In steady sliding Newton converges in one or two iterations, so the step may grow from
``solver.step_size`` to the larger sliding step there; near reversals, in the friction
law's Stribeck band and where tips can snap off edges it stays ``step_size``
(docs/model.md, "Steps in the middle of a stroke"). While a sine pose term acts the step
is no larger than its cycle over ``solver.steps_per_cycle`` (docs/motion.md).
:func:`motion_step_cap` makes the step hook that sets Exudyn's cap
(exubrush.run.solver.step_cap) accordingly.
"""

from __future__ import annotations

import bisect
from typing import TYPE_CHECKING

import exudyn as exu
import numpy as np

from exubrush.parameters.surface_kinds import SURFACE_KIND, TOOTH_ROW
from exubrush.run.budget import term_segments
from exubrush.run.solver import step_cap
from exubrush.world.surfaces import flat_top_clearance

if TYPE_CHECKING:
    from exubrush.parameters.case import Case, Surface
    from exubrush.world.motion import HeadMotion

# the larger steps also need the slide at this multiple of the tip law's v_d or faster:
# where the tips' slip enters the Stribeck band (below v_d) Newton's trouble starts; the
# default fraction 0.3 of the paper's 7.85 mm/s is 1.57 v_d
STRIBECK_MARGIN = 1.5


def sliding_step_largest(case: Case, motion: HeadMotion, tips: list):
    """``largest(mbs, t)``: the step [s] may grow from ``solver.step_size`` to the
    sliding step (``solver.sliding_step_factor`` times it, at most ``output.interval``)
    while the head slides fast enough from now until a lower cap could take hold
    (HeadMotion.sliding_faster_throughout) and, on a tooth row, every tip of ``tips``
    (node, sphere radius [mm]) is over a flat top (:func:`tips_on_flat_tops`); None where
    the step never grows: a sliding step no larger than ``step_size``, or a surface kind
    without them (SurfaceKind.larger_steps, exubrush.parameters.surface_kinds). Groups of
    bristles that touch each other take them too (since 0.12.0): their broad phase looks
    as far ahead as each step attempt
    (exubrush.contact.exudyn_between.contact_refresh)."""
    solver = case.solver
    sliding_step = min(solver.sliding_step_factor * solver.step_size, case.output.interval)
    if not (SURFACE_KIND[case.surface.kind].larger_steps and sliding_step > solver.step_size):
        return None
    # above the friction law's Stribeck band with a margin, whatever the peak speed
    speed = max(solver.sliding_speed_fraction * motion.slide.peak_speed,
                STRIBECK_MARGIN * case.contact.dynamic_velocity)
    # how long a lower cap may take to hold: the step in progress and up to
    # solver.step_recovery_steps - 1 more stay large (step_cap); two steps of margin, for a
    # step that took more than Exudyn's 7 Newton iterations where the step would be
    # changed (it defers the change)
    ahead = (solver.step_recovery_steps + 2) * sliding_step
    clear = None
    if case.surface.kind == TOOTH_ROW:  # tips snap off its edges into the gaps
        clear = tips_on_flat_tops(case.surface, tips, ahead, motion.slide.peak_speed)
    fast = motion.sliding_faster_throughout(speed, ahead, solver.step_size)
    pose = motion.pose  # its terms move faster than a slide: never a larger step while on

    def largest(mbs, t):
        larger = (fast(t) and (pose is None or not pose.acts_between(t, t + ahead))
                  and (clear is None or clear(mbs)))
        return sliding_step if larger else solver.step_size

    return largest


def motion_step_cap(case: Case, motion: HeadMotion, tips: list):
    """The step hook (mbs, t) that sets Exudyn's largest step (exubrush.run.solver.step_cap):
    ``solver.step_size``, larger in the middle of a stroke (:func:`sliding_step_largest`),
    and no larger than a sine pose term's cycle over ``solver.steps_per_cycle`` from the
    look-ahead before it acts to its end (:func:`term_step_cap`); None
    where the step is ``solver.step_size`` throughout."""
    sliding = sliding_step_largest(case, motion, tips)
    term = term_step_cap(case, motion)
    if sliding is None and term is None:
        return None
    step = case.solver.step_size

    def largest(mbs, t):
        value = step if sliding is None else sliding(mbs, t)
        finer = None if term is None else term(t)
        return value if finer is None else min(value, finer)

    return step_cap(largest)


def term_step_cap(case: Case, motion: HeadMotion):
    """``finer(t)``: the largest step [s] the sine pose terms allow at t, None outside
    their windows (exubrush.run.budget.term_segments: from the look-ahead before each term
    to its end); None if no term asks for less than ``solver.step_size``."""
    segments = term_segments(case, motion.slide_start, motion.end_time)
    if not segments:
        return None
    starts = [start for start, _, _ in segments]

    def finer(t):  # the segment that holds t, or the two that meet at t
        last = bisect.bisect_right(starts, t)
        caps = [cap for start, end, cap in segments[max(last - 2, 0):last] if start <= t <= end]
        return min(caps) if caps else None

    return finer


def tips_on_flat_tops(surface: Surface, tips: list, ahead: float, speed: float):
    """``clear(mbs)`` for :func:`sliding_step_largest` on a tooth row: whether every tip
    (node, sphere radius [mm]) lies over the flat part of a tooth top with room along the
    row, before the rounded edges begin, for its radius and its travel over ``ahead`` [s]
    at ``speed`` (the head's peak [mm/s]) or at its own speed along the row if faster (so
    that no large step carries it onto an edge or into a gap;
    exubrush.world.surfaces.flat_top_clearance)."""
    # the along-row coordinate of exubrush.world.surfaces.to_surface_frame, in plain arithmetic:
    # this runs for every tip and step
    cosine, sine = np.cos(surface.yaw), np.sin(surface.yaw)
    position = exu.OutputVariableType.Position
    velocity = exu.OutputVariableType.Velocity

    def clear(mbs):
        for node, radius in tips:
            x, y, z = mbs.GetNodeOutput(node, position)
            room = flat_top_clearance(surface, cosine * (x - surface.x)
                                      + sine * (y - surface.y), z) - radius
            if room < ahead * speed:
                return False
            vx, vy, _ = mbs.GetNodeOutput(node, velocity)
            if room < ahead * abs(cosine * vx + sine * vy):
                return False
        return True

    return clear
