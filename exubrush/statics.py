"""Static solutions of single bristle models in Exudyn (for convergence checks)."""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

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
