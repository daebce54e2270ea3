"""Compose, run and read out a brushing simulation.

With the head's motion prescribed and no bristle-bristle contact, the bristles do not
interact: the head force is the sum of the bristles' forces. By default
(``solver.partition = "per-bristle"``) every bristle is therefore solved as its own small
Exudyn system, in parallel processes (Exudyn's threads do not mix with Python user
functions), and the drive reactions are summed. ``"coupled"`` solves the whole head as one
system, which the same forces must come out of (tests/integration/test_partition.py).

>>> from exubrush.parameters.case import orthogonal_case
>>> from exubrush.simulation import simulate
>>> results = simulate(orthogonal_case())          # doctest: +SKIP
>>> results.save("results/orthogonal")              # doctest: +SKIP
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import platform
import queue
import signal
import tempfile
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

import exudyn as exu
import numpy as np
from tqdm import tqdm

import exubrush
from exubrush.models.geometry import head_bristles
from exubrush.motion import head_motion
from exubrush.parameters.case import Case
from exubrush.parameters.fields import to_plain
from exubrush.results import Results
from exubrush.rundir import RunDirectory
from exubrush.sanity import normal_force_bound
from exubrush.scene import SLIDE_AXES, build_scene, handle_kinematics, prb_parameters
from exubrush.solver import dynamic_settings, record_coordinates
from exubrush.viewer import head_coordinates, read_coordinate_file

PROGRESS_STEP = 0.05  # s of simulated time between progress reports of a group


def _solver_statistics(mbs) -> dict:
    solver = mbs.sys.get("dynamicSolver")
    if solver is None:
        return {}
    it = solver.it
    return {
        "steps": int(it.currentStepIndex),
        "newton_iterations": int(it.newtonStepsCount),
        "jacobian_updates": int(it.newtonJacobiCount),
        "rejected_modified_newton_steps": int(it.rejectedModifiedNewtonSteps),
    }


_WORKER = {"queue": None, "parent": None, "stop": None}


def _init_worker(progress_queue, parent_pid: int, stop) -> None:
    """Pool initializer: where to report progress, which process to outlive never, and the
    event that asks for a clean stop. Ctrl-C reaches the whole process group; the parent
    decides, so workers ignore SIGINT and watch ``stop`` instead."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _WORKER.update(queue=progress_queue, parent=parent_pid, stop=stop)


def _solve_in_worker(case: Case, selection: list[int] | None) -> dict:
    return solve_group(case, selection, _WORKER["queue"], _WORKER["parent"], _WORKER["stop"])


