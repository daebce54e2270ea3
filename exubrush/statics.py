"""Static solutions of single bristle models in Exudyn (for convergence checks)."""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from exubrush.models.assembly import rigid_marker
from exubrush.models.dfm import add_dfm_bristle
from exubrush.models.geometry import BristleGeometry
from exubrush.models.prb import add_prb_bristle
from exubrush.parameters.case import Material
from exubrush.solver import static_settings


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
    """Shortening [mm] of a PRB bristle with the buckling link (exubrush.models.buckling),
    clamped at its root, its tip held on the bristle's axis (free to slide along it and to
    rotate: a pinned tip) and pushed along the axis towards the root by ``force`` [N]."""
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
