"""Discrete flexible model (DFM) of a bristle in Exudyn.

The bristle of length l is cut into N segments of length L = l/N with nodes at s = L, 2L,
..., l (the root node s = 0 is the handle). Each segment's elasticity is one 6x6
spring-damper at the segment's midpoint, with both connector frames there (see
:mod:`exubrush.models.stiffness`); the rigid body of node i spans from one midpoint to the
next, so it carries the slice [iL - L/2, iL + L/2] (the tip body the half slice
[l - L/2, l] and the tip sphere); the root's half slice [0, L/2] rides on the handle
(exubrush.models.inertia.dfm_root_piece). This is a Hencky bar chain, whose tip error
falls as 1/N² against the elastica (tests/integration/test_cantilever.py).
"""

from __future__ import annotations

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
from exubrush.models.inertia import dfm_root_piece
from exubrush.models.stiffness import midpoint_stiffness
from exubrush.parameters.head import Material


def add_dfm_bristle(
    mbs,
    handle_body,
    bristle: BristleGeometry,
    material: Material,
    segments: int,
    handle_position=(0.0, 0.0, 0.0),
    drawn: bool = False,
    rotation: str = "euler-parameters",
) -> BristleItems:
    """Add a DFM bristle clamped to ``handle_body``.

    Parameters
    ----------
    segments : int
        Number N of rigid bodies.
    handle_position : array of 3
        Reference position of the handle body [mm]; its frame is parallel to the head frame.
    drawn : bool
        Give the bodies graphics for Exudyn's renderer (exubrush view).
    rotation : str
        Rotation coordinates of the nodes (:data:`exubrush.models.assembly.NODE_TYPES`).
    """
    if segments < 1:
        raise ValueError(f"a DFM bristle needs at least one segment, got {segments}")
    L = bristle.length / segments
    K = midpoint_stiffness(bristle.section, material.youngs_modulus, material.shear_modulus, L)
    C = material.damping_time * K
    items = BristleItems()
    previous_marker = rigid_marker(mbs, handle_body,
                                   bristle.point(dfm_root_piece(bristle.length, segments)),
                                   bristle.frame)
    for i in range(1, segments + 1):
        if i < segments:
            inertia = slice_inertia(bristle, material.density, L)
        else:
            inertia = slice_inertia(bristle, material.density, 0.5 * L, -0.25 * L)
            inertia = inertia + tip_sphere_inertia(bristle, material.density)
        drawing = None
        if drawn:
            drawing = piece_graphics(bristle, -0.5 * L, 0.5 * L if i < segments else 0.0,
                                     tip=i == segments)
        node, body = add_body(
            mbs, np.add(handle_position, bristle.point(i * L)), bristle.frame, inertia, drawing,
            rotation,
        )
        items.nodes.append(node)
        items.bodies.append(body)
        marker = rigid_marker(mbs, body, [-0.5 * L, 0.0, 0.0])
        items.connectors.append(add_spring_damper(mbs, previous_marker, marker, K, C))
        if i < segments:
            previous_marker = rigid_marker(mbs, body, [0.5 * L, 0.0, 0.0])
    return items
