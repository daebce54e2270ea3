"""Pseudo-rigid-body model (PRB, Howell, extended to 3-D) of a bristle in Exudyn.

The stub from the root to the characteristic pivot, (1 - γ)l long, is part of the handle
(exubrush.models.inertia.prb_root_piece); the link from the pivot to the tip, γl long, is
one rigid body held by three torsional springs and dampers (k_x, k_y, k_z; C =
damping_time · K). The springs act on the rotation
vector of the link relative to its upright frame (Exudyn's intrinsic formulation), which
stays regular for any bending angle.

Two links (``model.prb_link``):

- ``"buckling"`` (default): the link may slide along its own axis through the pivot,
  against the axial spring of :mod:`exubrush.models.buckling`: as stiff as the bristle in
  compression up to the buckling load, then nearly constant, so that a pushed bristle
  shortens and passes under its pivot;
- ``"rigid"``: the paper's link of fixed length on a spherical joint.

What holds the sliding link's axis on the pivot (``model.prb_pivot``):

- ``"spring"`` (default): a stiff lateral spring between the pivot and the link's axis,
  :data:`PIVOT_STIFFNESS_FACTOR` times the bristle's axial stiffness EA/l, whose force
  acts on the link where the link passes the pivot (a penalty form of the joint);
- ``"joint"``: Exudyn's generic joint (a constraint): exact, but Newton took 3.8 iterations
  a step against 2.1 with the spring (docs/decisions/0017).
"""

from __future__ import annotations

import exudyn as exu
import exudyn.graphics as graphics
import exudyn.itemInterface as eii
import numpy as np
from exudyn.advancedUtilities import CreateSymbolicUserFunction

from exubrush.models.assembly import (
    BristleItems,
    add_body,
    add_spring_damper,
    piece_graphics,
    rigid_marker,
    slice_inertia,
    tip_sphere_inertia,
)
from exubrush.models.buckling import axial_force, clamped_pinned_load
from exubrush.models.geometry import BristleGeometry
from exubrush.models.inertia import prb_root_piece
from exubrush.models.stiffness import prb_torsional_stiffness
from exubrush.parameters.head import Material

# lateral stiffness of the pivot spring over the bristle's axial stiffness EA/l: on four
# bristles of the default head (1.5 periods) the mean flat-zone force lay 0.02 % from the
# joint's with 10, 0.003 % with 100 (which took 10 % longer: Newton iterates more against a
# stiffer spring), 0.25 % with 1 (docs/decisions/0017)
PIVOT_STIFFNESS_FACTOR = 10.0


def add_prb_bristle(
    mbs,
    handle_body,
    bristle: BristleGeometry,
    material: Material,
    gamma: float,
    stiffness_coefficient: float,
    handle_position=(0.0, 0.0, 0.0),
    drawn: bool = False,
    rotation: str = "euler-parameters",
    link_kind: str = "buckling",
    pivot: str = "spring",
) -> BristleItems:
    """Add a PRB bristle clamped to ``handle_body``.

    Parameters
    ----------
    gamma, stiffness_coefficient : float
        Howell's γ and K_Θ [-].
    handle_position : array of 3
        Reference position of the handle body [mm]; its frame is parallel to the head frame.
    drawn : bool
        Give the link graphics for Exudyn's renderer (the stub is drawn with the handle:
        :func:`stub_graphics`).
    rotation : str
        Rotation coordinates of the link's node
        (:data:`exubrush.models.assembly.NODE_TYPES`).
    link_kind : str
        ``"buckling"`` (sliding link with the axial spring) or ``"rigid"`` (module text).
    pivot : str
        What holds the sliding link on the pivot: ``"spring"`` or ``"joint"`` (module
        text); the rigid link always has its spherical joint.
    """
    link = gamma * bristle.length
    k = prb_torsional_stiffness(
        bristle.section, material.youngs_modulus, material.shear_modulus,
        bristle.length, gamma, stiffness_coefficient,
    )
    K = np.diag([0.0, 0.0, 0.0, *k])
    C = material.damping_time * K
    inertia = slice_inertia(bristle, material.density, link, -0.5 * link)
    inertia = inertia + tip_sphere_inertia(bristle, material.density)
    tip = np.add(handle_position, bristle.point(bristle.length))
    drawing = piece_graphics(bristle, -link, 0.0, tip=True) if drawn else None
    node, body = add_body(mbs, tip, bristle.frame, inertia, drawing, rotation)
    pivot_on_handle = rigid_marker(mbs, handle_body,
                                   bristle.point(prb_root_piece(bristle.length, gamma)),
                                   bristle.frame)
    pivot_on_link = rigid_marker(mbs, body, [-link, 0.0, 0.0])
    if link_kind == "rigid":
        joint = mbs.AddObject(eii.ObjectJointSpherical(
            markerNumbers=[pivot_on_handle, pivot_on_link],
            visualization=eii.VObjectJointSpherical(show=False)))
        springs = add_spring_damper(mbs, pivot_on_handle, pivot_on_link, K, C)
        return BristleItems(nodes=[node], bodies=[body], connectors=[joint, springs])
    if pivot not in ("spring", "joint"):
        raise ValueError(f"pivot {pivot!r}: use 'spring' or 'joint'")
    # the handle's pivot stays on the link's axis (y, z in the link frame); the link slides
    laws = []
    if pivot == "joint":
        holder = mbs.AddObject(eii.ObjectJointGeneric(
            markerNumbers=[pivot_on_link, pivot_on_handle], constrainedAxes=[0, 1, 1, 0, 0, 0],
            visualization=eii.VObjectJointGeneric(show=False)))
    else:
        holder, pivot_law = _add_pivot_spring(mbs, pivot_on_link, pivot_on_handle, bristle,
                                              material)
        laws.append(pivot_law)
    springs = add_spring_damper(mbs, pivot_on_handle, pivot_on_link, K, C)
    axial, law = _add_axial_spring(mbs, pivot_on_handle, body, bristle, material, link)
    return BristleItems(nodes=[node], bodies=[body], connectors=[holder, springs, axial],
                        user_functions=[*laws, law])


