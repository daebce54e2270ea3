"""What a run will cost, and whether its settings resolve its motion (pure).

Checked by :func:`exubrush.run.prepared.prepare` before any Exudyn system is built, so that a
run which would take days, exhaust memory or step over its own motion is refused at once
with one line: the estimate, the limit and the setting that changes it.

Estimates (per run, internal units):

- steps: end time / solver.step_size per solved system. The solver cuts steps where it
  must, so this is a lower bound of the real count (the default orthogonal run takes about
  four times as many for the whole head);
- memory: the recorded node positions and tip contact forces at the output interval, kept
  for every bristle (3 doubles per node and per force, per row), times 3 for the copies
  made while the groups' results are joined, plus the coordinates kept for the viewer;
- pose-term evaluations: the steps times the pose terms (motion.sine entries and a pose
  table), each evaluated in Python at every step whether it acts or not (about 3 us a term
  and a step): 2,000 small, slow sine terms made a run of one bristle and 880 steps take
  5.3 s of solving instead of 0.0 s, and 100,000 of them would take minutes where the
  steps alone looked cheap. The estimate and these checks take O(terms log terms), never
  terms x steps.

Resolution: the largest step must resolve the motion, or the solver steps over it (a
20 s step on a 12 s slide period ran to the end with a peak force 9.4x the right one):
at least 100 steps per slide period (or over a slide CSV's duration), 20 per approach, 4
per hold and 100 over a pose CSV's duration; while a sine pose term acts the step is capped
at its cycle over solver.steps_per_cycle (exubrush.run.step_policy), which the steps'
estimate counts,
and a term that would need a step below solver.minimum_step_size is refused. A slide
CSV's sample spacing is no bound: a finely sampled smooth profile needs no step that small,
and where a profile moves faster than the step resolves (a jump, a sharp corner), a warning
says so (:func:`motion_warnings`). The output interval must fit into the run at least
twice, or the run records nothing but its start.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

STEPS_PER_PERIOD = 100
STEPS_PER_APPROACH = 20
STEPS_PER_HOLD = 4
COPIES = 3  # tip and node histories held at once while joining the groups' results
DOUBLE = 8  # bytes
C_INT = 2**31 - 1  # Exudyn's step counter is a C int


@dataclass(frozen=True)
class WorkEstimate:
    """The size of a run before it starts.

    Attributes
    ----------
    steps : int
        Time steps per solved system at the largest step (a lower bound).
    memory : float
        Memory of the recorded results [B] (estimate).
    term_evaluations : int
        Evaluations of the pose terms per solved system: every term is evaluated at every
        step, so the terms (motion.sine entries and a pose table) times ``steps``.
    """

    steps: int
    memory: float
    term_evaluations: int = 0


def term_step(case, frequency: float) -> float:
    """The largest step [s] while a sine pose term of ``frequency`` [Hz] acts: its cycle
    over ``solver.steps_per_cycle``."""
    return 1.0 / (frequency * case.solver.steps_per_cycle)


def term_windows(case, slide_start: float, end_time: float) -> list[tuple[float, float, float]]:
    """(from [s], to [s], largest step [s]) of each sine pose term (motion.sine) whose step
    is below ``solver.step_size``: from (solver.step_recovery_steps + 2) steps before it
    starts (a smaller cap takes hold only at Exudyn's next try to grow the step,
    exubrush.run.solver.step_cap) to its end or the run's (exubrush.run.step_policy)."""
    step = case.solver.step_size
    ahead = (case.solver.step_recovery_steps + 2) * step
    windows = []
    for term in case.motion.sine:
        fine = term_step(case, term.frequency)
        if fine < step:
            start = slide_start + term.start
            end = min(start + term.duration if term.duration else end_time, end_time)
            windows.append((start - ahead, end, fine))
    return windows


