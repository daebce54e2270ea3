"""Turn the group solutions of a run into its :class:`~exubrush.output.results.Results`.

The head force is the sum of the groups' forces with the handles' inertia removed
(:func:`exubrush.world.kinematics.head_force`) and, for a head with pose terms, the inertia
of the bristles' root pieces added (:func:`carried_root_pieces`); shapes gain their roots;
the run record (``Results.metadata``) says what was run, by which code, on which published
models and laws (exubrush.util.references), how it went and why it stopped.
"""

from __future__ import annotations

import functools
import platform
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from exubrush.models.geometry import imperfections
from exubrush.models.inertia import dfm_root_piece, prb_root_piece, root_piece_inertia
from exubrush.output.results import HeadWrench, Results
from exubrush.parameters.fields import to_plain
from exubrush.run.prepared import PreparedCase
from exubrush.run.sanity import BEYOND_BOUND
from exubrush.run.solution import GroupSolution, SolverStatistics
from exubrush.run.solution_files import head_coordinates
from exubrush.run.twins import with_twins
from exubrush.util.exudyn_build import build_in_use
from exubrush.util.provenance import code_identity, package_version
from exubrush.util.references import run_references
from exubrush.world.kinematics import (
    CarriedLoad,
    carried_wrench,
    handle_angles,
    handle_history,
    head_force,
    head_moment,
    in_head_frame,
)
from exubrush.world.pose import rotation_matrix


@dataclass(frozen=True)
class RunFacts:
    """How a run went, besides its solutions.

    Attributes
    ----------
    interrupted : bool
        Stopped by Ctrl-C or SIGTERM.
    wall_time : float
        Wall time of the solves [s].
    workers : int
        Tasks that could run at once.
    resumed : int
        Groups read back from a checkpoint instead of solved.
    """

    interrupted: bool
    wall_time: float
    workers: int
    resumed: int = 0


def assemble_results(prepared: PreparedCase, solutions: Sequence[GroupSolution | None],
                     facts: RunFacts) -> Results:
    """The run's results from one solution per group (None: never started).

    If a solve failed or the run was interrupted, the results hold the head force over the
    time every group reached (nothing if a group never started), and the metadata's
    ``status`` is "failed" or "interrupted" with the reason in ``message``.
    """
    case = prepared.case
    solved = [solutions[i] for i, _ in prepared.solved_groups if solutions[i] is not None]
    # the handle's motion on the longest output grid, once: the twins need it on their
    # stand-ins' grids, the head force on the grid all groups reached (every grid is the
    # multiples of output.interval from 0, so each is a start of the longest)
    longest = max((s.time for s in solutions if s is not None), key=len, default=np.zeros(0))
    history = handle_history(prepared.motion, prepared.slide_axis, longest)
    solutions = with_twins(prepared, solutions, history[2])
    ran = [s for s in solutions if s is not None]
    n = min(len(s.time) for s in ran) if len(ran) == len(solutions) else 0
    t = ran[0].time[:n] if ran else np.zeros(0)
    handle_position = history[0][:n] + np.array([0.0, 0.0, prepared.start_height])
    angles = handle_angles(prepared.motion, t)
    force, wrench = _head_wrench(prepared, ran, n, history[2][:n], angles)
    # the groups' bristles joined, then put back in the head's order (groups that can
    # touch each other need not be contiguous ranges)
    order = np.argsort(np.concatenate(prepared.groups))
    tips = (np.concatenate([s.tips[:n] for s in solutions], axis=1)[:, order] if n
            else np.zeros((0, len(prepared.bristles), 3)))
    rows = np.arange(0, n, case.output.shape_stride)  # the groups' shape samples
    tip_force = (np.concatenate([s.tip_force[:n] for s in solutions], axis=1)[:, order] if n
                 else np.zeros((0, len(prepared.bristles), 3)))
    shape_coordinates = None
    if case.output.solution_file and n:
        shape_coordinates = head_coordinates([s.coordinates for s in solutions], order)
    return Results(
        time=t,
        slider_position=np.array([prepared.motion.sliding(ti)[0] for ti in t]),
        normal_force=-force[:, 2],
        tangential_force=force @ prepared.slide_axis,
        head_height=handle_position[:, 2],
        shape_time=t[rows],
        shape_nodes=_shape_nodes(prepared, solutions, n, rows, order,
                                 handle_position[rows], angles[0][rows]),
        shape_coordinates=shape_coordinates,
        tip_position=tips,
        tip_force=tip_force,
        metadata=_run_record(prepared, solutions, solved, facts, t, force),
        wrench=wrench,
        built_case=case,  # what metadata["parameters"] records, without building it again
    )


