"""Assemble a brushing case into an Exudyn system.

Contents: a rigid handle whose six coordinates are prescribed by coordinate constraints
(the drive; its reaction is what the load cells read), the bristles (DFM or PRB) clamped
to it, a contact for each tip that can reach the surface (made by its back end,
exubrush.contact.tip_backends), the contact between bristles, and sensors for the drive
reactions and the bristle nodes. :func:`build_scene` adds them part by part
(:func:`add_handle`, :func:`add_drive`, :func:`add_bristle`, :func:`add_surface_contact`,
:func:`add_contact_between`, :func:`add_step_hooks`); the step hooks run in the phases of
exubrush.run.step_hooks.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import exudyn as exu
import exudyn.graphics as graphics
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import InertiaCuboid

from exubrush.contact.exudyn_contact import surface_marker
from exubrush.contact.tip_backends import BACKENDS, TipContact, TipSite, tip_backend
from exubrush.models.dfm import add_dfm_bristle
from exubrush.models.geometry import BristleGeometry
from exubrush.models.prb import add_prb_bristle, stub_graphics
from exubrush.parameters.choices import POSE_AXES
from exubrush.parameters.surface_kinds import (
    CYLINDER,
    MESH,
    PLANE,
    SPHERE,
    TOOTH_ROW,
)
from exubrush.run.newton import LineSearch, after_step_cut, has_lie_group_nodes
from exubrush.run.prepared import PreparedCase
from exubrush.run.solver import (
    fresh_jacobian_after_step_change,
    fresh_jacobian_while,
    linear_solver,
)
from exubrush.run.step_hooks import (
    AFTER_CUT,
    CANDIDATES,
    DRIVE,
    FRICTION,
    JACOBIAN,
    SAMPLING,
    STEP_SIZE,
    SURFACES,
    StepHooks,
)
from exubrush.run.step_policy import motion_step_cap, term_step_cap
from exubrush.world.kinematics import handle_coordinates
from exubrush.world.mesh import frame_with_normal
from exubrush.world.motion import HeadMotion
from exubrush.world.surfaces import orientation, tooth_pitch

if TYPE_CHECKING:
    from exubrush.contact.exudyn_between import BristleContact

# the handle is a stiff block whose mass only enters the drive reaction, from which the
# exact inertia force m·a of the prescribed motion is removed again
# (exubrush.world.kinematics.head_force)
HANDLE_SIZE = (20.0, 8.0, 3.0)  # mm
HANDLE_DENSITY = 1.2e-9  # t/mm³ (acrylic-like)
# a head that vibrates or turns (pose terms) gets a handle this much lighter: its m·a is
# removed exactly, but the drive's reaction carries the time integration's error of it,
# a share that falls with the step squared. A 0.58 g handle shaken at 258 Hz by 1.5 mm
# (2.3 N of m·a) left 0.13 N RMS of error at 20 steps a cycle in a filament's 7.5 mN; a
# thousandth of it still 1.7 mN at single samples against 1.2 mN RMS of side force, a
# millionth 2 µN, with the same steps and Newton iterations (docs/motion.md, "The head's
# force and moment")
POSED_HANDLE_LIGHTER = 1e-6


class ContactSensor(NamedTuple):
    """The sensors that record one tip contact's force (exubrush.contact.tip_force)."""

    bristle: int  # index of the bristle in the scene
    force: int  # sensor of the contact's force
    frame: int | None  # sensor of the contact frame's rotation matrix where it moves (a mesh)
    compiled: bool  # whether the contact is the compiled law (force_on_tip reads it so)


class TangentPlane(NamedTuple):
    """A tip on a mesh surface and the marker of the tangent plane it meets."""

    node: int  # the tip node
    marker: int  # the marker of its contact frame, moved before every step


@dataclass(frozen=True)
class DriveSensors:
    """The sensors of the drive's reactions on the handle, one per prescribed coordinate
    (exubrush.parameters.choices.POSE_AXES), each the Force of its coordinate constraint."""

    x: int  # [N]
    y: int  # [N]
    z: int  # [N]: the force pressing the head onto the surface
    rx: int  # generalised forces on the handle's Tait-Bryan angles [N·mm]
    ry: int
    rz: int

    @property
    def force(self) -> tuple[int, int, int]:
        """The force's sensors, x, y, z [N]."""
        return self.x, self.y, self.z

    @property
    def moment(self) -> tuple[int, int, int]:
        """The Tait-Bryan angles' sensors, rx, ry, rz [N·mm]."""
        return self.rx, self.ry, self.rz