def solve_group(
    case: Case, selection: list[int] | None, progress_queue=None, parent_pid: int | None = None,
    stop=None,
) -> dict:
    """Solve the bristles ``selection`` of ``case`` as one Exudyn system.

    A worker process passes ``parent_pid``: if that process dies (kill), the worker exits at
    once instead of computing on as an orphan. If the event ``stop`` is set (Ctrl-C), the
    solve ends at the next report and returns what it has, marked interrupted. The state is
    checked for non-finite values at each report; a diverged solve stops there.

    Returns
    -------
    dict
        ``time`` (n,) [s]; ``reaction`` (n, 3) drive force on the handle [N]; ``nodes``
        (n, bristles, nodes, 3) node positions [mm]; ``statistics``; ``completed``;
        ``message``; ``wall_time`` [s]; ``contacts`` (number of contact elements);
        ``handle_mass`` [t].
    """
    scene = build_scene(case, selection)
    end_time = scene.motion.end_time
    settings = dynamic_settings(case.solver, end_time, case.output.interval)
    coordinates_file = None
    if case.output.solution_file == "yes":
        handle, coordinates_file = tempfile.mkstemp(prefix="exubrush-", suffix=".txt")
        os.close(handle)
        # at the force interval: interpolated onto the shape grid between the same records
        # as the node positions (on_output_grid), so both say the same
        record_coordinates(settings, coordinates_file, case.output.interval)
    bound = normal_force_bound(case, scene.bristles)
    reported = [0.0]
    status = {"reason": ""}

    def report(mbs, t):
        for hook in scene.step_hooks:
            hook(mbs, t)
        if t - reported[0] >= PROGRESS_STEP:
            if parent_pid is not None and os.getppid() != parent_pid:
                os._exit(1)  # orphaned: nobody will read the result
            if stop is not None and stop.is_set():
                status["reason"] = "interrupted"
                return False
            if not np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())):
                status["reason"] = f"non-finite state at t = {t:.6g} s"
                return False
            pressing = float(np.max(np.abs(mbs.GetSensorValues(scene.drive_sensors[2]))))
            if pressing > bound:
                status["reason"] = _beyond_bound(case, t, pressing, bound)
                return False
            if progress_queue is not None:
                progress_queue.put(t - reported[0])
            reported[0] = t
        return True

    scene.mbs.SetPreStepUserFunction(report)
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
    if progress_queue is not None:
        progress_queue.put(end_time - reported[0])
    drive = [np.asarray(scene.mbs.GetSensorStoredData(s)) for s in scene.drive_sensors]
    histories = [[np.asarray(scene.mbs.GetSensorStoredData(s)) for s in sensors]
                 for sensors in scene.node_sensors]
    n = min(len(h) for h in [*drive, *(h for nodes in histories for h in nodes)])
    nodes = np.array([[h[:n, 1:4] for h in bristle] for bristle in histories])
    reaction = np.column_stack([d[:n, 1] for d in drive]) if n else np.zeros((0, 3))
    finite = np.all(np.isfinite(reaction), axis=1) & np.all(np.isfinite(nodes), axis=(0, 1, 3))
    sane = finite & (np.abs(np.nan_to_num(reaction[:, 2])) <= bound)
    if not sane.all():  # never pass a diverged or unphysical sample on as data
        n = int(np.argmin(sane))
        completed = False
        message = message or ("non-finite forces or positions" if not finite.all()
                              else "normal force beyond the physical bound")
    recorded = drive[0][:n, 0]
    grid, reaction = on_output_grid(recorded, reaction[:n], case.output.interval)
    _, nodes = on_output_grid(recorded, nodes[:, :, :n].transpose(2, 0, 1, 3),
                              case.output.interval)
    output = {
        "time": grid,
        "reaction": reaction,
        "nodes": nodes,
        "statistics": _solver_statistics(scene.mbs),
        "completed": bool(completed and n > 0 and drive[0][n - 1, 0] >= end_time - 1e-9),
        "message": message,
        "wall_time": wall,
        "contacts": len(scene.contacts),
        "handle_mass": float(scene.handle_mass),
    }
    if coordinates is not None:  # the rows up to the last sane sample
        kept = coordinates[coordinates[:, 0] <= (recorded[-1] if n else -1.0) + 1e-12]
        shape_grid, values = on_output_grid(kept[:, 0], kept[:, 1:], case.output.shape_interval)
        output["coordinates"] = np.column_stack([shape_grid, values])
    return output


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


def _beyond_bound(case: Case, t: float, force: float, bound: float) -> str:
    """Stop message for a force no real bristle can produce (exubrush.sanity)."""
    if case.model.kind == "prb":
        cause = ("the rigid PRB link jams where a real bristle would buckle (high friction or "
                 "deep interference); use the DFM model for this case")
    else:
        cause = "a numerical blow-up; try a smaller solver.step_size or a softer contact"
    return (f"normal force {force:.4g} N at t = {t:.6g} s exceeds the physical bound "
            f"{bound:.4g} N (every bristle straight and fully compressed, x2): {cause}")


def _groups(case: Case, count: int) -> list[list[int] | None]:
    if case.solver.partition == "coupled":
        return [None]
    return [[i] for i in range(count)]


def _drain(updates, bar, share: float) -> None:
    """Move the workers' progress reports (simulated seconds) onto the bar, never past its
    end (the reports add up to the total only within round-off; past it tqdm warns)."""
    while True:
        try:
            step = updates.get_nowait() * share
        except queue.Empty:
            return
        bar.update(max(0.0, min(step, bar.total - bar.n)))


