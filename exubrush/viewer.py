"""A finished run in Exudyn's SolutionViewer: the whole head, drawn, replayed from the node
coordinates the run kept (case parameter ``output.solution_file = "yes"``, or
``exubrush run --viewer``).

Every bristle is solved as its own Exudyn system (exubrush.simulation), each with a copy
of the handle. Their solution rows are joined into the coordinates of the whole head as
one system: the handle's coordinates once, then each bristle's in order. That is the
order of the system ``exubrush view`` builds (the coupled scene, with graphics), and
:func:`viewer_scene` checks the size before anything is shown.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

from exubrush.results import Results, ResultsError, atomic_file, read_results

HANDLE_COORDINATES = 6  # the handle's node (RotationRxyz) is the first node of every system
SOLUTION_FILE = "exudyn-solution.txt"


def read_coordinate_file(path: str | Path) -> np.ndarray:
    """Rows of an Exudyn text solution file holding ODE2 coordinates only, time first (any
    number of rows, none included: a solve may stop early)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # numpy's "empty input file"
        return np.loadtxt(path, comments="#", delimiter=",", ndmin=2)


def head_coordinates(groups: list[np.ndarray]) -> np.ndarray:
    """Join the solution rows of the groups (in bristle order) into rows of the whole head.

    Each group's rows are (time, handle coordinates, its bristles' coordinates). Rows are
    matched by index, up to the shortest group, and must be at the same times (every group
    writes at the same multiples of the shape interval).
    """
    rows = min(len(g) for g in groups)
    times = np.array([g[:rows, 0] for g in groups])
    if rows and np.max(np.abs(times - times[0])) > 1e-9:
        raise ValueError("the groups' solution rows are not at the same times; the head's "
                         "coordinates cannot be joined")
    skip = 1 + HANDLE_COORDINATES
    return np.hstack([groups[0][:rows], *(g[:rows, skip:] for g in groups[1:])])


def write_solution_file(path: Path, coordinates: np.ndarray, source: str) -> None:
    """Write rows (time, ODE2 coordinates) in Exudyn's text solution-file format."""
    count = coordinates.shape[1] - 1
    header = [
        "#Exudyn solution file (ODE2 coordinates only; Exudyn reads the counts on line 5)",
        f"#written by exubrush from {source} (model output)",
        "#columns contain: time, ODE2 displacements",
        f"#number of system coordinates [nODE2, nODE1, nAlgebraic, nData] = [{count},0,0,0]",
        "#number of written coordinates [nODE2, nVel2, nAcc2, nODE1, nVel1, nAlgebraic, "
        f"nData] = [{count},0,0,0,0,0,0]",
        f"#total columns exported  (excl. time) = {count}",
        f"#number of time steps = {len(coordinates)}",
        "#",
    ]
    with atomic_file(path, "w") as handle:
        handle.write("\n".join(header) + "\n")
        np.savetxt(handle, coordinates, delimiter=",", fmt="%.12g")


def viewer_scene(results: Results):
    """The run's head as one Exudyn system with graphics, checked against its coordinates."""
    from exubrush.parameters.case import Case
    from exubrush.parameters.fields import build
    from exubrush.scene import build_scene

    scene = build_scene(build(Case, results.metadata["parameters"]), drawn=True)
    size = scene.mbs.systemData.ODE2Size()
    stored = results.shape_coordinates.shape[1] - 1
    if size != stored:
        raise ResultsError(f"the run kept {stored} coordinates per row but its head has "
                           f"{size}: was it made by another exubrush version?")
    return scene


def prepare(directory: str | Path) -> tuple[Results, Path]:
    """Read a run that kept its coordinates and write its Exudyn solution file beside it."""
    results = read_results(directory)
    if results.shape_coordinates is None:
        raise ResultsError(f"{str(directory)!r} kept no node coordinates: run the case again "
                           "with --viewer (or --set output.solution_file=yes)")
    path = Path(directory) / SOLUTION_FILE
    write_solution_file(path, results.shape_coordinates, str(directory))
    return results, path


def has_display() -> bool:
    """Whether a window can open: Windows and macOS always, Linux with an X or Wayland
    display."""
    if sys.platform in ("win32", "darwin"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def open_viewer(scene, solution_path: Path) -> None:
    """Open Exudyn's renderer and SolutionViewer on ``scene`` (from :func:`viewer_scene`)
    replaying ``solution_path``; returns when the window is closed."""
    from exudyn.rigidBodyUtilities import RotationMatrixX
    from exudyn.utilities import LoadSolutionFile

    solution = LoadSolutionFile(str(solution_path), verbose=False)
    container = scene.system_container
    # looking at the head from the side, slightly from above, z up (turn it with the mouse)
    container.visualizationSettings.openGL.initialModelRotation = (
        RotationMatrixX(np.radians(70.0)).tolist())
    container.renderer.Start()
    try:
        scene.mbs.SolutionViewer(solution, runOnStart=True, runMode=0,
                                 title=f"exubrush: {solution_path.parent.name}")
    finally:
        container.renderer.Stop()