@dataclass
class Scene:
    """An assembled Exudyn system and the indices needed to read it."""

    system_container: exu.SystemContainer
    mbs: exu.MainSystem
    motion: HeadMotion
    slide_axis: np.ndarray
    handle_mass: float
    bristles: tuple[BristleGeometry, ...]
    # the drive's reactions (add_drive)
    drive_sensors: DriveSensors | None = None
    # the handle's inertia about its centre (its node), body frame [t·mm²]
    handle_inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))
    node_sensors: list = field(default_factory=list)
    # each tip's contact with the surface (exubrush.contact.tip_backends)
    contacts: list[TipContact] = field(default_factory=list)
    contact_sensors: list[ContactSensor] = field(default_factory=list)
    keep_alive: list = field(default_factory=list)
    ground: int = 0
    # the callables (mbs, t) that the solve must call before every step, by phase
    step_hooks: StepHooks = field(default_factory=StepHooks)
    # contact between the bristles (contact.between_bristles, a group of two or more)
    bristle_contact: BristleContact | None = None
    # the line search in Newton's iterations (solver.line_search), where it runs
    line_search: LineSearch | None = None

    @property
    def tangent_planes(self) -> list[TangentPlane]:
        """Each tip on a mesh surface and its contact frame's marker."""
        return [TangentPlane(c.node, c.frame_marker) for c in self.contacts
                if c.frame_marker is not None]

    def run_step_hooks(self, mbs, t) -> bool:
        """Call every step hook, phase by phase; True (go on). Fit for Exudyn's pre-step
        user function where a solve needs nothing else before a step."""
        return self.step_hooks(mbs, t)


def add_drive(scene: Scene, handle_node) -> None:
    """Prescribe the handle's six coordinates: the slide along the slide axis plus the
    descent along z, nothing on the other axes; with pose terms, all six follow
    exubrush.world.kinematics.handle_coordinates.

    The moving axes' offsets are set in a step hook, not by an offset user function: Exudyn
    calls the pre-step function before every step attempt (retries included) with t at the
    step's end, where the implicit solver imposes the constraint, so the offsets are the
    same as the user function's, while the user function was called several times per
    Newton iteration (115,602 Python calls in one bristle's approach and period).
    """
    mbs = scene.mbs
    ground_node = mbs.AddNode(eii.NodePointGround())
    ground_marker = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
    motion, slide_axis = scene.motion, scene.slide_axis
    posed = motion.pose is not None
    start = handle_coordinates(motion, slide_axis, 0.0) if posed else None
    moving = []  # (constraint, slide factor, descent factor) of the axes that move
    sensors = []
    for axis in range(6):
        marker = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=handle_node, coordinate=axis))
        along = float(slide_axis[axis]) if axis < 3 else 0.0
        down = 1.0 if axis == 2 else 0.0
        offset = (float(start[axis]) if start is not None
                  else along * motion.sliding(0.0)[0] - down * motion.descent(0.0)[0])
        constraint = mbs.AddObject(
            eii.ObjectConnectorCoordinate(
                markerNumbers=[ground_marker, marker], offset=offset,
                visualization=eii.VObjectConnectorCoordinate(show=False),
            )
        )
        if along or down or posed:
            moving.append((constraint, along, down))
        sensors.append(mbs.AddSensor(eii.SensorObject(
            objectNumber=constraint, storeInternal=True, writeToFile=False,
            outputVariableType=exu.OutputVariableType.Force)))
    scene.drive_sensors = DriveSensors(**dict(zip(POSE_AXES, sensors, strict=True)))

    last = [None] * len(moving)

    def offsets(t):
        """The moving axes' offsets at t: all six from the pose, or the slide's and the
        descent's share of each."""
        if posed:
            return [float(value) for value in handle_coordinates(motion, slide_axis, t)]
        slide, descent = motion.sliding(t)[0], motion.descent(t)[0]
        return [along * slide - down * descent for _, along, down in moving]

    def drive(mbs, t):
        for k, ((constraint, _, _), offset) in enumerate(zip(moving, offsets(t), strict=True)):
            # an unchanged offset is not set again (~0.9 µs a call): the descent holds
            # after the approach, the slide before it
            if offset != last[k]:
                last[k] = offset
                mbs.SetObjectParameter(constraint, "offset", offset)

    scene.step_hooks.add(DRIVE, drive)


def _drawings(prepared: PreparedCase, bristles, gamma: float | None):
    """Graphics of the surface and of the handle (a block above the roots, and the PRB
    stubs of a link factor ``gamma``) for Exudyn's renderer [mm]."""
    size = 2.0 * (max(HANDLE_SIZE) + prepared.case.motion.amplitude)
    surface = surface_graphics(prepared.case.surface, size, prepared.mesh)
    handle = [graphics.Brick(centerPoint=[0.0, 0.0, 0.5 * HANDLE_SIZE[2]], size=HANDLE_SIZE,
                             color=[0.6, 0.6, 0.6, 0.5])]
    if gamma is not None:
        handle += [piece for b in bristles for piece in stub_graphics(b, gamma)]
    return surface, handle


