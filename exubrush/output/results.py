"""Results of a brushing run: unit-labelled time series, files on disk, the force plot.

Sign conventions (what load cells between slider and head read, with the head's own
inertia removed): ``normal_force`` is positive when the head presses on the surface;
``tangential_force`` is the force the head exerts on the surface along the +slide axis
(positive while the head moves forward and drags its bristles); ``friction_coefficient`` is
|F_t| / F_n, left empty where F_n is below 1 µN (no contact: the ratio is undefined).
"""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from exubrush.models.geometry import head_bristles
from exubrush.output.cleaning import TipContacts, cleaning_summary, part_names, touching_geometry
from exubrush.output.metrics import friction_coefficient, travelled_distance
from exubrush.output.tufts import tuft_columns, tuft_forces
from exubrush.output.vibration import vibration_summary
from exubrush.parameters.case import Case
from exubrush.parameters.fields import MAGNITUDE, ParameterError, build
from exubrush.run.solution_files import HANDLE_COORDINATES
from exubrush.util.files import atomic_file, read_npz, write_csv
from exubrush.world.kinematics import SLIDE_AXES
from exubrush.world.mesh import MeshError, read_mesh

RESULT_FILES = ("forces.csv", "shapes.npz", "forces.png", "tips.npz", "summary.json",
                "cleaning.png", "vibration.png", "tufts.csv")
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


@dataclass(frozen=True)
class HeadWrench:
    """Force [N] and moment [N·mm] of the head on the surface, each (n, 3): the moment about
    the head frame's origin (the roots' surface at the head's centre, which the handle's
    node carries), in the surface frame's axes (``force``, ``moment``) and in the head
    frame's axes as the head turns (``head_force``, ``head_moment``; the same without pose
    terms that turn it)."""

    force: np.ndarray
    moment: np.ndarray
    head_force: np.ndarray
    head_moment: np.ndarray

    def columns(self) -> dict[str, np.ndarray]:
        """The twelve columns of :data:`WRENCH_COLUMNS` by name."""
        stacked = np.column_stack([self.force, self.moment, self.head_force, self.head_moment])
        return {name: stacked[:, k] for k, (name, _) in enumerate(WRENCH_COLUMNS)}

    @classmethod
    def from_columns(cls, series: dict[str, np.ndarray]) -> HeadWrench | None:
        """The wrench of columns read back by name, None if the file has none of them
        (a run of exubrush 0.13.0 or older)."""
        if not all(name in series for name, _ in WRENCH_COLUMNS):
            return None
        stacked = np.column_stack([series.pop(name) for name, _ in WRENCH_COLUMNS])
        return cls(*(stacked[:, 3 * k:3 * k + 3] for k in range(4)))


