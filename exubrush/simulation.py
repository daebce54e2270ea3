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

import multiprocessing
import os
import platform
import queue
import time
from concurrent.futures import ProcessPoolExecutor

import exudyn as exu
import numpy as np
from tqdm import tqdm

import exubrush
from exubrush.models.geometry import head_bristles
from exubrush.motion import head_motion
from exubrush.parameters.case import Case
from exubrush.parameters.fields import to_plain
from exubrush.results import Results
from exubrush.scene import SLIDE_AXES, build_scene, handle_kinematics, prb_parameters
from exubrush.solver import dynamic_settings

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


_WORKER = {"queue": None, "parent": None}


def _init_worker(progress_queue, parent_pid: int) -> None:
    """Pool initializer: where to report progress, and which process to outlive never."""
    _WORKER["queue"], _WORKER["parent"] = progress_queue, parent_pid


def _solve_in_worker(case: Case, selection: list[int] | None) -> dict:
    return solve_group(case, selection, _WORKER["queue"], _WORKER["parent"])


def solve_group(
    case: Case, selection: list[int] | None, progress_queue=None, parent_pid: int | None = None
) -> dict:
    """Solve the bristles ``selection`` of ``case`` as one Exudyn system.

    A worker process passes ``parent_pid``: if that process dies (Ctrl-C, kill), the worker
    exits at once instead of computing on as an orphan.

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
    reported = [0.0]

    def report(mbs, t):
        if t - reported[0] >= PROGRESS_STEP:
            if parent_pid is not None and os.getppid() != parent_pid:
                os._exit(1)  # orphaned: nobody will read the result
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
        completed, message = False, str(err)
    wall = time.perf_counter() - start
    if progress_queue is not None:
        progress_queue.put(end_time - reported[0])
    drive = [np.asarray(scene.mbs.GetSensorStoredData(s)) for s in scene.drive_sensors]
    histories = [[np.asarray(scene.mbs.GetSensorStoredData(s)) for s in sensors]
                 for sensors in scene.node_sensors]
    n = min(len(h) for h in [*drive, *(h for nodes in histories for h in nodes)])
    nodes = np.array([[h[:n, 1:4] for h in bristle] for bristle in histories])
    return {
        "time": drive[0][:n, 0],
        "reaction": np.column_stack([d[:n, 1] for d in drive]),
        "nodes": nodes.transpose(2, 0, 1, 3),
        "statistics": _solver_statistics(scene.mbs),
        "completed": completed and n > 0 and drive[0][n - 1, 0] >= end_time - 1e-9,
        "message": message,
        "wall_time": wall,
        "contacts": len(scene.contacts),
        "handle_mass": scene.handle_mass,
    }


def _groups(case: Case, count: int) -> list[list[int] | None]:
    if case.solver.partition == "coupled":
        return [None]
    return [[i] for i in range(count)]


def _run_groups(case: Case, groups, workers: int, progress: bool, total: float) -> list[dict]:
    bar = tqdm(total=round(total, 2), disable=not progress, desc=f"{case.name} {case.model.kind}",
               bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} s simulated [{elapsed}<{remaining}]")
    share = 1.0 / len(groups)
    if workers <= 1 or len(groups) == 1:
        local = queue.SimpleQueue()
        outputs = []
        for group in groups:
            outputs.append(solve_group(case, group, local))
            while not local.empty():
                bar.update(local.get() * share)
        bar.close()
        return outputs
    context = multiprocessing.get_context("spawn")
    updates = context.Queue()
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_init_worker,
                             initargs=(updates, os.getpid())) as pool:
        futures = [pool.submit(_solve_in_worker, case, group) for group in groups]
        while not all(f.done() for f in futures):
            try:
                bar.update(updates.get(timeout=0.2) * share)
            except queue.Empty:
                pass
        outputs = [f.result() for f in futures]
    bar.close()
    return outputs


def simulate(case: Case, progress: bool = True, workers: int | None = None) -> Results:
    """Build and solve ``case``; return its results (marked incomplete if a solve stopped).

    Parameters
    ----------
    progress : bool
        Show a progress bar of the simulated time on standard error.
    workers : int, optional
        Processes for per-bristle solves (default: the number of cores).
    """
    bristles = head_bristles(case.head)
    motion, start_height = head_motion(case, bristles)
    groups = _groups(case, len(bristles))
    workers = workers or os.cpu_count() or 1
    start = time.perf_counter()
    outputs = _run_groups(case, groups, workers, progress, motion.end_time)
    wall = time.perf_counter() - start
    n = min(len(o["time"]) for o in outputs)
    t = outputs[0]["time"][:n]
    reaction = sum(o["reaction"][:n] for o in outputs)
    nodes = np.concatenate([o["nodes"][:n] for o in outputs], axis=1)
    slide_axis = SLIDE_AXES[case.motion.direction]
    kinematics = np.array([handle_kinematics(motion, slide_axis, ti) for ti in t])
    handle_position = kinematics[:, 0] + np.array([0.0, 0.0, start_height])
    # The drive's reaction is the constraint multiplier: the force the handle's coordinates
    # exert on the drive. The head's force on the surface is its negative, minus the m·a of
    # the handle of each group (each group has its own handle).
    handle_mass = sum(o["handle_mass"] for o in outputs)
    head_force = -reaction - handle_mass * kinematics[:, 2]
    completed = all(o["completed"] for o in outputs)
    messages = sorted({o["message"] for o in outputs if o["message"]})
    stride = max(1, round(case.output.shape_interval / case.output.interval))
    rows = np.arange(0, n, stride)
    roots = np.array([b.root for b in bristles])
    shape_nodes = np.concatenate(
        [(handle_position[rows][:, None, :] + roots[None, :, :])[:, :, None, :], nodes[rows]],
        axis=2,
    )
    statistics = {key: sum(o["statistics"].get(key, 0) for o in outputs)
                  for key in outputs[0]["statistics"]}
    derived = {
        "bristles": len(bristles),
        "contact_elements": sum(o["contacts"] for o in outputs),
        "partition": case.solver.partition,
        "systems_solved": len(outputs),
        "worker_processes": min(workers, len(groups)),
        "approach_distance_mm": motion.approach_distance,
        "slide_start_s": motion.slide_start,
        "end_time_s": motion.end_time,
    }
    if case.model.kind == "prb":
        derived["prb_gamma"], derived["prb_stiffness_coefficient"] = prb_parameters(case)
    metadata = {
        "case": case.name,
        "model": case.model.kind,
        "parameters": to_plain(case),
        "derived": derived,
        "versions": {"exubrush": exubrush.__version__, "exudyn": exu.__version__,
                     "python": platform.python_version()},
        "solver_statistics": statistics,
        "solver_wall_time_s_sum": sum(o["wall_time"] for o in outputs),
        "wall_time_s": wall,
        "simulated_time_s": float(t[-1]) if n else 0.0,
        "completed": completed,
        "message": "; ".join(messages),
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
        metadata=metadata,
    )


def run_case(case: str, model: str = "dfm", overrides=(), progress: bool = True) -> Results:
    """Simulate a built-in case or case file with ``model`` and ``KEY=VALUE`` overrides."""
    from exubrush.parameters.io import load_case

    return simulate(load_case(case, [f"model.kind='{model}'", *overrides]), progress)
