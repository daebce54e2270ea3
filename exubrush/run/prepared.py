"""A case prepared for solving: everything the bristle solves share, computed once.

:func:`prepare` resolves the head into bristles, the motion (a slide CSV is read here, once),
the PRB parameters (a fit to the elastica takes seconds), when friction is blended in and
the physical force bound. The result is frozen and picklable: the executor hands the same
object to every worker, and the CLI, the viewer and the sanity check read it instead of
recomputing. Errors that only the physics reveals (no bristle reaches the surface, an
unreadable slide CSV) are raised here as :class:`~exubrush.parameters.fields.ParameterError`.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import numpy as np

from exubrush.models.geometry import BristleGeometry, can_reach, head_bristles, touching_groups
from exubrush.models.howell import howell_parameters
from exubrush.models.stiffness import buckling_load
from exubrush.parameters.case import Case
from exubrush.parameters.fields import ParameterError
from exubrush.parameters.surface_kinds import MESH, PLANE
from exubrush.run.budget import (
    WorkEstimate,
    estimate,
    motion_warnings,
    over_size,
    over_work,
    unresolved,
)
from exubrush.run.sanity import (
    bristle_mass,
    inertia_allowance,
    normal_force_bound,
    static_force_limits,
)
from exubrush.world.clearance import (
    RY_LIMIT,
    Unchecked,
    closest_approach,
    largest_acceleration,
    largest_tilt,
    lowest_root,
    outermost,
    root_distances,
    sunken_roots,
)
from exubrush.world.kinematics import SLIDE_AXES
from exubrush.world.mesh import MeshError, MeshSurface, read_mesh
from exubrush.world.motion import HeadMotion, head_motion, with_pose
from exubrush.world.slide import TabulatedSlide
from exubrush.world.surfaces import height as surface_height
from exubrush.world.surfaces import highest_near, to_surface_frame

# twins under a turning head: distances and frames compared to this many decimals [mm, -]
TURN_KEY_DIGITS = 9
# the pivot of a turn that makes twins lies over the head's centre within this [mm]
TURN_PIVOT_TOLERANCE = 1e-12


@dataclass(frozen=True)
class PrbParameters:
    """Pseudo-rigid-body parameters of a run.

    Attributes
    ----------
    gamma : float
        Characteristic radius factor γ [-].
    stiffness_coefficient : float
        Stiffness coefficient K_Θ [-].
    load_ratio : float or None
        The load ratio n they were taken at (None for explicit values).
    """

    gamma: float
    stiffness_coefficient: float
    load_ratio: float | None


@dataclass(frozen=True)
class PreparedCase:
    """A validated case with what every solve of it shares (see module docstring).

    Attributes
    ----------
    case : Case
        The parameters.
    bristles : tuple of BristleGeometry
        Every bristle of the head, in order.
    motion : HeadMotion
        Approach, hold and slide of the head.
    start_height : float
        Height of the roots' surface above the plane at t = 0 [mm].
    prb : PrbParameters or None
        γ and K_Θ for the PRB model; None for DFM.
    friction_window : (float, float) or None
        Times [s] between which friction is blended in; None: it acts from the start.
    force_limits : tuple of float
        Each bristle's force straight and fully compressed [N] (exubrush.run.sanity).
    groups : tuple
        The bristle groups solved as separate Exudyn systems: tuples of bristle indices.
    work : WorkEstimate
        What the run will cost (exubrush.run.budget), within ``case.limits``.
    inputs : tuple of (str, str)
        (key, SHA-256 of what was read from it) for every input file the case names, so
        that a resume can tell a changed file from the same one (exubrush.output.rundir).
    warnings : tuple of str
        What the user should know before the run (e.g. a slide CSV faster than the step).
    reaching : tuple of bool
        Per bristle, whether its tip can ever touch the surface (those that cannot get no
        contact element).
    mesh : MeshSurface or None
        The surface's triangle mesh (surface.kind "mesh"), read and checked once.
    stand_ins : tuple of int
        Per group, the group whose solve stands for it: its own index, or a twin's
        (exubrush.run.twins); empty: every group is solved.
    stand_in_turns : tuple of float
        Per group, the angle [rad] about the head's centre by which it lies turned from its
        stand-in (0: shifted along the plane, or its own).
    peak_acceleration : float
        An upper bound of the acceleration of the head's roots and origin over the run
        [mm/s²] (exubrush.world.clearance.largest_acceleration): what the inertia allowance
        of the force bound is taken at (exubrush.run.sanity).
    """

    case: Case
    bristles: tuple[BristleGeometry, ...]
    motion: HeadMotion
    start_height: float
    prb: PrbParameters | None
    friction_window: tuple[float, float] | None
    force_limits: tuple[float, ...]
    groups: tuple[tuple[int, ...], ...]
    work: WorkEstimate
    inputs: tuple[tuple[str, str], ...]
    warnings: tuple[str, ...] = ()
    reaching: tuple[bool, ...] = ()
    mesh: MeshSurface | None = None
    stand_ins: tuple[int, ...] = ()
    stand_in_turns: tuple[float, ...] = ()
    peak_acceleration: float = 0.0

    @property
    def solved_groups(self) -> list[tuple[int, tuple[int, ...]]]:
        """(index, bristle indices) of each group that is solved: all but the twins."""
        return [(i, group) for i, group in enumerate(self.groups)
                if not self.stand_ins or self.stand_ins[i] == i]

    @property
    def slide_axis(self) -> np.ndarray:
        """Unit vector of the slide in the head frame."""
        return SLIDE_AXES[self.case.motion.direction]

    def force_bound(self, selection: tuple[int, ...] | None = None) -> float:
        """Largest physically possible normal force [N] of the bristles ``selection``
        (default: the whole head)."""
        limits = self.force_limits
        return normal_force_bound(limits if selection is None
                                  else [limits[i] for i in selection])

    def group_bound(self, selection: tuple[int, ...] | None, handle_mass: float) -> float:
        """What the drive's normal reaction [N] of the bristles ``selection`` (default: the
        whole head) on handles of ``handle_mass`` [t] in all may reach: their contact bound
        (:meth:`force_bound`) and the inertia allowance of the handles and bristles at the
        head's largest acceleration (exubrush.run.sanity.inertia_allowance)."""
        chosen = self.bristles if selection is None else [self.bristles[i] for i in selection]
        return self.force_bound(selection) + inertia_allowance(
            handle_mass + bristle_mass(chosen), self.peak_acceleration)

    def newton_force_tolerance(self, selection: tuple[int, ...]) -> float:
        """Residual [N] below which Newton accepts a step of the bristles ``selection``:
        ``solver.force_tolerance`` times the smallest Euler buckling load among them
        (docs/model.md, "Newton's tolerance")."""
        weakest = min(buckling_load(b.section, b.material.youngs_modulus, b.length)
                      for b in (self.bristles[i] for i in selection))
        return self.case.solver.force_tolerance * weakest

    @property
    def unreachable(self) -> int:
        """Number of bristles that can never touch the surface."""
        return sum(not reaches for reaches in self.reaching)


