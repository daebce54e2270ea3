"""Friction without creep: a stick/slip law with a state per tip contact, on the plane z = 0
(pure, mm-N-s units; ``contact.friction_model = "stick-slip"``).

The paper's friction (exubrush.contact.laws.friction_coefficient) has no stick state: below
μ_s F_n a loaded tip slides at a speed under v_s (it creeps). This law is its Coulomb limit
written as an elastic-plastic return map (the "reset integrator" of Haessig & Friedland
1991, and the tangential spring of most discrete-element codes):

- The tip's contact point is tied to an **anchor** on the plane by a tangential spring. Its
  stretch u is the contact point's travel since the anchor was set, counting the sphere's
  rolling: the point of the sphere at the contact moves with v + ω × (−r e_z), so u
  tracks p_xy + r (−φ_y, φ_x), φ the rotation.
- **Stick** while |w| <= s_e, w = u + τ v_c the stretch and its rate (v_c the contact
  point's slip velocity, τ ``contact.stick_damping_time``), s_e ``contact.stick_stretch``
  (1 µm by default): F_t = −μ_s F_n w / s_e, a spring and a damper in parallel (a
  Kelvin-Voigt element; without the damper the spring rings undamped wherever a step
  resolves it). The spring stores the ratio F_t / F_n, so a change of F_n while the tip
  sticks changes F_t in proportion (a Mindlin contact's tangential stiffness grows with
  the load too, as F_n^(1/3); here simply as F_n).
- **Slip** beyond: F_t = −μ F_n w/|w|, with μ = μ_s r, r the paper's drop from μ_s at v_s
  to μ_d at v_d (exubrush.contact.laws.friction_drop) taken at the slip speed of the
  step's start, so F_t has no derivative in the slip speed. Where the friction rises with
  the speed instead (μ_d > μ_s), r is taken at the current slip speed: a rise taken a step
  behind lets a light tip swing between too little friction and too much from step to
  step (one bristle of the paper's head with μ_s = 0.6 took 41,234 Jacobians against 133),
  and a rising friction is what Newton handles well (as in the paper's law, whose rise is
  never lagged: exubrush.contact.laws.drop_can_lag). Between steps the anchor is
  dragged along so that |u| <= s_e (:func:`committed_state`): a sliding tip is held back
  by μ F_n against its travel (w turns from u towards v_c as the slip speed exceeds
  s_e / τ), and a tip that stops, or turns back, sticks at once.
- **Touchdown in stick**: a tip off the plane carries its anchor along with it (u = 0).

Within a step the anchor and the rolling's linearisation are fixed (the law is then a
function of the state alone); between steps :func:`committed_state` moves them. Exudyn
calls a pre-step function before every step attempt, with the state of the last accepted
step, so committing there is committing once per accepted step, and committing again at
the same state changes nothing.

The state is six numbers (:data:`STATE_SIZE`), Exudyn's connector offset:
``(a_x, a_y, j_xy, j_xz, j_yz, r)``: the anchor [mm] in the coordinates of the track
p_xy + J φ, the rolling's matrix J (2x3) at the step's start [mm/rad], and the drop ratio.
φ are the tip's Tait-Bryan angles (x, y, z) relative to the plane, the connector's
``rotation``, whose rates give ω = G(φ) φ' with G's columns e_x, R_x e_y, R_x R_y e_z;
the rows of −r e_z × G give J: J = r [[0, −cos φ_x, sin φ_x cos φ_y], [1, 0, sin φ_y]],
so J_yx = r and J_xx = J_yy = 0 are not stored.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from exubrush.contact.laws import (
    drop_can_lag,
    drop_ratios,
    friction_drop,
    normal_force,
    plane_slip,
)
from exubrush.util.float_math import FLOAT_MATH

if TYPE_CHECKING:  # the law reads the parameters' attributes only
    from exubrush.parameters.case import ContactLaw

STATE_SIZE = 6  # (anchor x, anchor y, J_xy, J_xz, J_yz, drop ratio)
ANCHOR_X, ANCHOR_Y, J_XY, J_XZ, J_YZ, DROP = range(STATE_SIZE)


def rolling_matrix(radius: float, rotation) -> tuple[float, float, float]:
    """The stored entries (J_xy, J_xz, J_yz) [mm/rad] of J at the Tait-Bryan angles
    ``rotation`` [rad] (module text): the contact point's travel r (−ω_y, ω_x) dt = J dφ."""
    angle_x, angle_y = rotation[0], rotation[1]
    return (-radius * math.cos(angle_x), radius * math.sin(angle_x) * math.cos(angle_y),
            radius * math.sin(angle_y))


