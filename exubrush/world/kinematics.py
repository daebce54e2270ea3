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


HEAD_ORIGIN = np.zeros((1, 3))  # the handle's node: the head frame's origin at t = 0


def handle_kinematics(motion: HeadMotion, slide_axis: np.ndarray, t: float):
    """Handle displacement from its start [mm], velocity [mm/s], acceleration [mm/s²] at t:
    the slide and the descent, plus what the pose terms (about the pivot) add."""
    s, v, a = motion.sliding(t)
    z, vz, az = motion.descent(t)
    position = s * slide_axis + z * DOWN
    velocity = v * slide_axis + vz * DOWN
    acceleration = a * slide_axis + az * DOWN
    if motion.pose is not None:
        moved, moving, turning = motion.pose.point_motion(HEAD_ORIGIN, t)
        position, velocity, acceleration = (
            position + moved[0], velocity + moving[0], acceleration + turning[0])
    return position, velocity, acceleration


def handle_coordinates(motion: HeadMotion, slide_axis: np.ndarray, t: float) -> np.ndarray:
    """The handle node's six coordinates at t: its displacement [mm] and its Tait-Bryan
    angles (rx, ry, rz) [rad] (exubrush.world.pose), as the drive prescribes them."""
    angles = np.zeros(3) if motion.pose is None else motion.pose.evaluate(t)[0][3:]
    return np.concatenate([handle_kinematics(motion, slide_axis, t)[0], angles])


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
