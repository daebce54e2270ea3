"""A saved run's files read back and checked against its run record, without the
:class:`~exubrush.output.results.Results` class that holds them.

:func:`read_metadata` and :func:`read_records` read run.json and the arrays; the checks
(:func:`check_records`) hold every array read to what run.json says the run was before
anything else is done with it.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exubrush.parameters.fields import MAGNITUDE
from exubrush.run.solution_files import HANDLE_COORDINATES
from exubrush.util.files import read_npz
from exubrush.util.tables import check_time_axis, read_unit_table

CSV_COLUMNS = (
    ("time", "s"),
    ("slider_position", "mm"),
    ("travelled_distance", "mm"),
    ("normal_force", "N"),
    ("tangential_force", "N"),
    ("friction_coefficient", "-"),
    ("head_height", "mm"),
)

# the head's wrench (HeadWrench), after CSV_COLUMNS: force [N] and moment about the head
# frame's origin [N*mm] of the head on the surface, in the surface frame's axes, then in
# the turned head frame's
WRENCH_COLUMNS = tuple(
    (f"{prefix}{quantity}_{axis}", unit)
    for prefix in ("", "head_") for quantity, unit in (("force", "N"), ("moment", "N*mm"))
    for axis in "xyz")

# the series forces.csv holds that are no function of others, time first
SERIES = ("time", "slider_position", "normal_force", "tangential_force", "head_height")


class ResultsError(ValueError):
    """A result directory is missing, incomplete or not written by exubrush."""


# what to do about a result file that cannot be read back
REMAKE = "; the result directory is damaged: make the run again (exubrush run with --overwrite)"


def read_metadata(directory: Path) -> dict:
    """run.json of ``directory``, which must also hold forces.csv (ResultsError if not)."""
    meta_path = directory / "run.json"
    if not meta_path.is_file():
        raise ResultsError(f"{str(directory)!r} holds no run.json: it is not an exubrush "
                           "result directory (make one with 'exubrush run CASE --out DIR')")
    try:
        metadata = json.loads(meta_path.read_bytes().decode("utf-8"))
    except json.JSONDecodeError as err:
        raise ResultsError(f"{str(meta_path)!r} is not valid JSON ({err})") from None
    except UnicodeDecodeError as err:
        raise ResultsError(f"{str(meta_path)!r} is not UTF-8 text (byte {err.start}): not "
                           "written by exubrush") from None
    if not isinstance(metadata, dict):
        raise ResultsError(f"{str(meta_path)!r} holds a JSON {type(metadata).__name__}, not "
                           "the object exubrush writes: not a run record of exubrush")
    if not (directory / "forces.csv").is_file():
        raise ResultsError(f"{str(directory)!r} has no forces.csv (run status "
                           f"{metadata.get('status', 'unknown')!r}): nothing to read")
    return metadata


def read_records(directory: Path) -> tuple[dict, dict, dict | None]:
    """forces.csv's columns by name (the wrench's among them if it has them), shapes.npz's
    arrays (empty ones if there is no such file) and tips.npz's (None: no such file);
    ResultsError naming a file that cannot be read."""
    units = {**{name: unit for name, unit in CSV_COLUMNS if name in SERIES},
             **dict(WRENCH_COLUMNS)}
    try:
        series = read_unit_table(directory / "forces.csv", units, "result file",
                                 optional=tuple(name for name, _ in WRENCH_COLUMNS))
        shapes = _read_arrays(directory / "shapes.npz", {"time": 1, "nodes": 4},
                              {"coordinates": 2})
        tips = _read_arrays(directory / "tips.npz", {"position": 3, "force": 3})
    except ValueError as err:
        raise ResultsError(f"{err}{REMAKE}") from None
    if shapes is None:
        shapes = {"time": np.zeros(0), "nodes": np.zeros((0, 0, 0, 3))}
    return series, shapes, tips


def check_records(results, directory: Path) -> None:
    """ResultsError naming the file unless every array of ``results`` (read from
    ``directory``) fits what run.json says the run was (:class:`_Claims`): forces.csv
    finite at strictly increasing times; shapes.npz with the shape samples of those times
    (output.shape_interval), the head's bristles and the model's nodes, and, where the run
    kept them (output.solution_file), rows of the head's coordinates at the shape samples;
    tips.npz with every time and bristle. (Finite 64-bit floats within 1e20 in the .npz
    files: files.read_npz.) The sizes are compared before any work that grows with them: a
    run.json may claim any head."""
    wrench = results.wrench
    series = [getattr(results, name) for name in SERIES]  # time first
    if wrench is not None:
        series += [wrench.force, wrench.moment, wrench.head_force, wrench.head_moment]
    forces = str(directory / "forces.csv")
    try:
        check_time_axis(*series)
    except ValueError as err:
        raise ResultsError(f"{forces!r}: {err}{REMAKE}") from None
    if max(float(np.max(np.abs(values))) for values in series) > MAGNITUDE[1]:
        raise ResultsError(f"{forces!r}: holds a value beyond {MAGNITUDE[1]:g}, which "
                           f"exubrush never writes{REMAKE}")
    claims = _Claims.of(results, directory)
    if (directory / "shapes.npz").is_file():
        _check_shapes(results, directory / "shapes.npz", claims)
    tips, steps = results.tip_position, results.time.size
    if tips is not None and not (tips.shape == results.tip_force.shape
                                 and _fits(tips.shape, (steps, claims.bristles, 3))):
        raise ResultsError(f"{str(directory / 'tips.npz')!r}: its arrays {tips.shape} and "
                           f"{results.tip_force.shape} do not fit the {steps} times of "
                           f"forces.csv and the run's {claims.bristles} bristles: the file is "
                           "damaged or of another run")


@dataclass(frozen=True)
class _Claims:
    """What run.json says the saved arrays hold (None: not claimed, by results saved from
    Python without parameters): bristles, points of each (root included), shape samples
    among forces.csv's times (every ``stride``-th), whether node coordinates were kept and
    the columns of their rows."""

    bristles: int | None = None
    points: int | None = None
    samples: int | None = None
    stride: int | None = None
    kept: bool = False
    columns: int | None = None

    @classmethod
    def of(cls, results, directory: Path) -> _Claims:
        if "parameters" not in results.metadata:
            return cls()
        try:
            case = results.case()
        except ResultsError as err:
            raise ResultsError(f"{str(directory / 'run.json')!r}: {err}") from None
        bristles, output = case.head.count, case.output
        return cls(bristles, case.model.shape_nodes + 1,
                   output.shape_samples(results.time.size), output.shape_stride,
                   output.solution_file,
                   1 + HANDLE_COORDINATES + bristles * case.model.bristle_coordinates)


def _check_shapes(results, path: Path, claims: _Claims) -> None:
    """shapes.npz against forces.csv and run.json (see :func:`check_records`)."""
    name, nodes, times = str(path), results.shape_nodes, results.shape_time
    if not _fits(nodes.shape, (None, claims.bristles, claims.points, 3)):
        raise ResultsError(f"{name!r}: holds nodes {nodes.shape}, but its run (run.json) has "
                           f"{claims.bristles} bristles of {claims.points} nodes{REMAKE}")
    if not _fits((times.size, len(nodes)), (claims.samples or len(nodes),) * 2):
        raise ResultsError(f"{name!r}: holds {times.size} times and {len(nodes)} shapes, but "
                           f"the {results.time.size} times of forces.csv make "
                           f"{claims.samples} shape samples (output.shape_interval){REMAKE}")
    try:
        check_time_axis(times)
    except ValueError as err:
        raise ResultsError(f"{name!r}: {err}{REMAKE}") from None
    # forces.csv holds 9 significant digits: its times are within 5e-9 of the shapes'
    if claims.stride is not None and not np.allclose(times, results.time[::claims.stride],
                                                     rtol=1e-8, atol=0.0):
        raise ResultsError(f"{name!r}: its times are not every {claims.stride}th time of "
                           f"forces.csv (output.shape_interval){REMAKE}")
    coordinates = results.shape_coordinates
    if coordinates is None:
        if claims.kept:
            raise ResultsError(f"{name!r} lacks the node coordinates its run kept "
                               f"(output.solution_file){REMAKE}")
        return
    # a row per shape sample; a run that did not complete may end a sample early (the rows
    # kept of its shortest group, exubrush.run.solve)
    least = times.size if results.metadata.get("status") == "completed" else 1
    if not (least <= len(coordinates) <= times.size and coordinates.shape[1] >= 2
            and _fits(coordinates.shape[1:], (claims.columns,))):
        raise ResultsError(f"{name!r}: its node coordinates {coordinates.shape} are not rows "
                           f"of {claims.columns or 'time and'} coordinates at its "
                           f"{times.size} times{REMAKE}")
    # both are multiples of output.interval computed apart: equal to rounding (1e-16)
    if not np.allclose(coordinates[:, 0], times[:len(coordinates)], rtol=1e-9, atol=1e-12):
        raise ResultsError(f"{name!r}: its node coordinates are not at its shapes' "
                           f"times{REMAKE}")


def _fits(shape: tuple, expected: tuple) -> bool:
    """Whether ``shape`` is ``expected``, whose None entries fit any size."""
    return len(shape) == len(expected) and all(
        e is None or s == e for s, e in zip(shape, expected, strict=True))


def _read_arrays(path: Path, required, optional=None) -> dict[str, np.ndarray] | None:
    """The arrays of a result's .npz file (files.read_npz), None if there is no such file;
    no value beyond the magnitudes exubrush computes with (parameters.fields.MAGNITUDE)."""
    return read_npz(path, required, optional, MAGNITUDE[1]) if path.is_file() else None
