"""Static solutions in Exudyn for checks against closed forms: single bristle models, a
tip sphere pressed onto a surface and a bristle pushed against its neighbour."""

from __future__ import annotations

from dataclasses import dataclass

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import InertiaSphere

from exubrush.contact.exudyn_between import add_bristle_contact, locate_in_system
from exubrush.contact.exudyn_contact import (
    add_tip_contact,
    contact_user_function,
    surface_marker,
)
from exubrush.models.assembly import rigid_marker
from exubrush.models.dfm import add_dfm_bristle
from exubrush.models.geometry import BristleGeometry
from exubrush.models.prb import add_prb_bristle
from exubrush.parameters.case import BristleContactLaw, ContactLaw, Surface
from exubrush.parameters.head import Material
from exubrush.parameters.settings import Solver
from exubrush.run.solver import dynamic_settings, static_settings
from exubrush.world.mesh import frame_with_normal


def tip_loaded_cantilever(
    bristle: BristleGeometry,
    material: Material,
    force: np.ndarray,
    model: str = "dfm",
    segments: int = 6,
    gamma: float = 0.8517,
    stiffness_coefficient: float = 2.67617,
    load_steps: int = 40,
) -> np.ndarray:
    """Tip-sphere centre of a bristle clamped at its root under a dead tip force.

    Parameters
    ----------
    force : array of 3
        Tip force in the head frame [N]; applied in ``load_steps`` equal increments.
    model : {"dfm", "prb"}
        Bristle model; ``segments`` for DFM, ``gamma`` and ``stiffness_coefficient`` for PRB.

    Returns
    -------
    ndarray (3,)
        Tip position in the head frame [mm].
    """
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    if model == "dfm":
        items = add_dfm_bristle(mbs, ground, bristle, material, segments)
    else:
        items = add_prb_bristle(mbs, ground, bristle, material, gamma, stiffness_coefficient)
    tip = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=items.tip_body, localPosition=[0, 0, 0]))
    mbs.AddLoad(eii.LoadForceVector(markerNumber=tip, loadVector=list(force)))
    mbs.Assemble()
    if not mbs.SolveStatic(static_settings(load_steps)):
        raise RuntimeError("static solve of the cantilever did not converge")
    return np.asarray(mbs.GetNodeOutput(items.nodes[-1], exu.OutputVariableType.Position))


