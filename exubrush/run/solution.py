"""What solving one bristle group gives back: typed, picklable, free of Exudyn.

The executor moves these records between processes (or cluster workers), the run directory
stores them as checkpoints and the assembly turns them into results; none of those needs
Exudyn, so this module does not import it (exubrush.run.solve makes them).
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass

import numpy as np

INTERRUPTED = "interrupted"  # the message of a solve stopped on request (Ctrl-C, SIGTERM)


@dataclass(frozen=True)
class SolverStatistics:
    """Counters of Exudyn's dynamic solver for one or more systems."""

    steps: int = 0
    newton_iterations: int = 0
    jacobian_updates: int = 0
    rejected_modified_newton_steps: int = 0
    # Newton updates that the line search shortened, step attempts it gave up
    # (exubrush.run.newton)
    shortened_updates: int = 0
    given_up_attempts: int = 0

    def __add__(self, other: SolverStatistics) -> SolverStatistics:
        return SolverStatistics(*(a + b for a, b in zip(dataclasses.astuple(self),
                                                        dataclasses.astuple(other), strict=True)))


@dataclass(frozen=True)
class GroupSolution:
    """The outcome of solving one bristle group, on the case's output grid.

    Attributes
    ----------
    time : ndarray (n,)
        Multiples of ``output.interval`` up to the last sane record [s].
    reaction : ndarray (n, 3)
        Drive reaction: the force the handle's coordinates exert on the drive [N].
    tips : ndarray (n, bristles, 3)
        Each bristle's last node (its tip sphere's centre), head frame fixed to the
        surface [mm].
    nodes : ndarray (m, bristles, nodes, 3)
        Bristle node positions at the shape samples, every ``output.shape_stride``-th time
        from the first (m = ceil(n / stride)), head frame fixed to the surface [mm]: only
        the tips are kept at every time (a sonic head's forces need a fine output
        interval, which every node's history would make gigabytes).
    tip_force : ndarray (n, bristles, 3)
        Contact force of the surface on each tip, head frame [N] (zero for a tip without a
        contact element).
    coordinates : ndarray (m, 1 + coordinates) or None
        Rows (time [s], ODE2 coordinates) at ``output.shape_interval``, if the case keeps
        them (``output.solution_file``).
    statistics : SolverStatistics
        Exudyn's step, Newton and Jacobian counts.
    completed : bool
        Whether the solve reached the end time.
    message : str
        Why it stopped early ("" if it completed).
    wall_time : float
        Wall time of Exudyn's solve [s].
    contacts : int
        Contact elements in the system.
    handle_mass : float
        Mass of the group's handle [t].
    bristle_contacts_max, bristle_contacts_mean : float
        Touching capsule pairs between the group's bristles, most and mean over the output
        samples (0 without contact between bristles).
    bristle_overlap_max : float
        Deepest overlap of two bristles seen at an output sample [mm].
    drive_moment : ndarray (n, 3) or None
        The drive's reaction on the handle's Tait-Bryan angles [N·mm]
        (exubrush.world.kinematics.head_moment); None where a group file lacks it.
    handle_inertia : list
        The handle's inertia about its centre, body frame, as nested lists [t·mm²].
    retried : bool
        Whether the group failed and was solved a second time with a full Newton
        (exubrush.run.solve.solve_group).
    """

    time: np.ndarray
    reaction: np.ndarray
    tips: np.ndarray
    nodes: np.ndarray
    tip_force: np.ndarray
    coordinates: np.ndarray | None
    statistics: SolverStatistics
    completed: bool
    message: str
    wall_time: float
    contacts: int
    handle_mass: float
    bristle_contacts_max: float = 0.0
    bristle_contacts_mean: float = 0.0
    bristle_overlap_max: float = 0.0
    drive_moment: np.ndarray | None = None
    handle_inertia: list = dataclasses.field(default_factory=lambda: [[0.0] * 3] * 3)
    retried: bool = False

    ARRAYS = ("time", "reaction", "tips", "nodes", "tip_force", "coordinates",
              "drive_moment")

    @property
    def interrupted(self) -> bool:
        """Whether the solve was stopped on request (not by a fault) before its end."""
        return not self.completed and self.message == INTERRUPTED

    def to_arrays(self) -> dict[str, np.ndarray]:
        """Plain arrays for ``np.savez`` (the scalars as one JSON text), read back by
        :meth:`from_arrays`."""
        scalars = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                   if f.name not in self.ARRAYS}
        scalars["statistics"] = dataclasses.asdict(self.statistics)
        arrays = {name: getattr(self, name) for name in self.ARRAYS
                  if getattr(self, name) is not None}
        return {"scalars": np.array(json.dumps(scalars)), **arrays}

    @classmethod
    def not_solved(cls, message: str) -> GroupSolution:
        """A group that produced nothing (e.g. every worker that ran it died), and why."""
        return cls(time=np.zeros(0), reaction=np.zeros((0, 3)), tips=np.zeros((0, 0, 3)),
                   nodes=np.zeros((0, 0, 0, 3)), tip_force=np.zeros((0, 0, 3)), coordinates=None,
                   statistics=SolverStatistics(), completed=False, message=message,
                   wall_time=0.0, contacts=0, handle_mass=0.0)

    @classmethod
    def from_arrays(cls, data) -> GroupSolution:
        """Inverse of :meth:`to_arrays` (``data``: a mapping such as an open ``.npz``)."""
        scalars = json.loads(str(data["scalars"]))
        scalars["statistics"] = SolverStatistics(**scalars["statistics"])
        arrays = {name: (data[name] if name in data else None) for name in cls.ARRAYS}
        return cls(**arrays, **scalars)