@dataclass
class Results:
    """Time series of one run (units in :data:`CSV_COLUMNS`) plus metadata.

    ``shapes`` holds the bristle centreline nodes: ``shape_time`` [s] of shape (n_t,) and
    ``shape_nodes`` [mm] of shape (n_t, n_bristles, n_nodes + 1, 3), root first, head frame
    fixed to the surface. ``shape_coordinates``, kept only if the run was asked to
    (``output.solution_file = true``), holds rows (time [s], the head's ODE2 coordinates [mm, rad
    or Euler parameters]) at the shape interval, for Exudyn's SolutionViewer
    (exubrush.output.viewer).

    ``tip_position`` [mm] and ``tip_force`` [N], each (n_t, n_bristles, 3) on ``time``, are
    every tip-sphere centre and the surface's contact force on it, head frame fixed to the
    surface: what the cleaning metrics (exubrush.output.cleaning) are computed from.
    """

    time: np.ndarray
    slider_position: np.ndarray
    normal_force: np.ndarray
    tangential_force: np.ndarray
    head_height: np.ndarray
    shape_time: np.ndarray
    shape_nodes: np.ndarray
    shape_coordinates: np.ndarray | None = None
    tip_position: np.ndarray | None = None
    tip_force: np.ndarray | None = None
    metadata: dict = field(default_factory=dict)
    wrench: HeadWrench | None = None

    @property
    def travelled_distance(self) -> np.ndarray:
        """Cumulative slide path Σ|Δs| [mm]."""
        return travelled_distance(self.slider_position)

    @property
    def friction_coefficient(self) -> np.ndarray:
        """|F_t| / F_n [-], NaN where F_n < 1 µN (undefined; written as an empty cell)."""
        return friction_coefficient(self.normal_force, self.tangential_force)

    def columns(self) -> dict[str, np.ndarray]:
        """All CSV columns by their header (name [unit])."""
        values = {
            "time": self.time,
            "slider_position": self.slider_position,
            "travelled_distance": self.travelled_distance,
            "normal_force": self.normal_force,
            "tangential_force": self.tangential_force,
            "friction_coefficient": self.friction_coefficient,
            "head_height": self.head_height,
        }
        written = CSV_COLUMNS
        if self.wrench is not None:
            values.update(self.wrench.columns())
            written = (*CSV_COLUMNS, *WRENCH_COLUMNS)
        return {f"{name} [{unit}]": values[name] for name, unit in written}

    @functools.cached_property
    def tip_contacts(self) -> TipContacts | None:
        """Where each tip touched the surface (exubrush.output.cleaning.touching_geometry),
        computed once; None without tip data or when the run's mesh file is gone."""
        if self.tip_position is None or self.tip_force is None or len(self.time) == 0:
            return None
        case = self.case()
        try:
            mesh = self.surface_mesh()
        except MeshError:  # the run's mesh file is gone or changed: no metrics
            return None
        return touching_geometry(case.surface, self.tip_position, self.tip_force,
                                 self._tip_radii(case), mesh)

    @functools.cached_property
    def _cleaning_summary(self) -> dict | None:
        contacts = self.tip_contacts
        if contacts is None:
            return None
        case = self.case()
        return cleaning_summary(case.surface, self.time, self.slider_position,
                                self.tip_position, self.tip_force, self._tip_radii(case),
                                contacts=contacts)

    def vibration(self) -> tuple[list[dict], list]:
        """The tips' amplitude against the head's for each sine pose term of the run
        (exubrush.output.vibration.vibration_summary), and every tip's amplitude per term;
        empty without such terms or tip data."""
        case = self.case()
        if not case.motion.sine or self.tip_position is None or len(self.time) == 0:
            return [], []
        axis = SLIDE_AXES[case.motion.direction]
        pivot_track = (np.asarray(case.motion.pivot) + self.head_height[:, None] * [0, 0, 1]
                       + self.slider_position[:, None] * axis)
        start = self.metadata.get("derived", {}).get("slide_start_s", 0.0)
        return vibration_summary(case, start, self.time, self.tip_position, pivot_track)

    def tuft_columns(self) -> dict[str, np.ndarray]:
        """tufts.csv's columns (exubrush.output.tufts): each tuft's force on the surface
        [N], surface frame; empty unless the head is made of tufts and tips were kept."""
        case = self.case()
        if case.head.layout != "tufts" or self.tip_force is None or len(self.time) == 0:
            return {}
        names = [t.name or f"tufts[{i}]" for i, t in enumerate(case.head.tufts)]
        forces = tuft_forces(self.tip_force, [b.tuft for b in head_bristles(case.head)],
                             len(names))
        return tuft_columns(names, self.time, forces)

    def cleaning(self) -> dict | None:
        """The cleaning metrics of the run (exubrush.output.cleaning.cleaning_summary), computed
        once; None without tip data or when the run's mesh file is gone."""
        return self._cleaning_summary

    @staticmethod
    def _tip_radii(case: Case) -> list[float]:
        return [b.tip_radius for b in head_bristles(case.head)]

    def surface_mesh(self):
        """The run's surface mesh (exubrush.world.mesh.MeshSurface) read again from its file, or
        None on an analytic surface; MeshError if the file is gone or unreadable."""
        surface = self.case().surface
        if surface.kind != "mesh":
            return None
        return read_mesh(surface.mesh_file, surface.mesh_unit)

    def save(self, directory: str | Path) -> Path:
        """Write forces.csv, run.json, shapes.npz, forces.png and, with tip data, tips.npz,
        summary.json (cleaning metrics) and cleaning.png into ``directory``.

        Each file is written to a temporary file first and renamed, so a file on disk is
        either complete or absent. Results without any time series (a run interrupted
        before every bristle started) write run.json only and remove older result files,
        so files of different runs never sit side by side. run.json is written last: its
        ``status`` describes the files beside it.
        """
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        (directory / "run.json").unlink(missing_ok=True)  # no status while files change
        if len(self.time) == 0:
            for name in RESULT_FILES:
                (directory / name).unlink(missing_ok=True)
            self._save_metadata(directory)
            return directory
        columns = self.columns()
        write_csv(directory / "forces.csv", list(columns), zip(*columns.values(), strict=True))
        with atomic_file(directory / "shapes.npz", "wb") as handle:
            extra = {} if self.shape_coordinates is None else {
                "coordinates": self.shape_coordinates}
            np.savez_compressed(handle, time=self.shape_time, nodes=self.shape_nodes, **extra)
        from exubrush.output.plotting import (  # matplotlib when drawn
            plot_cleaning,
            plot_forces,
            plot_vibration,
        )

        with atomic_file(directory / "forces.png", "wb") as handle:
            plot_forces(self, handle)
        summary, contacts = self.cleaning(), self.tip_contacts
        for name in ("tips.npz", "summary.json", "cleaning.png", "vibration.png", "tufts.csv"):
            (directory / name).unlink(missing_ok=True)
        if summary is not None:
            with atomic_file(directory / "tips.npz", "wb") as handle:
                np.savez_compressed(handle, time=self.time, position=self.tip_position,
                                    force=self.tip_force, in_contact=contacts.touching,
                                    part=np.where(contacts.touching, contacts.parts, -1),
                                    part_names=np.array(part_names(self.case().surface)))
            vibration, amplitudes = self.vibration()
            extra = {"vibration": vibration} if vibration else {}
            with atomic_file(directory / "summary.json", "w") as handle:
                json.dump({"data_origin": self.metadata.get("data_origin", ""),
                           "cleaning": summary, **extra}, handle, indent=2)
            with atomic_file(directory / "cleaning.png", "wb") as handle:
                plot_cleaning(self, summary, contacts, handle)
            tufts = self.tuft_columns()
            if tufts:
                write_csv(directory / "tufts.csv", list(tufts),
                          zip(*tufts.values(), strict=True))
            if any(a is not None for a in amplitudes):
                with atomic_file(directory / "vibration.png", "wb") as handle:
                    plot_vibration(self, vibration, amplitudes, handle)
        self._save_metadata(directory)
        return directory

    def case(self) -> Case:
        """The parameters of the run, rebuilt from ``metadata["parameters"]``.

        Raises
        ------
        ResultsError
            If they do not make a valid case of this exubrush version.
        """
        try:
            return build(Case, self.metadata["parameters"])
        except (KeyError, ParameterError) as err:
            versions = self.metadata.get("versions")
            made_by = (versions.get("exubrush", "an unknown version")
                       if isinstance(versions, dict) else "an unknown version")
            raise ResultsError(f"the run's parameters (run.json) are not a valid case for this "
                               f"exubrush (the run was made by exubrush {made_by}): {err}"
                               ) from None

    def _save_metadata(self, directory: Path) -> None:
        with atomic_file(directory / "run.json", "w") as handle:
            json.dump(self.metadata, handle, indent=2, default=_json_default)


