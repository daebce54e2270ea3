"""A finished run in Exudyn's SolutionViewer: the whole head, drawn, replayed from the node
coordinates the run kept (case parameter ``output.solution_file = true``, or
``exubrush run --viewer``).

The groups' rows are joined into the head as one system (exubrush.run.solution_files); the
system ``exubrush view`` builds is the whole head with graphics, and :func:`viewer_scene`
checks its size against the rows before anything is shown.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

import numpy as np

from exubrush.output.results import Results, ResultsError, read_results
from exubrush.run.solution_files import SOLUTION_FILE, write_solution_file


def viewer_scene(results: Results):
    """The run's head as one Exudyn system with graphics, checked against its coordinates."""
    from exubrush.parameters.fields import ParameterError
    from exubrush.run.prepared import prepare
    from exubrush.run.scene import build_scene

    try:
        prepared = prepare(results.case())
    except ParameterError as err:  # e.g. the run's slide CSV is gone
        raise ResultsError(f"the run's head cannot be rebuilt: {err}") from None
    scene = build_scene(prepared, drawn=True)
    size = scene.mbs.systemData.ODE2Size()
    stored = results.shape_coordinates.shape[1] - 1
    if size != stored:
        raise ResultsError(f"the run's shapes.npz holds {stored} node coordinates per row "
                           f"but its head has {size}: was it made by another exubrush "
                           "version?")
    return scene


def prepare(directory: str | Path) -> tuple[Results, Any, Path]:
    """Read a run that kept its coordinates, build its head (:func:`viewer_scene`, which
    refuses coordinates that do not fit it), and only then write its Exudyn solution file
    beside it: a refused run gets no file. Returns the results, the scene and the file."""
    results = read_results(directory)
    if results.shape_coordinates is None:
        raise ResultsError(f"{str(directory)!r} kept no node coordinates: run the case again "
                           "with --viewer (or --set output.solution_file=true)")
    scene = viewer_scene(results)
    path = Path(directory) / SOLUTION_FILE
    write_solution_file(path, results.shape_coordinates, str(directory))
    return results, scene, path


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
