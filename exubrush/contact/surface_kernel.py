"""Compiled kernel of the tip-sphere contact with an analytic surface (numba; mm-N-s).

The same law as exubrush.contact.laws.sphere_surface_force over the features of
exubrush.world.surfaces (plane, cylinder, sphere, tooth row), for one sphere state at a time in
scalar code, and the generalized forces it puts on a tip node with Euler parameters,
with their derivatives: so that an Exudyn ``ObjectGenericODE2`` (contact.backend
"paper-compiled", exubrush.contact.exudyn_contact) computes the contact and its Jacobian
instead of Exudyn evaluating and differentiating the symbolic law, which on a tooth row
cost 395 µs a Jacobian and 20 µs a residual (docs/decisions/0018).
tests/unit/test_surface_kernel.py checks the law against the generic one at random states.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from exubrush.parameters import surface_kinds as kinds

PLANE, CYLINDER, SPHERE, TOOTH_ROW = 0, 1, 2, 3
_KINDS = {kinds.PLANE: PLANE, kinds.CYLINDER: CYLINDER, kinds.SPHERE: SPHERE,
          kinds.TOOTH_ROW: TOOTH_ROW}
_TINY = 1e-300  # as exubrush.world.surfaces
MAX_FEATURES = 3
_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}


# The law array the kernel takes (law_numbers): the ContactLaw field of each entry, and the
# entry's index by name, which the kernel reads (``law[STATIC_FRICTION]``, numba folds the
# module's integers into constants). A new parameter of the law is one name in each list.
LAW_FIELDS = ("stiffness", "stiffness_exponent", "damping", "damping_rate_exponent",
              "damping_depth_exponent", "static_friction", "dynamic_friction",
              "static_velocity", "dynamic_velocity")
(STIFFNESS, STIFFNESS_EXPONENT, DAMPING, DAMPING_RATE_EXPONENT, DAMPING_DEPTH_EXPONENT,
 STATIC_FRICTION, DYNAMIC_FRICTION, STATIC_VELOCITY, DYNAMIC_VELOCITY) = range(len(LAW_FIELDS))


def law_numbers(law) -> np.ndarray:
    """The law's parameters (a ContactLaw's, mm-N-s) as the kernel takes them:
    ``law_numbers(law)[STATIC_FRICTION] == law.static_friction`` for each of LAW_FIELDS."""
    return np.array([getattr(law, name) for name in LAW_FIELDS], float)


def surface_numbers(surface) -> tuple[int, np.ndarray]:
    """(kind code, parameters): R for a cylinder or sphere; w, g, h, ρ for a tooth row."""
    kind = _KINDS[surface.kind]
    if kind in (CYLINDER, SPHERE):
        return kind, np.array([surface.radius], float)
    if kind == TOOTH_ROW:
        return kind, np.array([surface.tooth_width, surface.gap_width, surface.gap_depth,
                               surface.edge_radius], float)
    return kind, np.zeros(0)


@njit(**_JIT)
def _normal_force(law, penetration, rate):
    depth = max(penetration, 0.0)
    sign = 1.0 if rate > 0.0 else (-1.0 if rate < 0.0 else 0.0)
    elastic = law[STIFFNESS] * depth ** law[STIFFNESS_EXPONENT]
    dissipative = (law[DAMPING] * sign * abs(rate) ** law[DAMPING_RATE_EXPONENT]
                   * depth ** law[DAMPING_DEPTH_EXPONENT])
    return max(elastic + dissipative, 0.0)


@njit(**_JIT)
def _friction_per_speed(law, slip_square, drop):
    """μ(v)/v of exubrush.contact.laws.friction_per_speed; ``drop`` < 0: not lagged."""
    mu_s, mu_d = law[STATIC_FRICTION], law[DYNAMIC_FRICTION]
    vs, vd = law[STATIC_VELOCITY], law[DYNAMIC_VELOCITY]
    creeping = mu_s / vs * (1.5 - 0.5 / (vs * vs) * slip_square)
    speed = math.sqrt(max(slip_square, vs * vs))
    if drop >= 0.0:
        return drop * (creeping if slip_square < vs * vs else mu_s / speed)
    eta = min((speed - vs) / (vd - vs), 1.0)
    sliding = (mu_s + (mu_d - mu_s) * (eta * eta) * (3.0 - 2.0 * eta)) / speed
    return creeping if slip_square < vs * vs else sliding


@njit(**_JIT)
def _add_feature_load(law, radius, nx, ny, nz, distance, v, w, scale, drop, out):
    """Add one feature's force and moment on the sphere (exubrush.contact.laws.
    sphere_feature_force) to ``out`` where the sphere reaches it (d < r)."""
    if not distance < radius:
        return
    cx = v[0] + -radius * (w[1] * nz - w[2] * ny)
    cy = v[1] + -radius * (w[2] * nx - w[0] * nz)
    cz = v[2] + -radius * (w[0] * ny - w[1] * nx)
    normal_speed = v[0] * nx + v[1] * ny + v[2] * nz
    sx, sy, sz = cx - normal_speed * nx, cy - normal_speed * ny, cz - normal_speed * nz
    force_n = _normal_force(law, radius - distance, -normal_speed)
    slip_square = sx * sx + sy * sy + sz * sz
    factor = -scale * force_n * _friction_per_speed(law, slip_square, drop)
    arm = -radius * factor
    out[0] += force_n * nx + factor * sx
    out[1] += force_n * ny + factor * sy
    out[2] += force_n * nz + factor * sz
    out[3] += arm * (ny * sz - nz * sy)
    out[4] += arm * (nz * sx - nx * sz)
    out[5] += arm * (nx * sy - ny * sx)


@njit(**_JIT)
def _round(a, b, c, radius, ball):
    """Normal (3) and distance of the outside of a ball (or a cylinder along y, ball
    False) of ``radius`` centred at the origin of (a, b, c) (exubrush.world.surfaces)."""
    square = a * a + b * b + c * c if ball else a * a + c * c
    length = math.sqrt(square)
    inverse = 1.0 / max(length, _TINY)
    return a * inverse, (b * inverse if ball else 0.0), c * inverse, length - radius


@njit(**_JIT)
def _tooth(params, u, z):
    """The feature of one tooth centred at u = 0 that the point (u, z) is closest to:
    normal (3) and distance (exubrush.world.surfaces._tooth_feature)."""
    width, rho = params[0], params[3]
    half = 0.5 * width
    b = z + rho
    sign = 1.0 if u >= 0.0 else -1.0
    along = u if u >= 0.0 else -u
    a = along - (half - rho)
    if a > 0.0:
        if b > 0.0:
            corner = math.sqrt(a * a + b * b)
            inverse = 1.0 / max(corner, _TINY)
            return sign * a * inverse, 0.0, b * inverse, corner - rho
        return sign, 0.0, 0.0, along - half
    if a > b:
        return sign, 0.0, 0.0, along - half
    return 0.0, 0.0, 1.0, z


@njit(**_JIT)
def surface_load(kind, params, law, radius, centre, v, w, scale, drops, out):
    """Force on the sphere [N] and moment about its centre [N·mm] (``out``, 6), surface
    frame, summed over the surface's features in the order of exubrush.world.surfaces.features;
    ``drops`` one lagged drop ratio per feature (negative: the implicit law), ``scale``
    the friction's factor (the friction window)."""
    for i in range(6):
        out[i] = 0.0
    x, y, z = centre[0], centre[1], centre[2]
    if kind == PLANE:
        _add_feature_load(law, radius, 0.0, 0.0, 1.0, z, v, w, scale, drops[0], out)
    elif kind == CYLINDER or kind == SPHERE:
        nx, ny, nz, d = _round(x, y, z + params[0], params[0], kind == SPHERE)
        _add_feature_load(law, radius, nx, ny, nz, d, v, w, scale, drops[0], out)
    else:
        pitch = params[0] + params[1]
        u = x - pitch * math.floor(x / pitch + 0.5)
        nx, ny, nz, d = _tooth(params, u, z)
        _add_feature_load(law, radius, nx, ny, nz, d, v, w, scale, drops[0], out)
        index = 1
        if 2.0 * radius > params[1]:
            nx, ny, nz, d = _tooth(params, u - pitch if u >= 0.0 else u + pitch, z)
            _add_feature_load(law, radius, nx, ny, nz, d, v, w, scale, drops[1], out)
            index = 2
        _add_feature_load(law, radius, 0.0, 0.0, 1.0, z + params[2], v, w, scale,
                          drops[index], out)


