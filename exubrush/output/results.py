"""Results of a brushing run: unit-labelled time series, the case they came from and the
metrics derived from them. Writing them is exubrush.output.result_files, reading a saved
run back and checking it exubrush.output.saved_run, the plots exubrush.output.plotting.

Sign conventions (what load cells between slider and head read, with the head's own
inertia removed): ``normal_force`` is positive when the head presses on the surface;
``tangential_force`` is the force the head exerts on the surface along the +slide axis
(positive while the head moves forward and drags its bristles); ``friction_coefficient`` is
|F_t| / F_n, left empty where F_n is below 1 µN (no contact: the ratio is undefined).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from exubrush.models.geometry import head_bristles
from exubrush.output.cleaning import TipContacts, cleaning_summary, touching_geometry
from exubrush.output.metrics import friction_coefficient, travelled_distance
from exubrush.output.result_files import RESULT_FILES, write_results
from exubrush.output.saved_run import (
    CSV_COLUMNS,
    REMAKE,
    WRENCH_COLUMNS,
    ResultsError,
    check_records,
    read_metadata,
    read_records,
)
from exubrush.output.tufts import tuft_columns, tuft_forces
from exubrush.output.vibration import vibration_summary
from exubrush.parameters.case import Case
from exubrush.parameters.fields import ParameterError, build
from exubrush.parameters.surface_kinds import MESH
from exubrush.world.kinematics import SLIDE_AXES
from exubrush.world.mesh import MeshError, read_mesh

__all__ = ["CSV_COLUMNS", "REMAKE", "RESULT_FILES", "WRENCH_COLUMNS", "HeadWrench", "Results",
           "ResultsError", "read_results"]


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

    ``built_case`` is the :class:`Case` the run solved, kept in memory where one exists (the
    results of a run just made, exubrush.output.assemble); None: :meth:`case` builds it from
    ``metadata["parameters"]`` once and keeps it (a change to that dict afterwards is not
    seen).

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
    built_case: Case | None = field(default=None, repr=False, compare=False)

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
        if surface.kind != MESH:
            return None
        return read_mesh(surface.mesh_file, surface.mesh_unit)

    def save(self, directory: str | Path) -> Path:
        """Write the run's files into ``directory``
        (exubrush.output.result_files.write_results): forces.csv, run.json, shapes.npz,
        forces.png and, with tip data, tips.npz, summary.json (cleaning metrics) and
        cleaning.png; each file complete or absent, run.json last."""
        return write_results(self, directory)

    def case(self) -> Case:
        """The parameters of the run: the case it solved where the results hold it
        (``built_case``), else built from ``metadata["parameters"]`` once and kept.

        Raises
        ------
        ResultsError
            If they do not make a valid case of this exubrush version.
        """
        if self.built_case is None:
            self.built_case = self._case_of_record()
        return self.built_case

    def _case_of_record(self) -> Case:
        try:
            return build(Case, self.metadata["parameters"])
        except (KeyError, ParameterError) as err:
            versions = self.metadata.get("versions")
            made_by = (versions.get("exubrush", "an unknown version")
                       if isinstance(versions, dict) else "an unknown version")
            raise ResultsError(f"the run's parameters (run.json) are not a valid case for this "
                               f"exubrush (the run was made by exubrush {made_by}): {err}"
                               ) from None


def read_results(directory: str | Path) -> Results:
    """Read a result directory written by :meth:`Results.save` (forces, shapes, run.json).

    Every array read is checked against what run.json says the run was
    (exubrush.output.saved_run.check_records) before anything else is done with it; the
    run's case is built from run.json once there and kept (:meth:`Results.case`).

    Raises
    ------
    ResultsError
        If the directory or one of its files is missing, unreadable or does not fit the run
        (one line naming the file and saying how the directory is made).
    """
    directory = Path(directory)
    metadata = read_metadata(directory)
    series, shapes, tips = read_records(directory)
    wrench = HeadWrench.from_columns(series)
    for name, _ in WRENCH_COLUMNS:  # some but not all of them: not exubrush's file
        if series.pop(name, None) is not None:
            raise ResultsError(f"{str(directory / 'forces.csv')!r} has some of the head's "
                               f"force and moment columns but not all{REMAKE}")
    results = Results(**series, wrench=wrench, shape_time=shapes["time"],
                      shape_nodes=shapes["nodes"], shape_coordinates=shapes.get("coordinates"),
                      tip_position=None if tips is None else tips["position"],
                      tip_force=None if tips is None else tips["force"], metadata=metadata)
    check_records(results, directory)
    return results
