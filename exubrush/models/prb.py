"""Pseudo-rigid-body model (PRB, Howell, extended to 3-D) of a bristle in Exudyn.

The stub from the root to the characteristic pivot, (1 - γ)l long, is part of the handle;
the link from the pivot to the tip, γl long, is one rigid body on a spherical joint, held
by three torsional springs and dampers (k_x, k_y, k_z; C = damping_time · K). The springs
act on the rotation vector of the link relative to its upright frame (Exudyn's intrinsic
formulation), which stays regular for any bending angle.
"""

from __future__ import annotations

import exudyn.graphics as graphics
import exudyn.itemInterface as eii
import numpy as np

from exubrush.models.assembly import (
    BristleItems,
    add_body,
    add_spring_damper,
    piece_graphics,
    rigid_marker,
    slice_inertia,
    tip_sphere_inertia,
)
from exubrush.models.geometry import BristleGeometry
from exubrush.models.stiffness import prb_torsional_stiffness
from exubrush.parameters.case import Material


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
    pivot_on_handle = rigid_marker(mbs, handle_body, bristle.point(bristle.length - link),
                                   bristle.frame)
    pivot_on_link = rigid_marker(mbs, body, [-link, 0.0, 0.0])
    joint = mbs.AddObject(
        eii.ObjectJointSpherical(
            markerNumbers=[pivot_on_handle, pivot_on_link],
            visualization=eii.VObjectJointSpherical(show=False),
        )
    )
    springs = add_spring_damper(mbs, pivot_on_handle, pivot_on_link, K, C)
    return BristleItems(nodes=[node], bodies=[body], connectors=[joint, springs])


def stub_graphics(bristle: BristleGeometry, gamma: float) -> list:
    """Drawing of the stub (root to pivot, part of the handle) in the handle frame [mm]."""
    stub = piece_graphics(bristle, 0.0, (1.0 - gamma) * bristle.length)
    return [graphics.Move(g, list(bristle.point(0.0)), np.asarray(bristle.frame)) for g in stub]