def surface_graphics(surface, size: float, mesh=None) -> list:
    """Exudyn graphics of ``surface`` over a square of side ``size`` [mm] (a mesh: all of
    it), head frame."""
    turn = orientation(surface)
    top = np.array([surface.x, surface.y, 0.0])
    grey = [0.7, 0.7, 0.7, 1.0]
    if surface.kind == MESH:
        points = mesh.triangles.reshape(-1, 3) @ turn.T + top
        trigs = np.arange(len(points)).reshape(-1, 3)
        return [graphics.FromPointsAndTrigs(points.tolist(), trigs.tolist(), color=grey)]
    if surface.kind == PLANE:
        return [graphics.CheckerBoard(point=[0.0, 0.0, 0.0], normal=[0.0, 0.0, 1.0], size=size)]
    if surface.kind == CYLINDER:
        centre = top + turn @ [0.0, 0.0, -surface.radius]
        axis = turn @ [0.0, size, 0.0]
        return [graphics.Cylinder(pAxis=(centre - 0.5 * axis).tolist(), vAxis=axis.tolist(),
                                  radius=surface.radius, color=grey, nTiles=48)]
    if surface.kind == SPHERE:
        return [graphics.Sphere(point=(top + [0.0, 0.0, -surface.radius]).tolist(),
                                radius=surface.radius, color=grey, nTiles=32)]
    if surface.kind == TOOTH_ROW:
        pitch = tooth_pitch(surface)
        drawn = [graphics.CheckerBoard(point=[0.0, 0.0, -surface.gap_depth],
                                       normal=[0.0, 0.0, 1.0], size=size)]
        for k in range(-int(0.5 * size / pitch) - 1, int(0.5 * size / pitch) + 2):
            centre = top + turn @ [k * pitch, 0.0, -0.5 * surface.gap_depth]
            box = turn @ [surface.tooth_width, size, surface.gap_depth]
            drawn.append(graphics.Brick(centerPoint=centre.tolist(),
                                        size=np.abs(box).tolist(), color=grey))
        return drawn
    raise ValueError(f"surface kind {surface.kind!r} has no graphics")


def _tangent_plane_refresh(mesh, surface, planes):
    """A step hook that puts each tip's contact frame on the mesh's tangent plane at the
    point closest to the tip's centre (origin there, z along the contact's outward
    normal), before every step attempt: within a step the tip meets that plane, with the
    plane's law (docs/surfaces.md)."""
    turn = orientation(surface)
    origin = np.array([surface.x, surface.y, 0.0])

    def refresh(mbs, t):
        for node, marker in planes:
            centre = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Position))
            point, normal, _ = mesh.closest(turn.T @ (centre - origin))
            frame = exu.HT(rotation=(turn @ frame_with_normal(normal)).tolist(),
                           translation=(origin + turn @ point).tolist())
            mbs.SetMarkerParameter(marker, "localHT", frame)

    return refresh


class Handle(NamedTuple):
    """The handle's Exudyn items: the node the drive prescribes and the body the bristles
    are clamped to."""

    node: int
    body: int


def build_scene(prepared: PreparedCase, selection: tuple[int, ...] | None = None,
                drawn: bool = False) -> Scene:
    """Assemble the bristles ``selection`` of ``prepared`` into a ready-to-solve system:
    the handle and its drive, each bristle with its tip's contact with the surface, the
    contact between the bristles, then the step hooks.

    Parameters
    ----------
    selection : tuple of int, optional
        Indices of the bristles to include (default: all). The motion is always that of
        the whole head, so a head split into groups moves identically in every group.
    drawn : bool
        Give surface, handle and bristles graphics for Exudyn's renderer (exubrush view);
        a solve needs none.
    """
    case = prepared.case
    indices = tuple(range(len(prepared.bristles))) if selection is None else selection
    bristles = tuple(prepared.bristles[i] for i in indices)
    scene, handle = add_handle(prepared, bristles, drawn)
    add_drive(scene, handle.node)
    surface = surface_marker(scene.mbs, scene.ground, case.surface)
    laws = {}  # tip radius -> the contact law's user function, shared by its tips
    polylines = []
    tips = []  # (node, sphere radius) of the tips that reach the surface
    # each bristle's tip contact right after its bodies: the items' order is the system's
    for index, bristle in enumerate(bristles):
        items = add_bristle(scene, prepared, bristle, handle.body, drawn)
        polylines.append(_polyline(bristle, items.nodes, _link_factor(prepared)))
        if prepared.reaching[indices[index]]:
            tips.append((items.nodes[-1], bristle.tip_radius))
            add_surface_contact(scene, prepared, surface, index, items, laws)
    scene.keep_alive.extend(laws.values())
    add_contact_between(scene, case, handle.node, polylines)
    add_step_hooks(scene, prepared, tips)
    scene.mbs.Assemble()
    if scene.bristle_contact is not None:
        from exubrush.contact.exudyn_between import locate_in_system

        locate_in_system(scene.mbs, scene.bristle_contact)
    _add_line_search(scene, case.solver.line_search, case.solver.touching_give_up)
    return scene