def prepare(case: Case) -> PreparedCase:
    """Compute once what every solve of ``case`` needs (see module docstring).

    Raises
    ------
    ParameterError
        If the work exceeds ``case.limits``, the step or output interval do not resolve the
        motion, no bristle can reach the surface or the slide CSV cannot be read.
    """
    _refuse(over_size(case, case.head.count))
    try:
        bristles = tuple(head_bristles(case.head))
    except ValueError as err:  # filaments that do not fit in their tuft
        raise ParameterError(str(err)) from None
    try:
        motion, height = head_motion(case, bristles)
    except ValueError as err:
        key = "motion.csv_file: " if case.motion.profile == "csv" else ""
        raise ParameterError(f"{key}{err}") from None
    try:
        motion = with_pose(motion, case.motion)
    except ValueError as err:
        raise ParameterError(f"motion.pose_csv: {err}") from None
    work = estimate(case, len(bristles), motion.end_time, motion.slide_start)
    _refuse(over_work(case, work) + unresolved(case, motion))
    # after the work is bounded: the pose's check evaluates every term at every sample
    roots = np.array([b.root for b in bristles])
    _refuse(impossible_pose(case, roots, motion, height))
    mesh = None
    if case.surface.kind == MESH:
        try:
            mesh = read_mesh(case.surface.mesh_file, case.surface.mesh_unit)
        except MeshError as err:
            raise ParameterError(str(err)) from None
    closest = closest_approach(motion, case.motion.direction, height, outermost(roots),
                               case.motion.interaction_distance
                               ) if case.surface.kind == PLANE else None
    distances = root_distances(case, roots, motion, closest)
    _refuse(sunken_roots(case, distances))
    reaching = surface_reach(case, bristles, motion, mesh, distances=distances)
    groups = bristle_groups(case, bristles)
    sources, turns = stand_ins(case, bristles, groups, motion)
    if not any(reaching) and not case.motion.posed:
        s = case.surface
        raise ParameterError(
            f"surface: no bristle can reach the {s.kind} at x = {s.x:g} mm, y = {s.y:g} mm "
            f"over the whole slide at motion.interaction_distance = "
            f"{case.motion.interaction_distance:g} mm; place it under the head (surface.x, "
            "surface.y), lower the interaction distance, or add pose terms (motion.sine, "
            "motion.pose_csv) for a head that moves in the air")
    return PreparedCase(
        case=case,
        bristles=bristles,
        motion=motion,
        start_height=height,
        prb=prb_parameters(case) if case.model.kind == "prb" else None,
        friction_window=friction_window(case, motion),
        force_limits=static_force_limits(case, bristles, distances),
        groups=groups,
        work=work,
        inputs=input_digests(motion, mesh),
        warnings=tuple(motion_warnings(case, motion)) + tuple(in_the_air(case, reaching))
        + tuple(unreachable_tufts(case, bristles, reaching)) + tuple(coupled_warning(case, groups)),
        reaching=reaching,
        mesh=mesh,
        stand_ins=sources,
        stand_in_turns=turns,
        peak_acceleration=largest_acceleration(motion, roots),
    )


