"""Solve one group of bristles: build its Exudyn system, step it, read it out.

This is the unit of work an executor (exubrush.execution) runs, in this process, in a
worker process or on a cluster: :func:`solve_group` takes the prepared case and the
indices of the bristles, and returns a :class:`GroupSolution`, a typed, picklable record
of plain arrays (exubrush.run.solution). It does not know where it runs: progress and stop
requests go through a :class:`SolveMonitor` the executor provides.
"""

from __future__ import annotations

import contextlib
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
    if first.completed or first.interrupted:
        return first
    fallback = full_newton(prepared.case)
    if fallback is None:
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
    settings = group_settings(prepared, scene, selection)
    bound = prepared.group_bound(selection, scene.handle_mass)
    guard = _StepGuard(scene, monitor, case.model.kind, bound)
    scene.mbs.SetPreStepUserFunction(guard)
    with _coordinates_file(settings, case.output) as coordinates_file:
        completed, message, wall = _step(scene, settings)
        coordinates = (read_coordinate_file(coordinates_file) if coordinates_file is not None
                       else None)
    if guard.reason:
        completed, message = False, guard.reason
    if monitor is not None:
        monitor.advance(scene.motion.end_time - guard.reported)
    readout = _read_out(scene)
    n, reaction, nodes, tip_force = _aligned(readout, case)
    n, completed, message = _last_sane(n, readout.drive[0][:, 0], reaction, nodes, bound,
                                       completed, message, case.model.kind)
    recorded = readout.drive[0][:n, 0]
    moment = (np.column_stack([d[:n, 1] for d in readout.turning]) if n
              else np.zeros((0, 3)))
    grid, reaction, moment, tips, nodes, tip_force = _on_grids(
        recorded, reaction[:n], moment, nodes[:, :, :n], tip_force[:, :n], case.output)
    return GroupSolution(
        time=grid,
        reaction=reaction,
        drive_moment=moment,
        handle_inertia=scene.handle_inertia.tolist(),
        tips=tips,
        nodes=nodes,
        tip_force=tip_force,
        coordinates=_kept_coordinates(coordinates, recorded, case.output),
        statistics=readout.statistics,
        completed=bool(completed and n > 0
                       and readout.drive[0][n - 1, 0] >= scene.motion.end_time - 1e-9),
        message=message,
        wall_time=wall,
        contacts=len(scene.contacts),
        handle_mass=float(scene.handle_mass),
        bristle_contacts_max=float(readout.counts.max()) if len(readout.counts) else 0.0,
        bristle_contacts_mean=float(readout.counts.mean()) if len(readout.counts) else 0.0,
        bristle_overlap_max=max(readout.overlaps, default=0.0),
    )


class _StepGuard:
    """Exudyn's pre-step function of a solve: runs the scene's step hooks, and every
    :data:`PROGRESS_STEP` of simulated time reports progress and stops the solve (returns
    False, with its ``reason``) on a stop request, a non-finite state or a normal force
    beyond ``bound`` [N]."""

    def __init__(self, scene: Scene, monitor: SolveMonitor | None, model: str, bound: float):
        self.scene, self.monitor, self.model, self.bound = scene, monitor, model, bound
        self.reported = 0.0  # simulated time [s] reported to the monitor
        self.asked = time.monotonic()  # wall time of the last look for a stop request
        self.reason = ""  # why the solve was stopped ("": it was not)

    def __call__(self, mbs, t) -> bool:
        self.scene.run_step_hooks(mbs, t)
        # a stop is also looked for by wall time: a solve crawling through tiny steps may
        # take minutes for one PROGRESS_STEP of simulated time (a SIGTERM went unheard for
        # 40 minutes in a tuft stuck at 1e-9 s steps)
        monitor = self.monitor
        if monitor is not None and time.monotonic() - self.asked >= STOP_CHECK_INTERVAL:
            self.asked = time.monotonic()
            if monitor.stop_requested():
                self.reason = INTERRUPTED
                return False
        if t - self.reported >= PROGRESS_STEP:
            self.reason = self._trouble(mbs, t)
            if self.reason:
                return False
            if monitor is not None:
                monitor.advance(t - self.reported)
            self.reported = t
        return True

    def _trouble(self, mbs, t) -> str:
        """Why the solve must stop at ``t`` [s], "" if it need not."""
        if self.monitor is not None and self.monitor.stop_requested():
            return INTERRUPTED
        if not np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())):
            return f"non-finite state at t = {t:.6g} s"
        pressing = float(np.max(np.abs(mbs.GetSensorValues(self.scene.drive_sensors.z))))
        if pressing > self.bound:
            return beyond_bound_message(self.model, t, pressing, self.bound)
        return ""


@contextlib.contextmanager
def _coordinates_file(settings, output):
    """The temporary file Exudyn writes the ODE2 coordinates into during the solve, where
    the case keeps them (``output.solution_file``; else None), removed afterwards."""
    if not output.solution_file:
        yield None
        return
    handle, name = tempfile.mkstemp(prefix="exubrush-", suffix=".txt")
    os.close(handle)
    # at the force interval: interpolated onto the shape grid between the same records
    # as the node positions (on_output_grid), so both say the same
    record_coordinates(settings, name, output.interval)
    try:
        yield name
    finally:
        os.unlink(name)


def _step(scene: Scene, settings) -> tuple[bool, str, float]:
    """Step ``scene`` to its end time: whether Exudyn finished, its error message ("" if
    none) and the wall time [s]."""
    start = time.perf_counter()
    completed, message = True, ""
    try:
        completed = bool(scene.mbs.SolveDynamic(settings, storeSolver=True))
    except (exu.SolverError, RuntimeError) as err:
        completed, message = False, " ".join(str(err).split())
    return completed, message, time.perf_counter() - start