def pinned_prb_push(
    bristle: BristleGeometry,
    material: Material,
    force: float,
    gamma: float = 0.8517,
    stiffness_coefficient: float = 2.67617,
    load_steps: int = 40,
) -> float:
    """Shortening [mm] of a PRB bristle with the buckling link (exubrush.models.buckling)
    on its default pivot spring, clamped at its root, its tip held on the bristle's axis
    (free to slide along it and to rotate: a pinned tip) and pushed along the axis towards
    the root by ``force`` [N]."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    items = add_prb_bristle(mbs, ground, bristle, material, gamma, stiffness_coefficient)
    tip_point = bristle.point(bristle.length)
    on_axis = rigid_marker(mbs, ground, tip_point, bristle.frame)
    tip = rigid_marker(mbs, items.tip_body, [0.0, 0.0, 0.0])
    mbs.AddObject(eii.ObjectJointGeneric(markerNumbers=[on_axis, tip],
                                         constrainedAxes=[0, 1, 1, 0, 0, 0]))
    axis = np.asarray(bristle.frame)[:, 0]
    mbs.AddLoad(eii.LoadForceVector(markerNumber=tip, loadVector=list(-force * axis)))
    mbs.Assemble()
    if not mbs.SolveStatic(static_settings(load_steps)):
        raise RuntimeError("static solve of the pushed PRB bristle did not converge")
    position = np.asarray(mbs.GetNodeOutput(items.nodes[-1], exu.OutputVariableType.Position))
    return float(np.dot(tip_point - position, axis))


def sphere_pressed_on_surface(surface: Surface, law: ContactLaw, radius: float, anchor,
                              direction, force: float, load_steps: int = 20) -> np.ndarray:
    """Centre of a rigid tip sphere pressed onto ``surface`` by a dead force, in statics.

    The sphere's centre may only move along the line anchor + s · direction (head frame,
    ``direction`` a unit vector, pointing away from the surface); it starts at s = r − 1 µm
    (just touching) and a force of ``force`` [N] pushes it along −direction, applied in
    ``load_steps`` equal increments. The contact is the one a run builds
    (exubrush.contact.exudyn_contact, the paper's law in the symbolic back end); a static
    solve has no velocities, so only the law's elastic term acts.

    Returns
    -------
    ndarray (3,)
        The centre at equilibrium [mm], head frame.
    """
    anchor = np.asarray(anchor, dtype=float)
    axis = np.asarray(direction, dtype=float)
    frame = frame_with_normal(axis)  # its z along the line
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    body = mbs.CreateRigidBody(referencePosition=(anchor + (radius - 1e-3) * axis).tolist(),
                               inertia=InertiaSphere(1e-9, radius), gravity=[0, 0, 0],
                               show=False, returnDict=True)
    held = rigid_marker(mbs, ground, anchor, frame)
    moving = rigid_marker(mbs, body["bodyNumber"], [0.0, 0.0, 0.0], frame)
    mbs.AddObject(eii.ObjectJointGeneric(markerNumbers=[held, moving],
                                         constrainedAxes=[1, 1, 0, 1, 1, 1],
                                         visualization=eii.VObjectJointGeneric(show=False)))
    function = contact_user_function(mbs, law, radius, surface=surface)
    add_tip_contact(mbs, surface_marker(mbs, ground, surface), body["bodyNumber"], function)
    centre = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=body["bodyNumber"],
                                                  localPosition=[0, 0, 0]))
    mbs.AddLoad(eii.LoadForceVector(markerNumber=centre, loadVector=(-force * axis).tolist()))
    mbs.Assemble()
    if not mbs.SolveStatic(static_settings(load_steps)):
        raise RuntimeError("static solve of the pressed sphere did not converge")
    return np.asarray(mbs.GetNodeOutput(body["nodeNumber"], exu.OutputVariableType.Position))


@dataclass(frozen=True)
class PushedPair:
    """End state of :func:`pushed_pair`.

    Attributes
    ----------
    tips : ndarray (2, 3)
        Both tip positions at the end [mm].
    deepest : float
        Deepest overlap of the two bristles seen at any 0.01 s sample [mm].
    contact_force : ndarray (3,)
        Contact force on the second bristle at the end [N].
    completed : bool
        Whether the solve reached the end.
    """

    tips: np.ndarray
    deepest: float
    contact_force: np.ndarray
    completed: bool


def pushed_pair(bristles: tuple[BristleGeometry, BristleGeometry], force: np.ndarray,
                law: BristleContactLaw, segments: int = 12, ramp: float = 1.0,
                step_size: float = 2e-3, in_plane: bool = False):
    """Two DFM bristles clamped to a fixed base, a dead force on the first's tip ramped up
    over ``ramp`` [s] and held for a fifth of that, with contact between them
    (exubrush.contact.exudyn_between): quasi-static, settled by the bristles' damping.

    ``in_plane``: every node's y coordinate is held, so the pair bends in the x-z plane
    only, as the planar reference does (exubrush.reference.touching_cantilevers). Round
    filaments pressed hard tip on side are unstable out of that plane: the pushed tip
    slides round its neighbour (beyond about P = 0.5 mN for two 0.2 mm nylon filaments
    10 mm long, where the contact force over the diameter exceeds their lateral stiffness).

    Returns
    -------
    PushedPair
    """
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    base = mbs.CreateRigidBody(referencePosition=[0.0, 0.0, 0.0],
                               inertia=InertiaSphere(1e-9, 1.0), gravity=[0.0, 0.0, 0.0],
                               nodeType=exu.NodeType.RotationRxyz, returnDict=True)
    fixed = mbs.AddMarker(eii.MarkerNodeCoordinate(
        nodeNumber=mbs.AddNode(eii.NodePointGround()), coordinate=0))
    for coordinate in range(6):
        marker = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=base["nodeNumber"],
                                                        coordinate=coordinate))
        mbs.AddObject(eii.ObjectConnectorCoordinate(markerNumbers=[fixed, marker]))
    items = [add_dfm_bristle(mbs, base["bodyNumber"], b, b.material, segments)
             for b in bristles]
    for node in (n for it in items for n in it.nodes) if in_plane else ():
        held = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=node, coordinate=1))
        mbs.AddObject(eii.ObjectConnectorCoordinate(markerNumbers=[fixed, held]))
    contact = add_bristle_contact(
        mbs, base["nodeNumber"],
        [[("handle", b.root)] + [("node", n) for n in it.nodes]
         for b, it in zip(bristles, items, strict=True)],
        [0.5 * max(b.width, b.height) for b in bristles], law)
    tip = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=items[0].tip_body,
                                               localPosition=[0.0, 0.0, 0.0]))
    load = np.asarray(force, float)
    mbs.AddLoad(eii.LoadForceVector(
        markerNumber=tip, loadVector=[0.0, 0.0, 0.0],
        loadVectorUserFunction=lambda mbs, t, vector: list(load * min(t / ramp, 1.0))))
    mbs.Assemble()
    locate_in_system(mbs, contact)
    samples = [-1.0]

    def sample(mbs, t):
        if t - samples[0] >= 0.01:
            contact.sample(mbs)
            samples[0] = t
        return True

    mbs.SetPreStepUserFunction(sample)
    settings = dynamic_settings(Solver(step_size=step_size), 1.2 * ramp, 0.01, touching=True)
    try:
        completed = bool(mbs.SolveDynamic(settings))
    except exu.SolverError:
        completed = False
    contact.sample(mbs)
    tips = np.array([mbs.GetNodeOutput(it.nodes[-1], exu.OutputVariableType.Position)
                     for it in items])
    return PushedPair(tips, max(contact.overlaps), contact.resultants(mbs)[1], completed)