def _link_factor(prepared: PreparedCase) -> float | None:
    """The PRB link factor gamma of ``prepared``'s model, None for the DFM."""
    return None if prepared.prb is None else prepared.prb.gamma


def add_handle(prepared: PreparedCase, bristles, drawn: bool) -> tuple[Scene, Handle]:
    """A new system with the ground (the surface's drawing) and the handle: a rigid block
    at the start height, lighter for a posed head (:data:`POSED_HANDLE_LIGHTER`), with no
    gravity; the scene that holds it and the handle's items."""
    surface_drawing, handle_drawing = (_drawings(prepared, bristles, _link_factor(prepared))
                                       if drawn else ([], []))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround(
        visualization=eii.VObjectGround(graphicsData=surface_drawing)))
    density = HANDLE_DENSITY * (POSED_HANDLE_LIGHTER if prepared.motion.pose is not None
                                else 1.0)
    handle_inertia = InertiaCuboid(density, HANDLE_SIZE)
    handle = mbs.CreateRigidBody(
        referencePosition=[0.0, 0.0, prepared.start_height], inertia=handle_inertia,
        nodeType=exu.NodeType.RotationRxyz, gravity=[0.0, 0.0, 0.0], show=drawn,
        graphicsDataList=handle_drawing, returnDict=True,
    )
    scene = Scene(SC, mbs, prepared.motion, prepared.slide_axis, handle_inertia.Mass(),
                  bristles, ground=ground, handle_inertia=handle_inertia.InertiaCOM())
    return scene, Handle(handle["nodeNumber"], handle["bodyNumber"])


def add_bristle(scene: Scene, prepared: PreparedCase, bristle: BristleGeometry,
                 handle_body: int, drawn: bool):
    """One bristle of ``prepared``'s model clamped to the handle body, and a sensor of each
    of its nodes' positions; its Exudyn items (exubrush.models.assembly.BristleItems)."""
    case, mbs = prepared.case, scene.mbs
    origin = (0.0, 0.0, prepared.start_height)
    if case.model.kind == "dfm":
        items = add_dfm_bristle(mbs, handle_body, bristle, bristle.material,
                                case.model.segments, origin, drawn, case.model.node_rotation)
    else:
        prb = prepared.prb
        items = add_prb_bristle(mbs, handle_body, bristle, bristle.material, prb.gamma,
                                prb.stiffness_coefficient, origin, drawn,
                                case.model.node_rotation, case.model.prb_link,
                                case.model.prb_pivot)
    scene.keep_alive.extend(items.user_functions)
    scene.node_sensors.append([
        mbs.AddSensor(eii.SensorNode(nodeNumber=n, storeInternal=True, writeToFile=False,
                                     outputVariableType=exu.OutputVariableType.Position))
        for n in items.nodes
    ])
    return items


def add_surface_contact(scene: Scene, prepared: PreparedCase, surface, index: int, items,
                        laws: dict) -> None:
    """The contact of the tip of the scene's bristle ``index`` (its Exudyn ``items``) with
    the surface (marker ``surface``), made by its back end (exubrush.contact.tip_backends;
    ``laws``: the user functions by tip radius, shared by the tips), and the sensors that
    record its force and, where it moves, its frame."""
    mbs = scene.mbs
    site = TipSite(mbs, scene.ground, surface, items.tip_body, items.nodes[-1],
                   scene.bristles[index])
    backend = tip_backend(prepared.case, site)
    contact = backend.add(site, prepared.case, prepared.friction_window, laws)
    scene.contacts.append(contact)
    frame_sensor = None
    if contact.frame_marker is not None:  # the frame moves: record it with the force
        frame_sensor = mbs.AddSensor(eii.SensorMarker(
            markerNumber=contact.frame_marker, storeInternal=True, writeToFile=False,
            outputVariableType=exu.OutputVariableType.RotationMatrix))
    scene.contact_sensors.append(ContactSensor(
        index, mbs.AddSensor(backend.force_sensor(contact)), frame_sensor,
        contact.compiled is not None))


