"""Compose, run and read out a brushing simulation.

>>> from exubrush.parameters.case import orthogonal_case
>>> from exubrush.simulation import simulate
>>> results = simulate(orthogonal_case())          # doctest: +SKIP
>>> results.save("results/orthogonal")              # doctest: +SKIP
"""

from __future__ import annotations

import platform
import time

import exudyn as exu
import numpy as np
from tqdm import tqdm

import exubrush
from exubrush.parameters.case import Case
from exubrush.parameters.fields import to_plain
from exubrush.results import Results
from exubrush.scene import Scene, build_scene, prb_parameters
from exubrush.solver import dynamic_settings


class SimulationError(RuntimeError):
    """The solver stopped before the end time."""


def _sensor_history(mbs, sensor) -> np.ndarray:
    return np.asarray(mbs.GetSensorStoredData(sensor))


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


def collect(scene: Scene, wall_time: float, completed: bool, message: str = "") -> Results:
    """Read the sensors of a solved scene into :class:`Results`."""
    mbs = scene.mbs
    drive = [_sensor_history(mbs, s) for s in scene.drive_sensors]
    n = min(len(d) for d in drive)
    t = drive[0][:n, 0]
    reaction = np.column_stack([d[:n, 1] for d in drive])
    offsets = [scene.handle_offset(ti) for ti in t]
    acceleration = np.array([o[2] for o in offsets])
    # drive reaction = force of the slider on the handle, sign as the coordinate constraint's
    # multiplier; the head's force on the surface is that minus the handle's own m·a
    head_force = -reaction - scene.handle_mass * acceleration
    slide = np.array([scene.motion.sliding(ti)[0] for ti in t])
    height = scene.start_height + np.array([o[0][2] for o in offsets])
    shape_time, shape_nodes = _shapes(scene, t)
    metadata = {
        "case": scene.case.name,
        "model": scene.case.model.kind,
        "parameters": to_plain(scene.case),
        "derived": _derived(scene),
        "versions": {
            "exubrush": exubrush.__version__,
            "exudyn": exu.__version__,
            "python": platform.python_version(),
        },
        "solver_statistics": _solver_statistics(mbs),
        "wall_time_s": wall_time,
        "simulated_time_s": float(t[-1]) if n else 0.0,
        "completed": completed,
        "message": message,
        "data_origin": "exubrush model output (simulation, not measurement)",
    }
    return Results(
        time=t,
        slider_position=slide,
        normal_force=-head_force[:, 2],
        tangential_force=head_force @ scene.slide_axis,
        head_height=height,
        shape_time=shape_time,
        shape_nodes=shape_nodes,
        metadata=metadata,
    )


def _derived(scene: Scene) -> dict:
    info = {
        "bristles": len(scene.bristles),
        "contact_elements": len(scene.contacts),
        "approach_distance_mm": scene.motion.approach_distance,
        "slide_start_s": scene.motion.slide_start,
        "end_time_s": scene.motion.end_time,
    }
    if scene.case.model.kind == "prb":
        info["prb_gamma"], info["prb_stiffness_coefficient"] = prb_parameters(scene.case)
    return info


def _shapes(scene: Scene, force_time: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Bristle nodes at the shape interval, in a frame fixed to the surface [mm]."""
    stride = max(1, round(scene.case.output.shape_interval / scene.case.output.interval))
    histories = [[_sensor_history(scene.mbs, s) for s in sensors]
                 for sensors in scene.node_sensors]
    n = min(len(force_time), *(len(h) for nodes in histories for h in nodes))
    rows = np.arange(0, n, stride)
    time_points = force_time[rows]
    roots = np.array([b.root for b in scene.bristles])
    handle = np.array([scene.handle_offset(ti)[0] for ti in time_points])
    handle[:, 2] += scene.start_height
    nodes = np.empty((len(rows), len(scene.bristles), len(histories[0]) + 1, 3))
    nodes[:, :, 0, :] = handle[:, None, :] + roots[None, :, :]
    for b, bristle_nodes in enumerate(histories):
        for k, history in enumerate(bristle_nodes):
            nodes[:, b, k + 1, :] = history[rows, 1:4]
    return time_points, nodes


def simulate(case: Case, progress: bool = True) -> Results:
    """Build and solve ``case``; return its results (marked incomplete if the solver stopped)."""
    scene = build_scene(case)
    end_time = scene.motion.end_time
    settings = dynamic_settings(case.solver, end_time, case.output.interval)
    bar = tqdm(total=round(end_time, 3), unit="s", desc=f"{case.name} {case.model.kind}",
               disable=not progress, bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} s simulated "
               "[{elapsed}<{remaining}]")

    def advance_bar(mbs, t):
        if t - bar.n >= 0.01 or t >= end_time:
            bar.update(round(t, 3) - bar.n)
        return True

    scene.mbs.SetPreStepUserFunction(advance_bar)
    start = time.perf_counter()
    completed, message = True, ""
    try:
        completed = bool(scene.mbs.SolveDynamic(settings, storeSolver=True))
    except (exu.SolverError, RuntimeError) as err:
        completed, message = False, str(err)
    wall = time.perf_counter() - start
    bar.close()
    results = collect(scene, wall, completed, message)
    if completed and results.metadata["simulated_time_s"] < end_time - 1e-6:
        results.metadata["completed"] = False
    return results