def stretch(radius: float, centre, rotation, state):
    """The tangential spring's stretch u (x, y) [mm]: the track p_xy + J φ less the
    anchor, J the state's (works on floats and on Exudyn's symbolic expressions)."""
    track_x = centre[0] + state[J_XY] * rotation[1] + state[J_XZ] * rotation[2]
    track_y = centre[1] + radius * rotation[0] + state[J_YZ] * rotation[2]
    return track_x - state[ANCHOR_X], track_y - state[ANCHOR_Y]


def stick_slip_plane_force(law: ContactLaw, radius: float, centre, rotation, velocity, omega,
                           state, m=FLOAT_MATH, friction_scale=1.0):
    """Force and moment of the plane z = 0 on a sphere with this law.

    Parameters
    ----------
    radius : float
        Sphere radius r [mm].
    centre, rotation, velocity, omega : sequence of 3
        Centre position [mm], Tait-Bryan angles [rad], centre velocity [mm/s] and angular
        velocity [rad/s] of the sphere in the plane's frame.
    state : sequence of 6
        The contact's state (module text; :func:`committed_state`).
    friction_scale : float or expression
        Factor on the friction force (friction switched on smoothly after the approach).

    Returns
    -------
    list of 6
        Force on the sphere [N] and moment about its centre [N·mm], plane frame: F_t acts
        at the contact point −r e_z, its moment (r F_ty, −r F_tx, 0).
    """
    force_n = normal_force(law, radius - centre[2], -velocity[2], m)
    u_x, u_y = stretch(radius, centre, rotation, state)
    slip_x, slip_y = plane_slip(radius, velocity, omega)
    w_x = u_x + law.stick_damping_time * slip_x
    w_y = u_y + law.stick_damping_time * slip_y
    length = m.max(m.sqrt(w_x * w_x + w_y * w_y), law.stick_stretch)
    if drop_can_lag(law):
        drop = state[DROP]
    else:
        drop = friction_drop(law, m.sqrt(slip_x * slip_x + slip_y * slip_y + 1e-12), m)
    scale = -friction_scale * law.static_friction * drop * force_n / length
    force_x, force_y = scale * w_x, scale * w_y
    return [force_x, force_y, force_n, radius * force_y, -radius * force_x, 0.0]


def committed_state(law: ContactLaw, radius: float, centre, rotation, velocity, omega,
                    state) -> list[float]:
    """The state a step starts from, given the tip at the end of the last accepted step
    (plane frame, as :func:`stick_slip_plane_force`) and the state that step used.

    Off the plane (the centre at or above r) the anchor follows the tip (u = 0: touchdown
    sticks); a stretch beyond s_e is pulled back to s_e along itself (the slip's plastic
    part); the rolling's J is renewed at the tip's angles and the drop ratio at its slip
    speed (exubrush.contact.laws.drop_ratios on the plane, the paper's slip). Committing
    a committed state again leaves it as it is.
    """
    u_x, u_y = stretch(radius, centre, rotation, state)
    length = math.hypot(u_x, u_y)
    if centre[2] >= radius:
        u_x = u_y = 0.0
    elif length > law.stick_stretch:
        u_x, u_y = u_x * law.stick_stretch / length, u_y * law.stick_stretch / length
    j_xy, j_xz, j_yz = rolling_matrix(radius, rotation)
    renewed = [0.0, 0.0, j_xy, j_xz, j_yz, 0.0]
    track_x, track_y = stretch(radius, centre, rotation, renewed)
    (drop,) = drop_ratios(law, radius, None, centre, velocity, omega)
    return [track_x - u_x, track_y - u_y, j_xy, j_xz, j_yz, drop]
