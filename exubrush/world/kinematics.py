"""The handle's prescribed motion in the head frame and the head force (pure, mm-N-s-t).

The handle is driven through coordinate constraints; their reaction is the force the
handle's coordinates exert on the drive. The head's force on the surface is its negative,
minus the m·a of the handle (each solved group of bristles has a handle of its own), plus
what moving the bristles' root pieces costs, which ride on the handle in no body of the
system (:func:`carried_wrench`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from exubrush.world.motion import HeadMotion
from exubrush.world.pose import (
    angular_acceleration,
    angular_velocity,
    g_matrix,
    rotation_matrix,
)

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


def handle_angles(motion: HeadMotion, times: np.ndarray):
    """The head's Tait-Bryan angles [rad], their rates [rad/s] and accelerations [rad/s²]
    at every time of ``times``: three (n, 3) arrays (zero without pose terms)."""
    if motion.pose is None:
        zero = np.zeros((len(times), 3))
        return zero, zero.copy(), zero.copy()
    values = np.array([[part[3:] for part in motion.pose.evaluate(t)] for t in times])
    values = values.reshape(len(times), 3, 3)  # no times (a run stopped before any): (0, 3, 3)
    return values[:, 0], values[:, 1], values[:, 2]


def head_moment(moment_reactions: Sequence[np.ndarray], handle_inertias: Sequence[np.ndarray],
                angles: np.ndarray, rates: np.ndarray,
                accelerations: np.ndarray) -> np.ndarray:
    """Moment of the head on the surface about the handle's node (the head frame's origin,
    the roots' surface at the head's centre) [N·mm], (n, 3), surface frame.

    The drive's reaction on the handle's rotation coordinates is a generalised force λ,
    conjugate to the Tait-Bryan angles θ: a torque τ does the work of λ where Gᵀ τ = λ
    (ω = G θ̇, exubrush.world.pose). As for :func:`head_force`, the head's moment is
    −Σ G⁻ᵀ λ minus the handles' own rate of angular momentum, I α + ω × I ω with
    I = A I_body Aᵀ about each handle's centre of mass (its node).

    Parameters
    ----------
    moment_reactions : sequence of (n, 3) arrays
        λ of each solved group's rotation coordinates [N·mm] on the same time grid.
    handle_inertias : sequence of (3, 3) arrays
        Each group's handle inertia about its centre of mass, body frame [t·mm²].
    angles, rates, accelerations : (n, 3) arrays
        θ [rad], θ̇ [rad/s], θ̈ [rad/s²] of the head.
    """
    total = sum(moment_reactions, np.zeros_like(angles))
    body = sum(handle_inertias, np.zeros((3, 3)))
    moment = np.empty_like(angles)
    for k, (theta, turn, omega, alpha) in enumerate(_turning(angles, rates, accelerations)):
        inertia = turn @ body @ turn.T
        moment[k] = (-np.linalg.solve(g_matrix(theta).T, total[k])
                     - inertia @ alpha - np.cross(omega, inertia @ omega))
    return moment


def _turning(angles: np.ndarray, rates: np.ndarray, accelerations: np.ndarray):
    """(θ, A, ω, α) at each sample of the head's angles θ [rad], rates θ̇ [rad/s] and
    accelerations θ̈ [rad/s²]: its rotation matrix, angular velocity [rad/s] and angular
    acceleration [rad/s²] in the surface frame (exubrush.world.pose)."""
    for theta, rate, acceleration in zip(angles, rates, accelerations, strict=True):
        yield (theta, rotation_matrix(theta), angular_velocity(theta, rate),
               angular_acceleration(theta, rate, acceleration))


class CarriedLoad(NamedTuple):
    """A rigid load that rides on the handle: the bristles' root pieces, part of the
    prescribed body but in no body of the Exudyn system (exubrush.output.assemble).

    Attributes
    ----------
    mass : float
        m [t].
    first_moment : (3,) array
        m c, c its centre of mass from the handle's node, head frame [t·mm].
    inertia : (3, 3) array
        Its inertia about the handle's node, head frame [t·mm²].
    """

    mass: float
    first_moment: np.ndarray
    inertia: np.ndarray


def carried_wrench(load: CarriedLoad, acceleration: np.ndarray, angles: np.ndarray,
                   rates: np.ndarray, accelerations: np.ndarray) -> tuple[np.ndarray,
                                                                       np.ndarray]:
    """Force [N] and moment about the handle's node [N·mm] that the head spends on moving
    ``load`` with it, (n, 3) each, surface frame: the rate of its momentum,

        m a + α × A mc + ω × (ω × A mc),

    and of its angular momentum about its centre plus the moment of that force about the
    node, which for a rigid body reads (about the node, I_O = A I Aᵀ)

        I_O α + ω × I_O ω + A mc × a.

    Parameters
    ----------
    acceleration : (n, 3) array
        The handle node's acceleration a [mm/s²].
    angles, rates, accelerations : (n, 3) arrays
        θ [rad], θ̇ [rad/s], θ̈ [rad/s²] of the head (:func:`handle_angles`).
    """
    force = np.empty_like(acceleration)
    moment = np.empty_like(acceleration)
    for k, (_, turn, omega, alpha) in enumerate(_turning(angles, rates, accelerations)):
        offset = turn @ load.first_moment
        inertia = turn @ load.inertia @ turn.T
        force[k] = (load.mass * acceleration[k] + np.cross(alpha, offset)
                    + np.cross(omega, np.cross(omega, offset)))
        moment[k] = (inertia @ alpha + np.cross(omega, inertia @ omega)
                     + np.cross(offset, acceleration[k]))
    return force, moment


def in_head_frame(vectors: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Vectors (n, 3) given in the surface frame, in the turned head frame's axes: Aᵀ v."""
    return np.array([rotation_matrix(theta).T @ v for v, theta in zip(vectors, angles,
                                                                       strict=True)])
