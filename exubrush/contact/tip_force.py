"""The force of the surface on a tip, read from its contact sensor.

The scene records each tip contact's force with the sensor its back end names
(exubrush.contact.tip_backends, ``force_sensor``); after the solve :func:`force_on_tip`
turns those values into the force on the tip, head frame [N].
"""

from __future__ import annotations

import numpy as np

from exubrush.parameters.choices import EXUDYN_BUILTIN
from exubrush.world.surfaces import orientation

BUILTIN_FORCE_SIGN = 1.0


def force_on_tip(case, values: np.ndarray, frames: np.ndarray | None = None,
                 compiled: bool = False) -> np.ndarray:
    """The contact force on a tip [N], head frame, from its contact sensor's values (n, 3):
    minus the user-function connector's ForceLocal turned out of the connector's frame
    (the surface frame, or on a mesh the recorded rotation matrices ``frames``, rows of 9),
    or the built-in contact's Force as it is (its sign checked in
    tests/integration/test_tip_forces.py), or, ``compiled``, minus the first three of the
    compiled contact's Force (its generalized forces' left-hand side, head frame)."""
    if compiled:
        return -values
    if case.contact.backend == EXUDYN_BUILTIN:
        return BUILTIN_FORCE_SIGN * values
    if frames is not None:
        return -np.einsum("nij,nj->ni", frames.reshape(-1, 3, 3), values)
    return -values @ orientation(case.surface).T