class ResultsError(ValueError):
    """A result directory is missing, incomplete or not written by exubrush."""


# what to do about a result file that cannot be read back
REMAKE = "; the result directory is damaged: make the run again (exubrush run with --overwrite)"


def read_results(directory: str | Path) -> Results:
    """Read a result directory written by :meth:`Results.save` (forces, shapes, run.json).

    Every array read is checked against what run.json says the run was (:func:`_checked`)
    before anything else is done with it.

    Raises
    ------
    ResultsError
        If the directory or one of its files is missing, unreadable or does not fit the run
        (one line naming the file and saying how the directory is made).
    """
    from exubrush.util.tables import read_unit_table

    directory = Path(directory)
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
    units = {**{name: unit for name, unit in CSV_COLUMNS if name in _SERIES},
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
    wrench = HeadWrench.from_columns(series)
    for name, _ in WRENCH_COLUMNS:  # some but not all of them: not exubrush's file
        if series.pop(name, None) is not None:
            raise ResultsError(f"{str(directory / 'forces.csv')!r} has some of the head's "
                               f"force and moment columns but not all{REMAKE}")
    return _checked(Results(**series, wrench=wrench, shape_time=shapes["time"],
                            shape_nodes=shapes["nodes"],
                            shape_coordinates=shapes.get("coordinates"),
                            tip_position=None if tips is None else tips["position"],
                            tip_force=None if tips is None else tips["force"],
                            metadata=metadata), directory)


def _checked(results: Results, directory: Path) -> Results:
    """``results`` if every array read fits what run.json says the run was (:class:`_Claims`),
    else ResultsError naming the file: forces.csv finite at strictly increasing times;
    shapes.npz with the shape samples of those times (output.shape_interval), the head's
    bristles and the model's nodes, and, where the run kept them (output.solution_file),
    rows of the head's coordinates at the shape samples; tips.npz with every time and
    bristle. (Finite 64-bit floats within 1e20 in the .npz files: files.read_npz.) The
    sizes are compared before any work that grows with them: a run.json may claim any
    head."""
    from exubrush.util.tables import check_time_axis

    wrench = results.wrench
    series = [getattr(results, name) for name in _SERIES]  # time first
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
    return results


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
    def of(cls, results: Results, directory: Path) -> _Claims:
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


def _check_shapes(results: Results, path: Path, claims: _Claims) -> None:
    """shapes.npz against forces.csv and run.json (see :func:`_checked`)."""
    from exubrush.util.tables import check_time_axis

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


_SERIES = ("time", "slider_position", "normal_force", "tangential_force", "head_height")


def _json_default(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"cannot write {type(value).__name__} to JSON")