def impossible_pose(case: Case, roots: np.ndarray, motion: HeadMotion,
                    start_height: float) -> list[str]:
    """What the pose terms ask that no head can do, each as one line: ``roots`` (n, 3)
    [mm, head frame] driven through the surface, or |ry| within 10° of the Tait-Bryan
    angles' singularity (exubrush.world.clearance: sampled so that neither is missed by
    more than its margin). A mesh surface's roots are not checked (docs/motion.md)."""
    if motion.pose is None:
        return []
    problems = []
    surface = case.surface
    if surface.kind == PLANE:
        roots = outermost(roots)
    height = None if surface.kind == PLANE else (
        lambda points: surface_height(surface, *to_surface_frame(surface, points)[:, :2].T))
    try:
        tilt = largest_tilt(motion)
        crossing = None if surface.kind == MESH else lowest_root(
            motion, case.motion.direction, start_height, roots, height)
    except Unchecked as err:
        return [f"motion: the pose keeps the head's roots within 0.01 mm of the {surface.kind}"
                f" or ry within 0.1° of ±{math.degrees(RY_LIMIT):g}° so long that checking it"
                f" would take {err}; move the head clear of it"]
    if crossing is not None:
        when, depth = crossing
        problems.append(
            f"motion: the pose drives the head's roots {depth:.3g} mm through the "
            f"{surface.kind} at t = {when:.6g} s (the roots stand "
            f"{case.motion.interaction_distance:g} mm above it after the approach); reduce "
            "the pose's z or turn terms, move motion.pivot, or raise "
            "motion.interaction_distance")
    if tilt is not None:
        when, angle = tilt
        problems.append(
            f"motion: ry reaches {math.degrees(angle):.4g}° at t = {when:.6g} s, within "
            f"{90.0 - math.degrees(RY_LIMIT):g}° of the Tait-Bryan angles' singularity at "
            f"±90° where the head's moment cannot be recovered from the drive; keep |ry| "
            f"below {math.degrees(RY_LIMIT):g}°")
    return problems


def input_digests(motion: HeadMotion, mesh: MeshSurface | None = None
                  ) -> tuple[tuple[str, str], ...]:
    """(key, SHA-256) of what the run read from each input file: the slide profile and the
    mesh's triangles [mm] as they were parsed, so no file is read twice and the hash is of
    the data the run uses."""
    digests = []
    if isinstance(motion.slide, TabulatedSlide):
        digests.append(("motion.csv_file", motion.slide.digest))
    table = motion.pose.table if motion.pose is not None else None
    if table is not None:
        digests.append(("motion.pose_csv", table.digest))
    if mesh is not None:
        digests.append(("surface.mesh_file",
                        hashlib.sha256(np.ascontiguousarray(mesh.triangles).tobytes())
                        .hexdigest()))
    return tuple(digests)