def term_segments(case, slide_start: float, end_time: float) -> list[tuple[float, float, float]]:
    """:func:`term_windows` merged: (from [s], to [s], largest step [s]) in time order, not
    overlapping, each step the smallest of the windows that cover the segment. Sorted once
    (O(n log n) for n terms), so that neither the estimate nor the step cap
    (exubrush.run.step_policy) goes through every term at every step."""
    windows = sorted(term_windows(case, slide_start, end_time))
    edges = sorted({time for start, end, _ in windows for time in (start, end)})
    segments: list[tuple[float, float, float]] = []
    active: list[tuple[float, float]] = []  # (step, to) of the windows begun, a heap
    begun = 0
    for start, end in zip(edges, edges[1:], strict=False):
        while begun < len(windows) and windows[begun][0] <= start:
            heapq.heappush(active, (windows[begun][2], windows[begun][1]))
            begun += 1
        while active and active[0][1] <= start:  # ended: only the finest one matters
            heapq.heappop(active)
        if not active:
            continue
        fine = active[0][0]
        if segments and segments[-1][1] == start and segments[-1][2] == fine:
            segments[-1] = (segments[-1][0], end, fine)
        else:
            segments.append((start, end, fine))
    return segments


def term_steps(case, end_time: float, slide_start: float) -> int:
    """Steps the sine pose terms add to ``end_time / solver.step_size`` [-]: over each of
    :func:`term_segments` within the run, its step instead of ``step_size``."""
    step = case.solver.step_size
    extra = 0
    for start, end, fine in term_segments(case, slide_start, end_time):
        span = max(end - max(start, 0.0), 0.0)
        extra += math.ceil(span / fine) - math.floor(span / step)
    return extra


def estimate(case, bristles: int, end_time: float, slide_start: float = 0.0) -> WorkEstimate:
    """The work of ``case`` with ``bristles`` bristles and ``end_time`` [s], the slide (and
    the pose terms' clock) starting at ``slide_start`` [s]."""
    rows = math.floor(end_time / case.output.interval) + 1
    shapes = case.output.shape_samples(rows)
    nodes = case.model.segments if case.model.kind == "dfm" else 1
    # every tip's position and force at every row; every node (and the root) at the shapes
    memory = float(rows * 2 + shapes * (nodes + 1)) * bristles * 3 * DOUBLE * COPIES
    if case.output.solution_file:
        coordinates = 6 + bristles * nodes * 7  # handle; Euler parameters: 7 per node
        memory += (math.floor(end_time / case.output.shape_interval) + 1) * coordinates * DOUBLE
    steps = math.ceil(end_time / case.solver.step_size) + term_steps(case, end_time, slide_start)
    terms = len(case.motion.sine) + bool(case.motion.pose_csv)
    return WorkEstimate(steps=steps, memory=memory, term_evaluations=steps * terms)


def over_size(case, bristles: int) -> list[str]:
    """The limits (case.limits) on the head's size that ``case`` exceeds, checked before
    any bristle is built."""
    limits = case.limits
    found = []
    if bristles > limits.bristles:
        found.append(f"the head has {bristles:,} bristles, more than limits.bristles = "
                     f"{limits.bristles:,}; to run it anyway, --set limits.bristles={bristles}")
    segments = case.model.segments
    if case.model.kind == "dfm" and segments > limits.segments:
        found.append(f"model.segments = {segments:,} is more than limits.segments = "
                     f"{limits.segments:,}; to run it anyway, --set limits.segments={segments}")
    return found


def over_work(case, work: WorkEstimate) -> list[str]:
    """The limits (case.limits) on steps and memory that ``work`` exceeds."""
    limits = case.limits
    found = []
    needs = f"the run needs at least {work.steps:,} time steps per system (end time / "
    if work.steps > C_INT:
        found.append(f"{needs}solver.step_size), more than Exudyn can count "
                     f"({C_INT:,}); shorten the run or take a longer step")
    elif work.steps > limits.steps:
        found.append(f"{needs}solver.step_size), more than limits.steps = {limits.steps:,}; "
                     f"to run it anyway, --set limits.steps={work.steps}")
    if work.term_evaluations > limits.term_evaluations:
        terms = work.term_evaluations // work.steps
        plural = "s" if terms != 1 else ""
        found.append(f"the run's {terms:,} pose term{plural} would be evaluated "
                     f"{work.term_evaluations:,} times per system (at each of at least "
                     f"{work.steps:,} steps), more "
                     f"than limits.term_evaluations = {limits.term_evaluations:,.0f}; a pose "
                     "table (motion.pose_csv) holds any motion as one term, or --set "
                     f"limits.term_evaluations={work.term_evaluations}")
    if work.memory > limits.memory:
        needed = math.ceil(work.memory / 1e9)
        found.append(f"its recorded results would take about {work.memory / 1e9:.3g} GB, more "
                     f"than limits.memory = {limits.memory / 1e9:.3g} GB; a longer "
                     f"output.interval records less, or --set limits.memory='{needed} GB'")
    return found