@njit(**_JIT)
def node_load(q, q_t, reference, turn, origin, kind, params, law, radius, scale, drops, out,
              local):
    """Generalized forces (``out``, 7) of the contact on a rigid-body node with Euler
    parameters: its coordinates ``q`` (displacement and parameters less ``reference``) and
    their rates ``q_t``; the surface frame's axes ``turn`` (3x3, columns) and origin
    ``origin`` [mm] in the global frame. The force acts at the node (the sphere's centre);
    the moment M enters as Gᵀ M with ω = G ψ' (Exudyn's Euler-parameter G)."""
    e0, e1 = reference[3] + q[3], reference[4] + q[4]
    e2, e3 = reference[5] + q[5], reference[6] + q[6]
    d0, d1, d2, d3 = q_t[3], q_t[4], q_t[5], q_t[6]
    wx = 2.0 * (-e1 * d0 + e0 * d1 - e3 * d2 + e2 * d3)
    wy = 2.0 * (-e2 * d0 + e3 * d1 + e0 * d2 - e1 * d3)
    wz = 2.0 * (-e3 * d0 - e2 * d1 + e1 * d2 + e0 * d3)
    centre = np.empty(3)
    velocity = np.empty(3)
    omega = np.empty(3)
    for i in range(3):
        centre[i] = (turn[0, i] * (reference[0] + q[0] - origin[0])
                     + turn[1, i] * (reference[1] + q[1] - origin[1])
                     + turn[2, i] * (reference[2] + q[2] - origin[2]))
        velocity[i] = turn[0, i] * q_t[0] + turn[1, i] * q_t[1] + turn[2, i] * q_t[2]
        omega[i] = turn[0, i] * wx + turn[1, i] * wy + turn[2, i] * wz
    surface_load(kind, params, law, radius, centre, velocity, omega, scale, drops, local)
    mx = turn[0, 0] * local[3] + turn[0, 1] * local[4] + turn[0, 2] * local[5]
    my = turn[1, 0] * local[3] + turn[1, 1] * local[4] + turn[1, 2] * local[5]
    mz = turn[2, 0] * local[3] + turn[2, 1] * local[4] + turn[2, 2] * local[5]
    for i in range(3):
        out[i] = turn[i, 0] * local[0] + turn[i, 1] * local[1] + turn[i, 2] * local[2]
    out[3] = 2.0 * (-e1 * mx - e2 * my - e3 * mz)
    out[4] = 2.0 * (e0 * mx + e3 * my - e2 * mz)
    out[5] = 2.0 * (-e3 * mx + e0 * my + e1 * mz)
    out[6] = 2.0 * (e2 * mx - e1 * my + e0 * mz)


