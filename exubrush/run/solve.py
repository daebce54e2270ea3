"""Solve one group of bristles: build its Exudyn system, step it, read it out.

This is the unit of work an executor (exubrush.execution) runs, in this process, in a
worker process or on a cluster: :func:`solve_group` takes the prepared case and the
indices of the bristles, and returns a :class:`GroupSolution`, a typed, picklable record
of plain arrays (exubrush.run.solution). It does not know where it runs: progress and stop
requests go through a :class:`SolveMonitor` the executor provides.
"""

from __future__ import annotations

import dataclasses
import os
import tempfile
import time
from typing import Protocol

import exudyn as exu
import numpy as np

from exubrush.contact.tip_force import force_on_tip
from exubrush.run.newton import LineSearch
from exubrush.run.prepared import PreparedCase
from exubrush.run.sanity import beyond_bound_message, within_bound
from exubrush.run.scene import Scene, build_scene
from exubrush.run.solution import INTERRUPTED, GroupSolution, SolverStatistics
from exubrush.run.solution_files import read_coordinate_file
from exubrush.run.solver import dynamic_settings, record_coordinates

PROGRESS_STEP = 0.05  # s of simulated time between two checks (progress, stop, divergence)
STOP_CHECK_INTERVAL = 0.5  # s of wall time between two looks for a stop request


class SolveMonitor(Protocol):
    """What a solve tells its executor, and asks it, while it runs."""

    def advance(self, simulated: float) -> None:
        """``simulated`` more seconds of this group are solved."""

    def stop_requested(self) -> bool:
        """Whether the solve should end now and return what it has (Ctrl-C, cancellation)."""


def group_settings(prepared: PreparedCase, scene: Scene, selection: tuple[int, ...]):
    """Exudyn's settings for stepping ``scene``, the system of the bristles ``selection``
    of ``prepared``: its case's solver, to the motion's end, a touching group's settings
    where its bristles touch each other, and Newton's force tolerance of its weakest
    bristle."""
    case = prepared.case
    return dynamic_settings(case.solver, scene.motion.end_time, case.output.interval,
                            touching=scene.bristle_contact is not None,
                            force_tolerance=prepared.newton_force_tolerance(selection))


def solve_group(prepared: PreparedCase, selection: tuple[int, ...],
                monitor: SolveMonitor | None = None) -> GroupSolution:
    """Solve the bristles ``selection`` of ``prepared`` as one Exudyn system (see
    :func:`solve_once`); a solve that fails, and was not stopped on request, is solved once
    more from the start with a fresh Jacobian at every Newton iteration
    (``solver.modified_newton = false``), marked ``retried``.

    Modified Newton fails now and then where a pressed filament lies over: 5 of the 40
    tufts of the ``manual-brush`` case stopped at t = 1.8 s, their steps cut down to
    solver.minimum_step_size; a full Newton, a line search after cuts, slower step recovery
    or a gentler cut each got them through (docs/decisions/0022). The returned record counts
    both solves' statistics and wall time, and keeps the one that got further.
    """
    first = solve_once(prepared, selection, monitor)
    fallback = full_newton(prepared.case)
    if first.completed or first.interrupted or fallback is None:
        return first
    again = solve_once(dataclasses.replace(prepared, case=fallback), selection,
                       _NoProgress(monitor) if monitor is not None else None)
    kept = again if again.completed or len(again.time) >= len(first.time) else first
    message = "" if kept.completed else (
        f"{first.message}; solved again with solver.modified_newton = false: {again.message}")
    return dataclasses.replace(kept, statistics=first.statistics + again.statistics,
                               wall_time=first.wall_time + again.wall_time, retried=True,
                               message=message)


def full_newton(case):
    """``case`` with a fresh Jacobian at every Newton iteration, or None if it has that."""
    if not case.solver.modified_newton:
        return None
    return case.replace(solver=case.solver.replace(modified_newton=False))


class _NoProgress:
    """A monitor that passes stop requests on but no progress (a retried solve's time was
    reported by the first)."""

    def __init__(self, monitor: SolveMonitor):
        self.monitor = monitor

    def advance(self, simulated: float) -> None:
        """Nothing: the first solve reported this group's time."""

    def stop_requested(self) -> bool:
        """The wrapped monitor's answer."""
        return self.monitor.stop_requested()