@contextlib.contextmanager
def signals_redirected(handler):
    """Handle Ctrl-C and SIGTERM with ``handler`` inside the block (restored after it).

    Used to let a solve in this process stop at its next report instead of raising inside
    Exudyn (an exception there surfaces as a solver failure or a traceback), and to finish
    writing results. Outside the main thread signals cannot be handled: no change.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {number: signal.signal(number, handler)
                for number in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for number, old in previous.items():
            signal.signal(number, old)


def _run_groups(case: Case, groups, workers: int, progress: bool, total: float,
                directory: RunDirectory | None) -> tuple[list[dict | None], bool]:
    """Solve ``groups`` (skipping those ``directory`` holds); store each as it finishes.

    Returns the outputs (None for a group never started) and whether the run was
    interrupted (Ctrl-C, or SIGTERM turned into one by the caller).
    """
    outputs: list[dict | None] = [None] * len(groups)
    for index, output in (directory.stored_groups() if directory else {}).items():
        outputs[index] = output
    todo = [i for i in range(len(groups)) if outputs[i] is None]
    bar = tqdm(total=round(total, 2), disable=not progress, desc=f"{case.name} {case.model.kind}",
               bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} s simulated [{elapsed}<{remaining}]")
    share = 1.0 / len(groups)
    bar.update(total * share * (len(groups) - len(todo)))

    def finished(index: int, output: dict) -> None:
        outputs[index] = output
        if directory is not None and output["completed"]:
            directory.keep(index, output)

    interrupted = False
    if workers <= 1 or len(todo) <= 1:
        local, stop = queue.SimpleQueue(), threading.Event()
        with signals_redirected(lambda *_: stop.set()):
            for index in todo:
                if stop.is_set():
                    break
                finished(index, solve_group(case, groups[index], local, stop=stop))
                _drain(local, bar, share)
        bar.close()
        return outputs, stop.is_set()
    context = multiprocessing.get_context("spawn")
    updates, stop = context.Queue(), context.Event()
    with ProcessPoolExecutor(min(workers, len(todo)), mp_context=context,
                             initializer=_init_worker,
                             initargs=(updates, os.getpid(), stop)) as pool:
        futures = {pool.submit(_solve_in_worker, case, groups[i]): i for i in todo}
        pending = set(futures)
        while pending:
            try:
                done, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
                for future in done:
                    if not future.cancelled():
                        finished(futures[future], future.result())
                _drain(updates, bar, share)
            except KeyboardInterrupt:
                interrupted = True
                stop.set()  # running solves return what they have at their next report
                for future in pending:
                    future.cancel()
    bar.close()
    return outputs, interrupted


def simulate(case: Case, progress: bool = True, workers: int | None = None,
             directory: RunDirectory | None = None) -> Results:
    """Build and solve ``case``; return its results.

    If a solve fails or the run is interrupted, the results hold the head force over the
    time every group reached (nothing if a group never started) and ``metadata["status"]``
    says "failed" or "interrupted" with the reason.

    Parameters
    ----------
    progress : bool
        Show a progress bar of the simulated time on standard error.
    workers : int, optional
        Processes for per-bristle solves (default: the number of cores).
    directory : RunDirectory, optional
        Where finished groups are stored as they finish, and read back when resuming.
    """
    bristles = head_bristles(case.head)
    motion, start_height = head_motion(case, bristles)
    groups = _groups(case, len(bristles))
    workers = workers or os.cpu_count() or 1
    start = time.perf_counter()
    outputs, interrupted = _run_groups(case, groups, workers, progress, motion.end_time,
                                       directory)
    wall = time.perf_counter() - start
    ran = [o for o in outputs if o is not None]
    n = min(len(o["time"]) for o in ran) if len(ran) == len(outputs) else 0
    t = ran[0]["time"][:n] if ran else np.zeros(0)
    reaction = sum(o["reaction"][:n] for o in ran) if n else np.zeros((0, 3))
    nodes_per_bristle = case.model.segments if case.model.kind == "dfm" else 1
    nodes = (np.concatenate([o["nodes"][:n] for o in outputs], axis=1) if n
             else np.zeros((0, len(bristles), nodes_per_bristle, 3)))
    slide_axis = SLIDE_AXES[case.motion.direction]
    kinematics = np.array([handle_kinematics(motion, slide_axis, ti) for ti in t])
    kinematics = kinematics.reshape(len(t), 3, 3)
    handle_position = kinematics[:, 0] + np.array([0.0, 0.0, start_height])
    # The drive's reaction is the constraint multiplier: the force the handle's coordinates
    # exert on the drive. The head's force on the surface is its negative, minus the m·a of
    # the handle of each group (each group has its own handle).
    handle_mass = sum(o["handle_mass"] for o in ran)
    head_force = -reaction - handle_mass * kinematics[:, 2]
    completed = not interrupted and len(ran) == len(outputs) and all(o["completed"] for o in ran)
    status = "completed" if completed else "interrupted" if interrupted else "failed"
    message = "" if completed else _stop_message(case, outputs, interrupted)
    stride = max(1, round(case.output.shape_interval / case.output.interval))
    rows = np.arange(0, n, stride)
    roots = np.array([b.root for b in bristles])
    shape_nodes = np.concatenate(
        [(handle_position[rows][:, None, :] + roots[None, :, :])[:, :, None, :], nodes[rows]],
        axis=2,
    )
    shape_coordinates = None
    if case.output.solution_file == "yes" and n:
        shape_coordinates = head_coordinates([o["coordinates"] for o in outputs])
    statistics = {key: sum(o["statistics"].get(key, 0) for o in ran)
                  for key in (ran[0]["statistics"] if ran else {})}
    derived = {
        "bristles": len(bristles),
        "contact_elements": sum(o["contacts"] for o in ran),
        "partition": case.solver.partition,
        "systems_solved": len(groups),
        "systems_finished": sum(bool(o["completed"]) for o in ran),
        "systems_resumed": directory.resumed if directory else 0,
        "worker_processes": min(workers, len(groups)),
        "approach_distance_mm": motion.approach_distance,
        "slide_start_s": motion.slide_start,
        "end_time_s": motion.end_time,
    }
    if case.model.kind == "prb":
        derived["prb_gamma"], derived["prb_stiffness_coefficient"] = prb_parameters(case)
        if case.model.prb_parameters != "explicit":
            derived["prb_load_ratio"] = case.load_ratio()
    bound = normal_force_bound(case, bristles)
    peak = float(np.max(np.abs(head_force[:, 2]))) if n else 0.0
    metadata = {
        "case": case.name,
        "model": case.model.kind,
        "parameters": to_plain(case),
        "derived": derived,
        "versions": {"exubrush": exubrush.__version__, "exudyn": exu.__version__,
                     "python": platform.python_version()},
        "solver_statistics": statistics,
        "sanity": {"peak_normal_force_N": peak, "normal_force_bound_N": bound,
                   "within_bound": peak <= bound},
        "solver_wall_time_s_sum": sum(o["wall_time"] for o in ran),
        "wall_time_s": wall,
        "simulated_time_s": float(t[-1]) if n else 0.0,
        "status": status,
        "completed": completed,
        "message": message,
        "data_origin": "exubrush model output (simulation, not measurement)",
    }
    return Results(
        time=t,
        slider_position=np.array([motion.sliding(ti)[0] for ti in t]),
        normal_force=-head_force[:, 2],
        tangential_force=head_force @ slide_axis,
        head_height=handle_position[:, 2],
        shape_time=t[rows],
        shape_nodes=shape_nodes,
        shape_coordinates=shape_coordinates,
        metadata=metadata,
    )


def _stop_message(case: Case, outputs: list[dict | None], interrupted: bool) -> str:
    """Why the run stopped, when, and what to change."""
    finished = sum(1 for o in outputs if o is not None and o["completed"])
    if interrupted:
        return (f"{finished} of {len(outputs)} bristle groups finished and are "
                "kept: run the same command again to resume")
    failed = [(i, o) for i, o in enumerate(outputs) if o is not None and not o["completed"]]
    index, output = min(failed, key=lambda item: len(item[1]["time"]))
    reached = float(output["time"][-1]) if len(output["time"]) else 0.0
    reason = output["message"] or "the solver stopped before the end time"
    if "physical bound" in reason:
        return f"group {index} stopped at t = {reached:.6g} s: {reason}"
    return (f"group {index} stopped at t = {reached:.6g} s ({reason}); likely cause: no "
            f"converged step down to solver.minimum_step_size ({case.solver.minimum_step_size:g}"
            " s), e.g. a contact too stiff for the step or a violent snap-through; try a "
            f"smaller solver.step_size (now {case.solver.step_size:g} s), a smaller "
            "solver.minimum_step_size, a softer contact.stiffness or more damping "
            "(head.material.damping_time)")


def run_case(case: str, model: str = "dfm", overrides=(), progress: bool = True) -> Results:
    """Simulate a built-in case or case file with ``model`` and ``KEY=VALUE`` overrides."""
    from exubrush.parameters.io import load_case

    return simulate(load_case(case, [f"model.kind='{model}'", *overrides]), progress)