# central-difference steps of the Jacobian: coordinates [mm or -] and their rates
POSITION_STEP = 1e-8
VELOCITY_STEP = 1e-5


@njit(**_JIT)
def _both_sides(q, q_t, varied, column, step, reference, turn, origin, kind, params, law,
                radius, scale, drops, plus, minus, local):
    """node_load with ``varied`` (q or q_t itself) moved by ±``step`` in ``column``."""
    held = varied[column]
    varied[column] = held + step
    node_load(q, q_t, reference, turn, origin, kind, params, law, radius, scale, drops, plus,
              local)
    varied[column] = held - step
    node_load(q, q_t, reference, turn, origin, kind, params, law, radius, scale, drops, minus,
              local)
    varied[column] = held


@njit(**_JIT)
def node_jacobian(q, q_t, reference, turn, origin, kind, params, law, radius, scale, drops,
                  f_position, f_velocity, triplets):
    """−(∂f/∂q · f_position + ∂f/∂q_t · f_velocity) of :func:`node_load` by central
    differences, as (row, column, value) ``triplets`` (49, 3): Exudyn's Jacobian user
    function of an ObjectGenericODE2."""
    plus = np.empty(7)
    minus = np.empty(7)
    local = np.empty(6)
    moved = q.copy()
    rates = q_t.copy()
    for column in range(7):
        _both_sides(moved, rates, moved, column, POSITION_STEP, reference, turn, origin, kind,
                    params, law, radius, scale, drops, plus, minus, local)
        for row in range(7):
            triplets[7 * column + row, 0] = row
            triplets[7 * column + row, 1] = column
            triplets[7 * column + row, 2] = -f_position * (plus[row] - minus[row]) / (
                2.0 * POSITION_STEP)
        _both_sides(moved, rates, rates, column, VELOCITY_STEP, reference, turn, origin, kind,
                    params, law, radius, scale, drops, plus, minus, local)
        for row in range(7):
            triplets[7 * column + row, 2] -= f_velocity * (plus[row] - minus[row]) / (
                2.0 * VELOCITY_STEP)
