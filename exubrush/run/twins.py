"""Bristles that need no solve of their own: twins of one that is solved.

The plane is the same everywhere along itself. Two bristles alike in everything (shape,
material, frame, the height of their roots) but where their roots sit on the head, on a
head that does not turn, move relative to the plane in the same way: Exudyn would solve
the same equations in coordinates shifted along the plane. Such twins are solved once
(``solver.share_identical``, default on; exubrush.run.prepared.stand_ins finds them): the
group solved first stands in for the others, and each twin's record is its stand-in's with
the positions shifted and the moment of the shifted force added (:func:`twin_solution`).
The filaments of a tuft are twins (they share the tuft's root tilt,
exubrush.models.geometry), so the 1,480 filaments of the ``sonic`` head take 40 solves.

Twins move alike, as their equations do. Solved apart, they drift apart by the solver's
tolerance, and where a pressed filament is near a snap that drift decides which of them
snaps: the tuft's filaments then spread over different paths (docs/decisions/0022).

Each condition is necessary:

- ``surface.kind = "plane"``: a tooth row, a cylinder, a sphere or a mesh changes along
  itself;
- ``solver.partition = "per-bristle"`` and no contact between bristles: a twin must be
  alone in its system, touching nothing but the surface;
- no pose term turns the head (exubrush.world.pose.HeadPose.turns): a turn carries a shift
  along the plane out of it, or moves the twins' roots along different paths.

A head that turns about the vertical axis through its centre, and moves along the plane
in no other way (no slide, pose terms on z and rz alone, the pivot over the centre), makes
twins of its bristles turned about that axis onto each other: alike, the same distance
from the centre, their frames turned by the same angle (compared to nine decimals). The
round `oscillating-rotating` head, whose roots tilt away from the centre
(``head.tilt_pattern = "radial"``), has 69 systems to solve for its 703 filaments. A
turned twin's rotation coordinates are not its stand-in's turned, so a run that keeps
coordinates (``output.solution_file``) has no turned twins.

Gravity is uniform, the contact law and friction depend only on the tip's height above the
plane and its velocities, and the handle of each group is the same, so nothing else tells
twins apart. A test solves twins both ways (tests/integration/test_twins.py).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from exubrush.run.solution import GroupSolution, SolverStatistics


def twin_solution(source: GroupSolution, shift: np.ndarray, acceleration: np.ndarray,
                  turn: float = 0.0) -> GroupSolution:
    """The record of a twin whose root lies ``shift`` [mm] from ``source``'s along the plane,
    or turned by ``turn`` [rad] about the head's centre (then ``shift`` is zero).

    Shifted: forces, tip forces and coordinates (displacements from each body's reference
    position) are the source's; tips and nodes move by ``shift``. The bristle's loads on
    the handle act ``shift`` further along, so the head's moment about the handle's node
    gains shift × f, f = −reaction − m a the twin's force on the surface
    (exubrush.world.kinematics.head_force); as the head does not turn, its moment is −λ of
    the drive's rotation coordinates (exubrush.world.kinematics.head_moment), so λ loses
    shift × f.

    Turned by R about the vertical axis through the handle's node: tips and nodes turn
    about it; the twin's force on the surface is R f, so its reaction is R (reaction + m a)
    − m a; the moment of the turned loads about a point on the axis is R times the
    source's, and as the head turns about z alone (G = I, its own inertia's moment along z,
    which R keeps), λ turns with it; tip forces in the head frame turn by R too (turns
    about z commute). No coordinates are kept (exubrush.run.prepared.stand_ins).

    ``acceleration`` is the handle's (n, 3) [mm/s²] at the source's times (at least).
    Nothing was solved for the twin: its statistics and wall time are zero.
    """
    moment = source.drive_moment
    inertia = source.handle_mass * acceleration[:len(source.time)]
    if turn == 0.0:
        if moment is not None:
            moment = moment - np.cross(shift, -source.reaction - inertia)
        return dataclasses.replace(source, tips=source.tips + shift,
                                   nodes=source.nodes + shift, drive_moment=moment,
                                   statistics=SolverStatistics(), wall_time=0.0)
    c, s = np.cos(turn), np.sin(turn)
    rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return dataclasses.replace(
        source, tips=source.tips @ rotation.T, nodes=source.nodes @ rotation.T,
        reaction=(source.reaction + inertia) @ rotation.T - inertia,
        drive_moment=None if moment is None else moment @ rotation.T,
        tip_force=source.tip_force @ rotation.T, coordinates=None,
        statistics=SolverStatistics(), wall_time=0.0)


def with_twins(prepared, solutions: Sequence[GroupSolution | None],
               acceleration: np.ndarray) -> list[GroupSolution | None]:
    """``solutions`` (one per group, None where not solved) with each twin's record made
    from its stand-in's (None while the stand-in has none); ``acceleration`` is the
    handle's (n, 3) [mm/s²] on the longest of their time grids."""
    sources = prepared.stand_ins
    complete = list(solutions)
    for index, stand_in in enumerate(sources):
        source = solutions[stand_in]
        if stand_in != index and source is not None:
            turn = prepared.stand_in_turns[index]
            root = prepared.bristles[prepared.groups[index][0]].root
            shift = (np.zeros(3) if turn else
                     root - prepared.bristles[prepared.groups[stand_in][0]].root)
            complete[index] = twin_solution(source, shift, acceleration, turn)
    return complete