def unresolved(case, motion) -> list[str]:
    """One message for each time scale of ``motion`` that the settings do not resolve."""
    step = case.solver.step_size
    m = case.motion
    scales = [(motion.approach_duration / STEPS_PER_APPROACH,
               f"{STEPS_PER_APPROACH} steps per approach (motion.approach_duration)")]
    if m.profile == "sine":
        scales.append((m.period / STEPS_PER_PERIOD,
                       f"{STEPS_PER_PERIOD} steps per slide period (motion.period)"))
    elif m.profile == "csv":  # the profile's own length; its fast parts: motion_warnings
        scales.append((motion.slide.duration / STEPS_PER_PERIOD,
                       f"{STEPS_PER_PERIOD} steps over the slide CSV's duration"))
    table = motion.pose.table if motion.pose is not None else None
    if table is not None:
        scales.append((table.duration / STEPS_PER_PERIOD,
                       f"{STEPS_PER_PERIOD} steps over the pose CSV's duration"))
    if motion.hold_duration > 0.0:
        scales.append((motion.hold_duration / STEPS_PER_HOLD,
                       f"{STEPS_PER_HOLD} steps per hold (motion.hold_duration)"))
    bound, why = min(scales)
    found = []
    late = [(f"motion.sine[{i}]", entry.start) for i, entry in enumerate(m.sine)]
    if m.pose_csv:  # motion.pose_csv_start
        late.append(("motion.pose_csv", m.pose_csv_start))
    for key, start in late:
        if motion.slide_start + start >= motion.end_time:
            found.append(f"{key} starts {_seconds(start)} after the slide, at or after the "
                         f"run's end ({_seconds(motion.end_time)}): it would never act; start "
                         "it earlier or run longer")
    for i, entry in enumerate(m.sine):  # its steps are capped while it acts (step_policy)
        fine = term_step(case, entry.frequency)
        if fine < case.solver.minimum_step_size:
            found.append(f"motion.sine[{i}] ({entry.frequency:g} Hz) needs steps of at most "
                         f"{_seconds(fine)} ({case.solver.steps_per_cycle} per cycle), below "
                         f"solver.minimum_step_size {_seconds(case.solver.minimum_step_size)}")
    if step > bound * (1 + 1e-12):  # the tightest scale; the others follow from it
        found.append(f"solver.step_size {_seconds(step)} does not resolve the motion: "
                     f"{why} need a step of at most {_seconds(bound)}")
    for key, interval in (("interval", case.output.interval),
                          ("shape_interval", case.output.shape_interval)):
        if interval > motion.end_time / 2:
            found.append(f"output.{key} {_seconds(interval)} is more than half the run "
                         f"({_seconds(motion.end_time)}): it would record only the start; "
                         f"use at most {_seconds(motion.end_time / 2)}")
    return found


def _seconds(value: float) -> str:
    return f"{value * 1e3:.4g} ms" if value < 1.0 else f"{value:.4g} s"


def motion_warnings(case, motion) -> list[str]:
    """Where a slide CSV moves faster than the step resolves (a warning, not a refusal).

    Within one step of ``solver.step_size`` the slide speed should change by less than the
    friction law's ``contact.static_velocity`` (the speed over which friction goes from
    sticking to sliding); a measured profile with a jump or a sharp corner can demand more,
    and the solver then cuts its step there (slower, not wrong).
    """
    if case.motion.profile != "csv":
        return []
    step = case.solver.step_size
    change, when = motion.slide.largest_speed_change(step)
    allowed = case.contact.static_velocity
    if change <= allowed:
        return []
    return [f"the slide CSV changes the slide speed by up to {change:.3g} mm/s within one "
            f"{_seconds(step)} step (from t = {when:.4g} s after the slide starts), more than "
            f"contact.static_velocity = {allowed:g} mm/s; the solver will cut its steps there "
            f"(a step of about {_seconds(step * allowed / change)} resolves it)"]
