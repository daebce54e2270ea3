"""Shear-deformable reference: a cantilever of Exudyn's 2-D geometrically exact beam elements.

The Euler elastica ignores shear and stretching; a short, thick bristle does not. The
reference for it is a converged chain of ``ObjectBeamGeometricallyExact2D`` elements
(Simo-Reissner beam: bending EI, axial EA and shear κGA, large rotations), clamped at the
origin with its axis along +x and a dead force at the tip, solved statically. The element
count is a parameter; :func:`tip_position` is converged when doubling it changes the tip by
less than the tolerance one needs (the validation notebook shows the convergence).
"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from exubrush.run.solver import static_settings


def tip_position(length: float, bending: float, axial: float, shear: float,
                 force: tuple[float, float], elements: int = 64,
                 load_steps: int = 20) -> np.ndarray:
    """Tip position (x, y) [mm] of the clamped geometrically exact beam under a tip force.

    Parameters
    ----------
    length : float
        Beam length L [mm].
    bending, axial, shear : float
        EI [N·mm²], EA [N] and κGA [N].
    force : (float, float)
        Dead tip force (F_x, F_y) [N], x along the undeformed axis.
    elements : int
        Number of beam elements.
    load_steps : int
        Static load steps.

    Raises
    ------
    RuntimeError
        If the static solve does not converge.
    """
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    element_length = length / elements
    nodes = [mbs.AddNode(eii.NodeRigidBody2D(referenceCoordinates=[i * element_length, 0.0, 0.0],
                                             visualization=eii.VNodeRigidBody2D(show=False)))
             for i in range(elements + 1)]
    for first, second in zip(nodes, nodes[1:], strict=False):
        mbs.AddObject(eii.ObjectBeamGeometricallyExact2D(
            nodeNumbers=[first, second], length=element_length,
            massPerLength=1.0, crossSectionInertia=1.0,  # a static solve: inertia unused
            bendingStiffness=bending, axialStiffness=axial, shearStiffness=shear,
            visualization=eii.VObjectBeamGeometricallyExact2D(show=False)))
    ground = mbs.AddNode(eii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    fixed = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    for coordinate in range(3):
        clamp = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=coordinate))
        mbs.AddObject(eii.CoordinateConstraint(markerNumbers=[fixed, clamp],
                                               visualization=eii.VCoordinateConstraint(show=False)))
    tip = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=nodes[-1]))
    mbs.AddLoad(eii.LoadForceVector(markerNumber=tip, loadVector=[force[0], force[1], 0.0]))
    mbs.Assemble()
    try:
        mbs.SolveStatic(static_settings(load_steps, "EigenSparse"))
    except exu.SolverError as err:
        raise RuntimeError(f"geometrically exact beam: static solve failed ({err})") from None
    return np.asarray(mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position))[:2]