def axial_spring_constants(bristle: BristleGeometry, material: Material) -> tuple[float, float]:
    """(k_a [N/mm], P_b [N]) of the sliding link's axial spring: EA/l and the clamped-pinned
    buckling load about the section's weaker axis (exubrush.models.buckling)."""
    section = bristle.section
    stiffness = material.youngs_modulus * section.area / bristle.length
    weaker = min(section.second_moment_y, section.second_moment_z)
    return stiffness, clamped_pinned_load(material.youngs_modulus * weaker, bristle.length)


def _add_pivot_spring(mbs, pivot_on_link, pivot_on_handle, bristle, material):
    """The lateral spring-damper that holds the sliding link's axis on the handle's pivot.

    A connector in the link's frame from the link's pivot marker (marker 0) to the handle's
    (marker 1) sees the handle's pivot at u = (s, u_y, u_z) [mm] from the link's, s the
    slide. The link's material point there moves relative to it with w = v + ω × u [mm/s]
    (v the markers' relative velocity, ω their relative angular velocity, both in the
    link's frame, as Exudyn hands them; the handle does not rotate). The user function
    returns the lateral force f = (0, k u_y + c w_y, k u_z + c w_z) [N] (k =
    PIVOT_STIFFNESS_FACTOR · EA/l, c = damping_time · k) and the torque u × f [N·mm], which
    Exudyn applies to the link (and its opposite to the driven handle): so the force acts
    on the link at its point on the pivot, as the joint's reaction does, and the spring
    converges to the joint as k grows (without the torque the mean force moved by 0.4-0.85
    %; with v instead of w the damping braked the link's rotation by c s², soon more than
    its torsional damper: docs/decisions/0017)."""
    stiffness = PIVOT_STIFFNESS_FACTOR * axial_spring_constants(bristle, material)[0]
    damping = material.damping_time * stiffness

    def holding(mbs, t, itemNumber, u, rotation, v, omega, stiffness_, damping_, rotJ0,
                rotJ1, offset):
        # (v + ω × u) along y and z
        f_y = stiffness * u[1] + damping * (v[1] + omega[2] * u[0] - omega[0] * u[2])
        f_z = stiffness * u[2] + damping * (v[2] + omega[0] * u[1] - omega[1] * u[0])
        return [0.0, f_y, f_z, u[1] * f_z - u[2] * f_y, -u[0] * f_z, u[0] * f_y]

    law = CreateSymbolicUserFunction(mbs, holding, "springForceTorqueUserFunction",
                                     itemTypeName="ObjectConnectorRigidBodySpringDamper")
    connector = mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(
        markerNumbers=[pivot_on_link, pivot_on_handle], useIntrinsicFormulation=False,
        springForceTorqueUserFunction=law,
        visualization=eii.VObjectConnectorRigidBodySpringDamper(show=False)))
    return connector, law


def _add_axial_spring(mbs, pivot_on_handle, body, bristle, material, link_length):
    """Spring-damper from the handle's pivot to the tip centre (reference length γl) with
    the buckling law as a symbolic user function; its damping is damping_time · k_a."""
    stiffness, buckling = axial_spring_constants(bristle, material)
    damping = material.damping_time * stiffness

    def tension(mbs, t, itemNumber, deltaL, deltaL_t, stiffness_, damping_, force_):
        # Exudyn's scalar force is a tension; the law's F is a compression of s = -deltaL
        return -axial_force(-deltaL, stiffness, buckling, bristle.length, exu.symbolic) \
            + damping * deltaL_t

    law = CreateSymbolicUserFunction(mbs, tension, "springForceUserFunction",
                                     itemTypeName="ObjectConnectorSpringDamper")
    tip_marker = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=body,
                                                      localPosition=[0.0, 0.0, 0.0]))
    spring = mbs.AddObject(eii.ObjectConnectorSpringDamper(
        markerNumbers=[pivot_on_handle, tip_marker], referenceLength=link_length,
        stiffness=stiffness, damping=damping, springForceUserFunction=law,
        visualization=eii.VObjectConnectorSpringDamper(show=False)))
    return spring, law


def stub_graphics(bristle: BristleGeometry, gamma: float) -> list:
    """Drawing of the stub (root to pivot, part of the handle) in the handle frame [mm]."""
    stub = piece_graphics(bristle, 0.0, (1.0 - gamma) * bristle.length)
    return [graphics.Move(g, list(bristle.point(0.0)), np.asarray(bristle.frame)) for g in stub]