def add_contact_between(scene: Scene, case, handle_node: int, polylines: list) -> None:
    """The contact between the scene's bristles (contact.between_bristles), where there are
    two or more, on the capsule chains ``polylines`` (:func:`_polyline`)."""
    if not (case.contact.between_bristles and len(scene.bristles) > 1):
        return
    # imported here: it loads numba, which a scene of bristles apart does not need
    from exubrush.contact.exudyn_between import add_bristle_contact

    scene.bristle_contact = add_bristle_contact(
        scene.mbs, handle_node, polylines,
        [0.5 * max(b.width, b.height) for b in scene.bristles], case.contact.bristles)
    scene.keep_alive.append(scene.bristle_contact)


def add_step_hooks(scene: Scene, prepared: PreparedCase, tips: list) -> None:
    """The hooks the solve calls before every step, each in its phase
    (exubrush.run.step_hooks; the drive's and the line search's are added with them): the
    mesh's tangent planes, the friction's lagged drop or blend, the contact between
    bristles' sampling, the Jacobian's renewal, the step cap (``tips``: (node, sphere
    radius) of the tips that reach the surface) and the contact between bristles'
    candidate pairs."""
    case, hooks, touching = prepared.case, scene.step_hooks, scene.bristle_contact
    if scene.tangent_planes:
        hooks.add(SURFACES, _tangent_plane_refresh(prepared.mesh, case.surface,
                                                   scene.tangent_planes))
    friction = BACKENDS[case.contact.backend].friction_hook(scene.contacts, case,
                                                            prepared.friction_window)
    if friction is not None:
        hooks.add(FRICTION, friction)
    # touching groups renew the Jacobian at every step attempt anyway (solver.dynamic_settings)
    if touching is None and linear_solver(case.solver) == "EigenSparse":
        hooks.add(JACOBIAN, fresh_jacobian_after_step_change())
    terms = term_step_cap(case, scene.motion)
    if terms is not None and touching is None:
        hooks.add(JACOBIAN, fresh_jacobian_while(lambda t: terms(t) is not None))
    cap = motion_step_cap(case, scene.motion, tips)
    if cap is not None:
        hooks.add(STEP_SIZE, cap)
    if touching is not None:
        from exubrush.contact.exudyn_between import contact_refresh

        hooks.add(SAMPLING, _contact_sampler(touching, case.output.interval))
        hooks.add(CANDIDATES, contact_refresh(touching))


def _add_line_search(scene: Scene, setting: str, give_up: float) -> None:
    """Run Newton's line search (exubrush.run.newton) as ``solver.line_search`` says. "auto":
    "always" in a group of touching bristles (a Newton iteration there costs a Jacobian of
    the group, the search's Python next to nothing), off elsewhere: one bristle's Jacobian
    is cheap, and on the tooth row 45 % fewer Jacobians saved 2 % of CPU time while the
    snaps' paths moved (decisions/0001); off where the nodes' rotations are on the Lie
    group. "after-cut" runs its switch in the step hooks' phase AFTER_CUT. In a group of
    touching bristles the search also gives up hopeless attempts (``give_up``,
    ``solver.touching_give_up``)."""
    if setting == "auto":  # the nodes are looked at only where the search would run
        if scene.bristle_contact is None or has_lie_group_nodes(scene.mbs):
            return
        setting = "always"
    if setting == "off":
        return
    scene.line_search = LineSearch(give_up=give_up if scene.bristle_contact is not None else 0.0)
    if setting == "always":
        scene.mbs.SetPreNewtonResidualUserFunction(scene.line_search)
    else:
        scene.step_hooks.add(AFTER_CUT, after_step_cut(scene.line_search))


def _polyline(bristle: BristleGeometry, nodes, gamma: float | None) -> list:
    """The points of a bristle's capsule chain (exubrush.contact.exudyn_between): its root
    (and a PRB link's pivot) on the handle, then its model's nodes."""
    points = [("handle", bristle.root)]
    if gamma is not None:
        points.append(("handle", bristle.point((1.0 - gamma) * bristle.length)))
    return points + [("node", n) for n in nodes]


def _contact_sampler(contact: BristleContact, interval: float):
    """Step hook recording the bristle contacts of the last converged state once per
    ``interval`` [s]."""
    last = [-np.inf]

    def sample(mbs, t):
        if t - last[0] >= interval:
            contact.sample(mbs)
            last[0] = t

    return sample