def surface_reach(case: Case, bristles, motion: HeadMotion, mesh: MeshSurface | None = None,
                  samples: int = 400, distances: np.ndarray | None = None
                  ) -> tuple[bool, ...]:
    """Per bristle, whether its tip can touch the surface somewhere along the slide.

    A tip's lowest point reaches at most l + r below its root, which stands its distance
    (``distances``, :func:`root_distances`; default: ``motion.interaction_distance``) above
    the level of the surface's top, and at most l + r to the side of it; it can touch if
    the surface's top (exubrush.world.surfaces.highest_near) rises above that depth anywhere
    within that distance of the root, at any of ``samples`` slide positions (on a mesh:
    anywhere near the root's straight path, an upper bound). On the plane this is
    d < l + r, with d the root's distance, lower than the interaction distance where pose
    terms bring the roots lower. On other surfaces a head with pose terms reaches
    everywhere (not sampled yet).
    """
    if distances is None:
        distances = np.full(len(bristles), case.motion.interaction_distance)
    if case.surface.kind == PLANE:
        return tuple(can_reach(b, d) for b, d in zip(bristles, distances, strict=True))
    if motion.pose is not None:  # turned or shaken: every bristle may reach (an upper bound)
        return (True,) * len(bristles)
    times = np.linspace(0.0, motion.end_time, samples)
    axis = SLIDE_AXES[case.motion.direction]
    shift = np.outer([motion.sliding(t)[0] for t in times], axis)
    reaching = []
    for bristle, distance in zip(bristles, distances, strict=True):
        reach = bristle.length + bristle.tip_radius
        centres = bristle.root[:2] + shift[:, :2]
        if mesh is None:
            top = highest_near(case.surface, centres, reach).max()
        else:  # the root's straight path, in the mesh's frame (placed by x, y, yaw)
            ends = to_surface_frame(case.surface, np.column_stack(
                [centres[[np.argmin(shift @ axis), np.argmax(shift @ axis)]], np.zeros(2)]))
            top = mesh.top_near_segment(ends[0, :2], ends[1, :2], reach)
        reaching.append(bool(distance - reach < top))
    return tuple(reaching)


def in_the_air(case: Case, reaching: tuple[bool, ...]) -> list[str]:
    """A warning for a head none of whose bristles can reach the surface (allowed only with
    pose terms: exubrush.world.motion.start_height)."""
    if any(reaching):
        return []
    return [f"surface: no bristle can reach the {case.surface.kind} at "
            f"motion.interaction_distance = {case.motion.interaction_distance:g} mm: the head "
            "moves in the air, without contact; its force and moment are the filaments' "
            "inertia and bending (docs/motion.md, \"A head in the air\")"]


def unreachable_tufts(case: Case, bristles, reaching: tuple[bool, ...]) -> list[str]:
    """A warning for each tuft none of whose filaments can reach the surface (they are
    built, but stay off the surface for the whole run)."""
    names = case.head.tuft_names()
    reaches = [False] * len(names)
    for bristle, reaching_tip in zip(bristles, reaching, strict=True):
        if bristle.tuft is not None:
            reaches[bristle.tuft] |= reaching_tip
    return [f"head: {name} cannot reach the surface at motion.interaction_distance = "
            f"{case.motion.interaction_distance:g} mm: its filaments never touch it"
            for name, reached in zip(names, reaches, strict=True) if not reached]


def coupled_warning(case: Case, groups) -> list[str]:
    """What contact between bristles will cost: the size of the largest system, and what
    touching groups of two sizes measured against their bristles solved apart
    (validation/benchmarks/README.md, "Where the targets stand"; docs/decisions/0026)."""
    largest = max((len(g) for g in groups), default=0)
    if not case.contact.between_bristles or largest < 2:
        return []
    return [f"contact.between_bristles: {len(groups)} system(s), the largest of {largest} "
            "bristles that can touch, each solved on one core; contact between bristles is "
            "slow and grows faster than the group (approach and 0.1 period: 19 touching "
            "filaments 27x, the tuft case's 37 39x the time of the same filaments apart)"]


def _refuse(problems: list[str]) -> None:
    """One ParameterError naming every problem found (one line)."""
    if problems:
        raise ParameterError("; ".join(problems))


def prb_parameters(case: Case) -> PrbParameters:
    """(γ, K_Θ) for the PRB model at n = case.load_ratio(): Howell's table, fitted to the
    exact elastica, or the explicit values (model.prb_parameters)."""
    source = case.model.prb_parameters
    if source == "explicit":
        return PrbParameters(case.model.prb_gamma, case.model.prb_stiffness_coefficient, None)
    n = case.load_ratio()
    if source == "fitted":  # the elastica's solvers (SciPy's integrate) only here
        from exubrush.reference.howell_fit import fit_prb_parameters

        fit = fit_prb_parameters(n)
        return PrbParameters(fit.gamma, fit.stiffness_coefficient, n)
    return PrbParameters(*howell_parameters(n), n)


