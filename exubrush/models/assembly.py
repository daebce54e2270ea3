"""Exudyn building blocks shared by the bristle models: slices, markers, spring-dampers."""

from __future__ import annotations

from dataclasses import dataclass, field

import exudyn as exu
import exudyn.graphics as graphics
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import InertiaSphere, RigidBodyInertia

from exubrush.models.geometry import BristleGeometry
from exubrush.models.inertia import slice_moments


@dataclass
class BristleItems:
    """Exudyn indices of one bristle.

    Attributes
    ----------
    nodes : list of NodeIndex
        Rigid-body nodes from root to tip; the last one sits at the tip-sphere centre.
    bodies : list of ObjectIndex
        The matching rigid bodies.
    tip_body : ObjectIndex
        Body carrying the tip sphere (its node is at the sphere centre).
    connectors : list of ObjectIndex
        Spring-dampers (and joints) of the bristle, root first.
    user_functions : list
        Symbolic user functions of its connectors: keep them alive as long as the system.
    """

    nodes: list = field(default_factory=list)
    bodies: list = field(default_factory=list)
    connectors: list = field(default_factory=list)
    user_functions: list = field(default_factory=list)

    @property
    def tip_body(self):
        return self.bodies[-1]


def slice_inertia(
    bristle: BristleGeometry, density: float, length: float, centre_offset: float = 0.0
) -> RigidBodyInertia:
    """Inertia of a prismatic slice of the bristle [t, t·mm²].

    The slice has ``length`` [mm] along the bristle's x axis and its centre of mass at
    ``centre_offset`` [mm] from the body's node along x; principal moments about the centre
    as :func:`exubrush.models.inertia.slice_moments` gives them.
    """
    mass, moments = slice_moments(bristle.section, density, length)
    inertia = RigidBodyInertia(mass=mass, inertiaTensor=np.diag(moments),
                               inertiaTensorAtCOM=True)
    return inertia.Translated([centre_offset, 0.0, 0.0])


def tip_sphere_inertia(bristle: BristleGeometry, density: float) -> RigidBodyInertia:
    """Solid tip sphere of the bristle's material, centred at the tip node."""
    radius = bristle.tip_radius
    return InertiaSphere(mass=density * 4.0 / 3.0 * np.pi * radius**3, radius=radius)


BRISTLE_COLOUR = [0.25, 0.45, 0.8, 1.0]
TIP_COLOUR = [0.85, 0.3, 0.2, 1.0]


def piece_graphics(bristle: BristleGeometry, start: float, end: float,
                   tip: bool = False) -> list:
    """Drawing of the bristle from ``start`` to ``end`` [mm] along x of the bristle frame: a
    cylinder for a round filament, else a box of the section's width and height (an
    elliptic section is drawn as its bounding box), and the tip sphere centred at ``end`` if
    ``tip``. For Exudyn's renderer only."""
    if bristle.shape == "circle":
        box = graphics.Cylinder(pAxis=[start, 0.0, 0.0], vAxis=[end - start, 0.0, 0.0],
                                radius=0.5 * bristle.width, color=BRISTLE_COLOUR, nTiles=8)
    else:
        box = graphics.Brick(centerPoint=[0.5 * (start + end), 0.0, 0.0],
                             size=[end - start, bristle.width, bristle.height],
                             color=BRISTLE_COLOUR)
    if not tip:
        return [box]
    return [box, graphics.Sphere(point=[end, 0.0, 0.0], radius=bristle.tip_radius,
                                 color=TIP_COLOUR, nTiles=12)]


NODE_TYPES = {
    "euler-parameters": exu.NodeType.RotationEulerParameters,
    "rotation-vector": exu.NodeType.RotationRotationVector,
}


def add_body(mbs, position, frame, inertia, drawing=None, rotation="euler-parameters"):
    """Add a rigid body (no gravity: it is negligible at this scale).

    ``drawing`` is its graphics data for Exudyn's renderer (default: none, not shown).
    ``rotation`` names its node's rotation coordinates (:data:`NODE_TYPES`): both are
    regular at any bending angle, unlike Tait-Bryan angles, which are singular where a
    bristle frame's x axis points down."""
    item = mbs.CreateRigidBody(
        referencePosition=list(position),
        referenceRotationMatrix=np.asarray(frame),
        inertia=inertia,
        gravity=[0.0, 0.0, 0.0],
        nodeType=NODE_TYPES[rotation],
        graphicsDataList=drawing or [],
        show=bool(drawing),
        returnDict=True,
    )
    return item["nodeNumber"], item["bodyNumber"]


def rigid_marker(mbs, body, position, frame=None):
    """Position-and-orientation marker on ``body`` at local ``position`` with local ``frame``."""
    rotation = np.eye(3) if frame is None else np.asarray(frame)
    return mbs.AddMarker(
        eii.MarkerBodyRigid(
            bodyNumber=body, localHT=exu.HT(rotation=rotation, translation=list(position))
        )
    )


def add_spring_damper(mbs, marker0, marker1, stiffness, damping, user_function=0):
    """Intrinsic 6x6 spring-damper between two rigid markers (SE(3) log at the mid-frame)."""
    return mbs.AddObject(
        eii.ObjectConnectorRigidBodySpringDamper(
            markerNumbers=[marker0, marker1],
            stiffness=np.asarray(stiffness).tolist(),
            damping=np.asarray(damping).tolist(),
            useIntrinsicFormulation=True,
            springForceTorqueUserFunction=user_function,
            visualization=eii.VObjectConnectorRigidBodySpringDamper(show=False),
        )
    )