def _head_wrench(prepared: PreparedCase, ran: list[GroupSolution], n: int,
                 acceleration: np.ndarray, handle_turn: tuple):
    """The head's force (n, 3) [N] on the ``n`` samples every group reached, and its
    :class:`HeadWrench` (None without the drive's moments, as in 0.13.0's checkpoints);
    ``acceleration`` [mm/s²] and ``handle_turn`` (kinematics.handle_angles) are the
    handle's there."""
    force = head_force([s.reaction[:n] for s in ran] if n else [],
                       [s.handle_mass for s in ran], acceleration)
    angles, rates, turning = handle_turn
    carried = None
    # a head without pose terms leaves its root pieces out: its forces stay bit for bit
    # those of earlier versions; in the default runs the pieces' m a would move them by up
    # to 1.1e-7 N of 4.9 N (docs/motion.md, "The head's force and moment")
    if prepared.motion.pose is not None:
        carried = carried_wrench(carried_root_pieces(prepared), acceleration, angles, rates,
                                 turning)
        force = force + carried[0]
    if not (n and all(s.drive_moment is not None for s in ran)):
        return force, None
    moment = head_moment([s.drive_moment[:n] for s in ran],
                         [np.array(s.handle_inertia) for s in ran], angles, rates, turning)
    if carried is not None:
        moment = moment + carried[1]
    return force, HeadWrench(force=force, moment=moment,
                             head_force=in_head_frame(force, angles),
                             head_moment=in_head_frame(moment, angles))


def _shape_nodes(prepared: PreparedCase, solutions: Sequence[GroupSolution], n: int,
                 rows: np.ndarray, order: np.ndarray, handle: np.ndarray,
                 angles: np.ndarray) -> np.ndarray:
    """The head's bristles at the shape samples ``rows`` (the handle's node at ``handle``
    [mm], turned by ``angles``), roots first, in the head's ``order`` [mm]."""
    nodes = (np.concatenate([s.nodes[:len(rows)] for s in solutions], axis=1)[:, order] if n
             else np.zeros((0, len(prepared.bristles), prepared.case.model.shape_nodes, 3)))
    roots = np.array([b.root for b in prepared.bristles])
    # the roots turn with the head about the handle's node (A r, exubrush.world.pose)
    if prepared.motion.pose is not None:
        turned = np.array([roots @ rotation_matrix(theta).T for theta in angles]).reshape(
            len(rows), *roots.shape)
    else:
        turned = roots[None, :, :]
    return np.concatenate([(handle[:, None, :] + turned)[:, :, None, :], nodes], axis=2)


def _run_record(prepared: PreparedCase, solutions: Sequence[GroupSolution | None],
                solved: list[GroupSolution], facts: RunFacts, t: np.ndarray,
                force: np.ndarray) -> dict:
    """The run record (run.json): what was run, by which code, on which references, how it
    went and why it stopped; ``force`` [N] is the head's on the times ``t`` [s]."""
    case = prepared.case
    ran = [s for s in solutions if s is not None]
    n = len(t)
    completed = (not facts.interrupted and len(ran) == len(solutions)
                 and all(s.completed for s in ran))
    status = "completed" if completed else "interrupted" if facts.interrupted else "failed"
    peak = float(np.max(np.abs(force[:, 2]))) if n else 0.0
    bound = prepared.group_bound(None, sum(s.handle_mass for s in ran))
    # groups stopped beyond their bound: their samples past it are dropped, so the peak
    # above cannot show it
    beyond = [i for i, s in enumerate(solutions) if s is not None and BEYOND_BOUND in s.message]
    return {
        "case": case.name,
        "model": case.model.kind,
        "parameters": to_plain(case),
        "derived": _derived(prepared, ran, solved, facts),
        "versions": {**code_identity(), "exudyn": package_version("exudyn"),
                     "exudyn_build": build_in_use(), "python": platform.python_version()},
        "references": run_references(case),
        "solver_statistics": _statistics(solved),
        "sanity": {"peak_normal_force_N": peak, "normal_force_bound_N": bound,
                   "within_bound": peak <= bound and not beyond,
                   "groups_stopped_beyond_bound": beyond},
        "solver_wall_time_s_sum": sum(s.wall_time for s in solved),
        "wall_time_s": facts.wall_time,
        "simulated_time_s": float(t[-1]) if n else 0.0,
        "status": status,
        "completed": completed,
        "message": "" if completed else stop_message(case, solutions, facts.interrupted),
        "data_origin": "exubrush model output (simulation, not measurement)",
    }


def carried_root_pieces(prepared: PreparedCase) -> CarriedLoad:
    """The bristles' root pieces that ride on the handle, all of the head's (twins'
    included), as one rigid load (exubrush.models.inertia): a DFM bristle's half segment,
    a PRB bristle's stub. Their mass is in no body of the system, so the drive's reaction
    misses their inertia."""
    model = prepared.case.model
    mass, first_moment, inertia = 0.0, np.zeros(3), np.zeros((3, 3))
    for bristle in prepared.bristles:
        length = (dfm_root_piece(bristle.length, model.segments) if prepared.prb is None
                  else prb_root_piece(bristle.length, prepared.prb.gamma))
        piece = root_piece_inertia(bristle, bristle.material.density, length)
        mass += piece[0]
        first_moment = first_moment + piece[1]
        inertia = inertia + piece[2]
    return CarriedLoad(mass, first_moment, inertia)