def friction_window(case: Case, motion: HeadMotion) -> tuple[float, float] | None:
    """When friction is blended in, or None if it acts from the start (motion.approach_friction).

    "off" switches friction on during the hold after the approach; "auto" does so for the
    PRB model only: a straight PRB link whose tip sticks cannot buckle as a real bristle
    does, and a measured single bristle jammed at 126 N instead of buckling at ~0.1 N.
    """
    mode = case.motion.approach_friction
    if mode == "on" or (mode == "auto" and case.model.kind == "dfm"):
        return None
    return (motion.approach_duration, motion.slide_start)


def bristle_groups(case: Case, bristles) -> tuple[tuple[int, ...], ...]:
    """Bristle indices of each Exudyn system: all in one (solver.partition "coupled"), the
    groups that can touch each other (contact.between_bristles; exubrush.models.geometry.
    touching_groups), or one per bristle."""
    count = len(bristles)
    if case.solver.partition == "coupled":
        return (tuple(range(count)),)
    if case.contact.between_bristles:
        return touching_groups(list(bristles))
    return tuple((i,) for i in range(count))


def stand_ins(case, bristles, groups, motion) -> tuple[tuple[int, ...], tuple[float, ...]]:
    """Per group of ``groups`` (tuples of indices into ``bristles``): the index of the group
    whose solve stands for it, its own or the first whose bristle is its twin, and the
    angle [rad] about the head's centre by which the twin lies turned from it (0 for a
    twin shifted along the plane). exubrush.run.twins says when each is exact."""
    count = len(groups)
    own = tuple(range(count)), (0.0,) * count
    if (not case.solver.share_identical or case.surface.kind != PLANE
            or case.solver.partition != "per-bristle" or case.contact.between_bristles
            or any(len(group) != 1 for group in groups)):
        return own
    if motion.pose is None or not motion.pose.turns:
        key = _shift_key
    elif _turns_about_its_centre_only(case, motion.pose):
        key = _turn_key
    else:
        return own
    first: dict[tuple, tuple[int, float]] = {}
    sources, turns = [], []
    for index, group in enumerate(groups):
        found, angle = key(bristles[group[0]])
        source, source_angle = first.setdefault(found, (index, angle))
        sources.append(source)
        turns.append(angle - source_angle if source != index else 0.0)
    return tuple(sources), tuple(turns)


def _shift_key(bristle) -> tuple[tuple, float]:
    """Everything of a bristle that its motion relative to the plane depends on under a
    head that does not turn: all but its root's position along the plane (exact floats:
    twins are built by the same operations); no angle."""
    return (float(bristle.root[2]), bristle.frame.tobytes(), *_shape_key(bristle)), 0.0


def _turn_key(bristle) -> tuple[tuple, float]:
    """The same under a head turning about its centre only: the bristle turned about the
    centre onto the +x axis (its distance and frame there, to TURN_KEY_DIGITS), and the
    polar angle [rad] of its root."""
    x, y, z = bristle.root
    radius = math.hypot(x, y)
    angle = math.atan2(y, x) if radius > 0.0 else 0.0
    back = np.array([[math.cos(angle), math.sin(angle), 0.0],
                     [-math.sin(angle), math.cos(angle), 0.0], [0.0, 0.0, 1.0]])
    frame = np.round(back @ bristle.frame, TURN_KEY_DIGITS) + 0.0  # + 0.0: no -0.0
    return (round(radius, TURN_KEY_DIGITS), float(z), frame.tobytes(),
            *_shape_key(bristle)), angle


def _shape_key(bristle) -> tuple:
    return (bristle.length, bristle.tip_radius, bristle.section, bristle.width,
            bristle.height, bristle.shape, bristle.material)


def _turns_about_its_centre_only(case, pose) -> bool:
    """Whether the head's only motion along the plane is a turn about the vertical axis
    through its centre: no slide, pose terms on z and rz alone, the pivot over the head's
    centre; and no coordinates are kept (a turned twin's rotation coordinates are not its
    stand-in's)."""
    rates = pose.peak_rate
    return (case.motion.profile == "none" and not case.output.solution_file
            and not np.any(rates[[0, 1, 3, 4]] > 0.0)
            and math.hypot(pose.pivot[0], pose.pivot[1]) <= TURN_PIVOT_TOLERANCE)