def solve_once(prepared: PreparedCase, selection: tuple[int, ...],
               monitor: SolveMonitor | None = None) -> GroupSolution:
    """Solve the bristles ``selection`` of ``prepared`` as one Exudyn system, once.

    Every :data:`PROGRESS_STEP` of simulated time the monitor hears of the progress and may
    stop the solve, which then returns what it has, marked not completed. The state is
    checked there for non-finite values and the normal force against the physical bound; a
    diverged or unphysical solve stops, and no sample of it past the last sane one is
    returned.
    """
    case = prepared.case
    scene = build_scene(prepared, selection)
    end_time = scene.motion.end_time
    settings = group_settings(prepared, scene, selection)
    coordinates_file = None
    if case.output.solution_file:
        handle, coordinates_file = tempfile.mkstemp(prefix="exubrush-", suffix=".txt")
        os.close(handle)
        # at the force interval: interpolated onto the shape grid between the same records
        # as the node positions (on_output_grid), so both say the same
        record_coordinates(settings, coordinates_file, case.output.interval)
    bound = prepared.group_bound(selection, scene.handle_mass)
    reported = [0.0]
    asked = [time.monotonic()]
    status = {"reason": ""}

    def before_step(mbs, t):
        scene.run_step_hooks(mbs, t)
        # a stop is also looked for by wall time: a solve crawling through tiny steps may
        # take minutes for one PROGRESS_STEP of simulated time (a SIGTERM went unheard for
        # 40 minutes in a tuft stuck at 1e-9 s steps)
        if monitor is not None and time.monotonic() - asked[0] >= STOP_CHECK_INTERVAL:
            asked[0] = time.monotonic()
            if monitor.stop_requested():
                status["reason"] = INTERRUPTED
                return False
        if t - reported[0] >= PROGRESS_STEP:
            if monitor is not None and monitor.stop_requested():
                status["reason"] = INTERRUPTED
                return False
            if not np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())):
                status["reason"] = f"non-finite state at t = {t:.6g} s"
                return False
            pressing = float(np.max(np.abs(mbs.GetSensorValues(scene.drive_sensors.z))))
            if pressing > bound:
                status["reason"] = beyond_bound_message(case.model.kind, t, pressing, bound)
                return False
            if monitor is not None:
                monitor.advance(t - reported[0])
            reported[0] = t
        return True

    scene.mbs.SetPreStepUserFunction(before_step)
    start = time.perf_counter()
    completed, message = True, ""
    try:
        completed = bool(scene.mbs.SolveDynamic(settings, storeSolver=True))
    except (exu.SolverError, RuntimeError) as err:
        completed, message = False, " ".join(str(err).split())
    wall = time.perf_counter() - start
    coordinates = None
    if coordinates_file is not None:
        try:
            coordinates = read_coordinate_file(coordinates_file)
        finally:
            os.unlink(coordinates_file)
    if status["reason"]:
        completed, message = False, status["reason"]
    if monitor is not None:
        monitor.advance(end_time - reported[0])
    def stored(sensor):
        return np.asarray(scene.mbs.GetSensorStoredData(sensor))

    drive = [stored(s) for s in scene.drive_sensors.force]
    turning = [stored(s) for s in scene.drive_sensors.moment]
    histories = [[stored(s) for s in sensors] for sensors in scene.node_sensors]
    # (force rows, frame rows or None) of each of scene.contact_sensors
    contact_rows = [(stored(s.force), None if s.frame is None else stored(s.frame))
                    for s in scene.contact_sensors]
    statistics = solver_statistics(scene.mbs, scene.line_search)
    touching = scene.bristle_contact
    counts = np.asarray(touching.counts if touching is not None else [], float)
    overlaps = touching.overlaps if touching is not None else []
    # Exudyn keeps a system container alive after its last Python reference is gone: without
    # this, a worker's memory grew by the stored sensor data of every group it solved
    # (0.9 MB per default bristle and 2 periods, docs/decisions/0008)
    scene.system_container.Reset()
    n = min(len(h) for h in [*drive, *turning, *(h for nodes in histories for h in nodes),
                             *(rows for rows, _ in contact_rows)])
    nodes = np.array([[h[:n, 1:4] for h in bristle] for bristle in histories])
    tip_force = np.zeros((len(histories), n, 3))
    for sensor, (rows, frames) in zip(scene.contact_sensors, contact_rows, strict=True):
        tip_force[sensor.bristle] = force_on_tip(case, rows[:n, 1:4],
                                                 None if frames is None else frames[:n, 1:10],
                                                 sensor.compiled)
    reaction = np.column_stack([d[:n, 1] for d in drive]) if n else np.zeros((0, 3))
    finite = np.all(np.isfinite(reaction), axis=1) & np.all(np.isfinite(nodes), axis=(0, 1, 3))
    sane = finite & within_bound(reaction, bound)
    if not sane.all():  # never pass a diverged or unphysical sample on as data
        n = int(np.argmin(sane))
        completed = False
        if message != INTERRUPTED:  # the first sample dropped, not the check that saw it
            first = drive[0][n, 0]
            message = (f"non-finite forces or positions at t = {first:.6g} s" if not finite[n]
                       else beyond_bound_message(case.model.kind, first,
                                                 abs(reaction[n, 2]), bound))
    recorded = drive[0][:n, 0]
    grid, reaction = on_output_grid(recorded, reaction[:n], case.output.interval)
    moment = np.column_stack([d[:n, 1] for d in turning]) if n else np.zeros((0, 3))
    _, moment = on_output_grid(recorded, moment, case.output.interval)
    _, nodes = on_output_grid(recorded, nodes[:, :, :n].transpose(2, 0, 1, 3),
                              case.output.interval)
    tips, nodes = nodes[:, :, -1].copy(), nodes[::case.output.shape_stride].copy()
    _, tip_force = on_output_grid(recorded, tip_force[:, :n].transpose(1, 0, 2),
                                  case.output.interval)
    if coordinates is not None:  # the rows up to the last sane sample
        kept = coordinates[coordinates[:, 0] <= (recorded[-1] if n else -1.0) + 1e-12]
        shape_grid, values = on_output_grid(kept[:, 0], kept[:, 1:], case.output.shape_interval)
        coordinates = np.column_stack([shape_grid, values])
    return GroupSolution(
        time=grid,
        reaction=reaction,
        drive_moment=moment,
        handle_inertia=scene.handle_inertia.tolist(),
        tips=tips,
        nodes=nodes,
        tip_force=tip_force,
        coordinates=coordinates,
        statistics=statistics,
        completed=bool(completed and n > 0 and drive[0][n - 1, 0] >= end_time - 1e-9),
        message=message,
        wall_time=wall,
        contacts=len(scene.contacts),
        handle_mass=float(scene.handle_mass),
        bristle_contacts_max=float(counts.max()) if len(counts) else 0.0,
        bristle_contacts_mean=float(counts.mean()) if len(counts) else 0.0,
        bristle_overlap_max=max(overlaps, default=0.0),
    )


