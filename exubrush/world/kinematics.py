"""The handle's prescribed motion in the head frame and the head force (pure, mm-N-s-t).

The handle is driven through coordinate constraints; their reaction is the force the
handle's coordinates exert on the drive. The head's force on the surface is its negative,
minus the m·a of the handle (each solved group of bristles has a handle of its own).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from exubrush.world.motion import HeadMotion

SLIDE_AXES = {"orthogonal": np.array([0.0, 1.0, 0.0]), "parallel": np.array([1.0, 0.0, 0.0])}
DOWN = np.array([0.0, 0.0, -1.0])  # the approach: towards the surface z = 0


def handle_kinematics(motion: HeadMotion, slide_axis: np.ndarray, t: float):
    """Handle displacement from its start [mm], velocity [mm/s], acceleration [mm/s²] at t."""
    s, v, a = motion.sliding(t)
    z, vz, az = motion.descent(t)
    return s * slide_axis + z * DOWN, v * slide_axis + vz * DOWN, a * slide_axis + az * DOWN


def handle_history(motion: HeadMotion, slide_axis: np.ndarray, times: np.ndarray):
    """:func:`handle_kinematics` at every time of ``times``: three (n, 3) arrays."""
    values = np.array([handle_kinematics(motion, slide_axis, t) for t in times])
    values = values.reshape(len(times), 3, 3)
    return values[:, 0], values[:, 1], values[:, 2]


def head_force(reactions: Sequence[np.ndarray], handle_masses: Sequence[float],
               acceleration: np.ndarray) -> np.ndarray:
    """Force of the head on the surface [N], (n, 3), head frame.

    Parameters
    ----------
    reactions : sequence of (n, 3) arrays
        Drive reaction of each solved group [N], on the same time grid.
    handle_masses : sequence of float
        Mass of each group's handle [t].
    acceleration : (n, 3) array
        The handle's prescribed acceleration [mm/s²].

    Returns
    -------
    ndarray (n, 3)
        −Σ reaction − (Σ m) a: the bristles' force with the handles' inertia removed.
    """
    # summed in order, as plain Python sums, so that a result does not depend on how numpy
    # blocks a reduction
    total = sum(reactions, np.zeros_like(acceleration))
    return -total - sum(handle_masses) * acceleration
