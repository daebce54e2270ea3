"""Exudyn's text solution-file format: reading the rows a solve writes, joining the groups'
rows into the whole head, writing the file Exudyn's SolutionViewer reads.

Every bristle group is solved as its own Exudyn system, each with a copy of the handle.
Their rows are joined into the coordinates of the whole head as one system: the handle's
coordinates once, then each bristle's in order. That is the order of the system
``exubrush view`` builds (exubrush.output.viewer).
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from exubrush.util.files import atomic_file

HANDLE_COORDINATES = 6  # the handle's node (RotationRxyz) is the first node of every system
SOLUTION_FILE = "exudyn-solution.txt"


def read_coordinate_file(path: str | Path) -> np.ndarray:
    """Rows of an Exudyn text solution file holding ODE2 coordinates only, time first (any
    number of rows, none included: a solve may stop early)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # numpy's "empty input file"
        return np.loadtxt(path, comments="#", delimiter=",", ndmin=2)


def head_coordinates(groups: list[np.ndarray], order: np.ndarray) -> np.ndarray:
    """Join the solution rows of the groups into rows of the whole head, the bristles'
    coordinates in the head's order.

    Each group's rows are (time, handle coordinates, its bristles' coordinates, the same
    number for every bristle). ``order[k]`` is the position, among the groups' bristles
    joined in group order, of the head's bristle k. Rows are matched by index, up to the
    shortest group, and must be at the same times (every group writes at the same
    multiples of the shape interval).
    """
    rows = min(len(g) for g in groups)
    times = np.array([g[:rows, 0] for g in groups])
    if rows and np.max(np.abs(times - times[0])) > 1e-9:
        raise ValueError("the groups' solution rows are not at the same times; the head's "
                         "coordinates cannot be joined")
    skip = 1 + HANDLE_COORDINATES
    bristles = np.hstack([g[:rows, skip:] for g in groups])
    per_bristle = bristles.shape[1] // len(order)
    blocks = bristles.reshape(rows, len(order), per_bristle)[:, order]
    return np.hstack([groups[0][:rows, :skip], blocks.reshape(rows, -1)])


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