def solver_statistics(mbs, line_search: LineSearch | None = None) -> SolverStatistics:
    """Step, Newton and Jacobian counts of the last dynamic solve of ``mbs``, and the
    updates its ``line_search`` shortened."""
    solver = mbs.sys.get("dynamicSolver")
    if solver is None:
        return SolverStatistics()
    it = solver.it
    return SolverStatistics(
        steps=int(it.currentStepIndex),
        newton_iterations=int(it.newtonStepsCount),
        jacobian_updates=int(it.newtonJacobiCount),
        rejected_modified_newton_steps=int(it.rejectedModifiedNewtonSteps),
        shortened_updates=line_search.counts.shortened if line_search is not None else 0,
    )


def on_output_grid(times: np.ndarray, values: np.ndarray, interval: float):
    """Samples onto exact multiples of ``interval`` [s], by linear interpolation.

    Exudyn records a sensor or solution row at the first step end at or after each
    multiple of the write period, so after a step cut two bristles' rows can be a step
    apart. Interpolated onto the same grid, rows of different bristles add up at the same
    time. The grid ends at the last record; ``values`` has the records along axis 0.
    """
    if len(times) == 0:
        return np.zeros(0), values[:0]
    count = int(np.floor(times[-1] / interval + 1e-9)) + 1
    grid = np.arange(count) * interval
    columns = values.reshape(len(times), -1).T
    resampled = np.array([np.interp(grid, times, column) for column in columns]).T
    return grid, resampled.reshape((count, *values.shape[1:]))