@dataclasses.dataclass(frozen=True)
class _Readout:
    """What a solved system held: each sensor's stored rows (time [s], values), its solver
    statistics and its bristles' contact counts and overlaps [mm]."""

    drive: list  # the drive's reaction sensors' rows, x, y, z
    turning: list  # the drive's moment sensors' rows
    histories: list  # per bristle, per node, the node's position rows
    contact_sensors: list  # scene.contact_sensors
    contact_rows: list  # per contact sensor, (force rows, frame rows or None)
    statistics: SolverStatistics
    counts: np.ndarray
    overlaps: list


def _read_out(scene: Scene) -> _Readout:
    """Everything the solved ``scene`` holds, read out before its system is freed."""
    def stored(sensor):
        return np.asarray(scene.mbs.GetSensorStoredData(sensor))

    touching = scene.bristle_contact
    readout = _Readout(
        drive=[stored(s) for s in scene.drive_sensors.force],
        turning=[stored(s) for s in scene.drive_sensors.moment],
        histories=[[stored(s) for s in sensors] for sensors in scene.node_sensors],
        contact_sensors=list(scene.contact_sensors),
        contact_rows=[(stored(s.force), None if s.frame is None else stored(s.frame))
                      for s in scene.contact_sensors],
        statistics=solver_statistics(scene.mbs, scene.line_search),
        counts=np.asarray(touching.counts if touching is not None else [], float),
        overlaps=touching.overlaps if touching is not None else [])
    # Exudyn keeps a system container alive after its last Python reference is gone: without
    # this, a worker's memory grew by the stored sensor data of every group it solved
    # (0.9 MB per default bristle and 2 periods, docs/decisions/0008)
    scene.system_container.Reset()
    return readout


def _aligned(readout: _Readout, case):
    """The rows every sensor recorded: their count n, the drive's reaction (n, 3) [N], the
    nodes (bristles, nodes, n, 3) [mm] and the force on each tip (bristles, n, 3) [N]."""
    histories = readout.histories
    n = min(len(h) for h in [*readout.drive, *readout.turning,
                             *(h for nodes in histories for h in nodes),
                             *(rows for rows, _ in readout.contact_rows)])
    nodes = np.array([[h[:n, 1:4] for h in bristle] for bristle in histories])
    tip_force = np.zeros((len(histories), n, 3))
    for sensor, (rows, frames) in zip(readout.contact_sensors, readout.contact_rows,
                                      strict=True):
        tip_force[sensor.bristle] = force_on_tip(case, rows[:n, 1:4],
                                                 None if frames is None else frames[:n, 1:10],
                                                 sensor.compiled)
    reaction = np.column_stack([d[:n, 1] for d in readout.drive]) if n else np.zeros((0, 3))
    return n, reaction, nodes, tip_force


def _last_sane(n: int, times: np.ndarray, reaction: np.ndarray, nodes: np.ndarray,
               bound: float, completed: bool, message: str, model: str):
    """(rows kept, completed, message): the ``n`` rows up to the first with a non-finite
    reaction or node or a normal force beyond ``bound`` [N], never passed on as data; a
    solve cut there did not complete, and says why unless it was stopped on request."""
    finite = np.all(np.isfinite(reaction), axis=1) & np.all(np.isfinite(nodes), axis=(0, 1, 3))
    sane = finite & within_bound(reaction, bound)
    if sane.all():
        return n, completed, message
    n = int(np.argmin(sane))
    if message != INTERRUPTED:  # the first sample dropped, not the check that saw it
        first = times[n]
        message = (f"non-finite forces or positions at t = {first:.6g} s" if not finite[n]
                   else beyond_bound_message(model, first, abs(reaction[n, 2]), bound))
    return n, False, message


def _on_grids(recorded, reaction, moment, nodes, tip_force, output):
    """The kept rows at their record times ``recorded`` [s] put on the output grid
    (:func:`on_output_grid`): the grid, the reaction, the drive's moment, the tips at every
    time, the nodes (bristles, nodes, n, 3) at the shape samples only, the tip forces
    (bristles, n, 3) as (n, bristles, 3)."""
    grid, reaction = on_output_grid(recorded, reaction, output.interval)
    _, moment = on_output_grid(recorded, moment, output.interval)
    _, nodes = on_output_grid(recorded, nodes.transpose(2, 0, 1, 3), output.interval)
    tips, nodes = nodes[:, :, -1].copy(), nodes[::output.shape_stride].copy()
    _, tip_force = on_output_grid(recorded, tip_force.transpose(1, 0, 2), output.interval)
    return grid, reaction, moment, tips, nodes, tip_force


def _kept_coordinates(coordinates, recorded, output):
    """The coordinate rows up to the last sane record time, on the shape grid (None: the
    run keeps none)."""
    if coordinates is None:
        return None
    kept = coordinates[coordinates[:, 0] <= (recorded[-1] if len(recorded) else -1.0) + 1e-12]
    shape_grid, values = on_output_grid(kept[:, 0], kept[:, 1:], output.shape_interval)
    return np.column_stack([shape_grid, values])


def solver_statistics(mbs, line_search: LineSearch | None = None) -> SolverStatistics:
    """Step, Newton and Jacobian counts of the last dynamic solve of ``mbs``, and the
    updates its ``line_search`` shortened and the attempts it gave up."""
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
        given_up_attempts=line_search.counts.given_up if line_search is not None else 0,
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