def _derived(prepared: PreparedCase, ran: list[GroupSolution], solved: list[GroupSolution],
             facts: RunFacts) -> dict:
    """What the run derived from its parameters and how its systems went (``ran``: every
    group's record there is, twins' included; ``solved``: those of the groups solved)."""
    case, motion = prepared.case, prepared.motion
    systems = len(prepared.solved_groups)
    derived = {
        "bristles": len(prepared.bristles),
        "contact_elements": sum(s.contacts for s in ran),
        "partition": case.solver.partition,
        "systems_solved": systems,
        "twins_not_solved": len(prepared.groups) - systems,
        "systems_finished": sum(bool(s.completed) for s in solved),
        "systems_retried": sum(bool(s.retried) for s in solved),
        "systems_resumed": facts.resumed,
        "worker_processes": min(facts.workers, systems),
        "approach_distance_mm": motion.approach_distance,
        "slide_start_s": motion.slide_start,
        "end_time_s": motion.end_time,
    }
    if case.contact.between_bristles:
        derived["bristle_groups"] = [list(g) for g in prepared.groups]
        derived["bristle_contacts_max"] = sum(s.bristle_contacts_max for s in solved)
        derived["bristle_contacts_mean"] = sum(s.bristle_contacts_mean for s in solved)
        derived["bristle_overlap_max_mm"] = max((s.bristle_overlap_max for s in solved),
                                                default=0.0)
    if case.head.imperfect:
        derived["imperfections"] = imperfection_record(prepared)
    if prepared.prb is not None:
        derived["prb_gamma"] = prepared.prb.gamma
        derived["prb_stiffness_coefficient"] = prepared.prb.stiffness_coefficient
        if prepared.prb.load_ratio is not None:
            derived["prb_load_ratio"] = prepared.prb.load_ratio
    return derived


def imperfection_record(prepared: PreparedCase) -> dict:
    """An imperfect head's drawn values, per bristle in the head's order (rounded to 1e-6
    of their unit; head.seed draws them again exactly): the tilts added about the head's x
    and y axes [deg], the free lengths [mm], the roots' offsets [mm] and the roots after
    the misalignment [mm, head frame]."""
    head = prepared.case.head
    drawn = imperfections(head, [b.tuft for b in prepared.bristles])

    def rounded(values) -> list:
        return (np.round(np.asarray(values, dtype=float), 6) + 0.0).tolist()  # no -0.0

    return {
        "distribution": "uniform within +- the spread (head.tilt_spread_x, tilt_spread_y, "
                        "length_spread, root_jitter)",
        "seed": head.seed,
        "tilt_x_deg": rounded(np.degrees(drawn.tilt_x)),
        "tilt_y_deg": rounded(np.degrees(drawn.tilt_y)),
        "length_mm": rounded([b.length for b in prepared.bristles]),
        "root_offset_mm": rounded(drawn.offset),
        "misalignment_deg": rounded(np.degrees([head.misalign_x, head.misalign_y])),
        "root_mm": rounded([b.root for b in prepared.bristles]),
    }


def _statistics(solved: list[GroupSolution]) -> dict[str, int]:
    total = functools.reduce(lambda a, b: a + b, (s.statistics for s in solved),
                             SolverStatistics())
    return total.__dict__.copy() if solved else {}


def stop_message(case, solutions: Sequence[GroupSolution | None], interrupted: bool) -> str:
    """Why the run stopped, when, and what to change."""
    finished = sum(1 for s in solutions if s is not None and s.completed)
    if interrupted:
        return (f"{finished} of {len(solutions)} bristle groups finished and are "
                "kept: run the same command again to resume")
    failed = [(i, s) for i, s in enumerate(solutions) if s is not None and not s.completed]
    index, solution = min(failed, key=lambda item: len(item[1].time))
    reached = float(solution.time[-1]) if len(solution.time) else 0.0
    reason = solution.message or "the solver stopped before the end time"
    if BEYOND_BOUND in reason:
        kept = ("its last sample within the bound" if len(solution.time)
                else "with no sample within the bound")
        return f"group {index} stopped at t = {reached:.6g} s, {kept}: {reason}"
    return (f"group {index} stopped at t = {reached:.6g} s ({reason}); likely cause: no "
            f"converged step down to solver.minimum_step_size ({case.solver.minimum_step_size:g}"
            " s), e.g. a contact too stiff for the step or a violent snap-through; try a "
            f"smaller solver.step_size (now {case.solver.step_size:g} s), a smaller "
            "solver.minimum_step_size, a softer contact.stiffness or more damping "
            "(head.material.damping_time)")
