"""Two parallel cantilevers, a dead tip load on the first pushing it onto the second: the
large-deflection reference of the contact between bristles (mm-N).

Both beams are inextensible and unshearable (Euler elastica), identical (length ``L``,
bending stiffness ``EI``, round section of radius ``r``), clamped upright at x = 0 and
x = 2r + gap, and bend in the x-z plane. A force ``P`` along +x acts on the first one's
tip. The first beam's tip is the centre of a sphere of radius r (the capsule's end cap);
the second beam is a chain of capsules of radius r. Once the tip reaches the second beam
it presses on it without friction; pushed further, the beams also touch along their
length (two 10 mm nylon filaments 0.2 mm thick from about P = 2 mN): every point of each
chain is kept at least 2r from the other chain, and the second beam carries the contact
forces alone.

Method: each beam is a Hencky bar chain (Hencky 1921): ``segments`` rotational springs
of stiffness EI/h at the midpoints s = (j + 1/2) h of the arc length, joined by rigid bars
(half bars at the clamp and at the tip), which makes the chain's compliance the midpoint
rule of the elastica's, with errors of order h². The equilibrium is the minimum of the
springs' energy less the load's work, P x_tip, with those clearances as constraints
(scipy's SLSQP, analytic gradients), reached through load steps from the straight beams.
The contact forces are the constraints' multipliers, found from the equilibrium the
minimum satisfies (the energy's gradient a non-negative combination of the touching
clearances' gradients).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit
from scipy.optimize import minimize, nnls


@dataclass(frozen=True)
class TouchingCantilevers:
    """Equilibrium of the pushed pair.

    Attributes
    ----------
    first, second : ndarray (segments + 2, 2)
        Points of each chain (x, z) [mm], root first, tip last.
    contact_force : ndarray (2,)
        Resultant (x, z) of the contact forces on the second beam [N] (zero if they do
        not touch).
    """

    first: np.ndarray
    second: np.ndarray
    contact_force: np.ndarray

    @property
    def tips(self) -> np.ndarray:
        """Tip positions (2, 2) [mm], first beam's first."""
        return np.array([self.first[-1], self.second[-1]])


def _bars(length: float, segments: int) -> np.ndarray:
    h = length / segments
    return np.r_[0.5 * h, np.full(segments - 1, h), 0.5 * h]


def _points(angles: np.ndarray, bars: np.ndarray, root_x: float) -> np.ndarray:
    """Chain points (x, z) [mm], root first: the clamp's half bar upright, then bars at
    ``angles`` from the vertical (positive towards +x)."""
    theta = np.concatenate(([0.0], angles))
    points = np.zeros((len(bars) + 1, 2))
    np.cumsum(bars * np.sin(theta), out=points[1:, 0])
    np.cumsum(bars * np.cos(theta), out=points[1:, 1])
    points[:, 0] += root_x
    return points


def _point_derivatives(angles: np.ndarray, bars: np.ndarray) -> np.ndarray:
    """d point_i / d angle_j, shape (points, angles, 2): bar j + 1 moves every later point."""
    moved = bars[1:, None] * np.column_stack([np.cos(angles), -np.sin(angles)])
    later = np.arange(len(bars) + 1)[:, None] >= np.arange(len(angles))[None, :] + 2
    return later[:, :, None] * moved[None, :, :]


@njit(cache=True)
def _closest_on_chain(points: np.ndarray, chain: np.ndarray):
    """For each of ``points`` (p, 2): the segment of ``chain`` closest to it (the first of
    equally close ones), the parameter there and the nearest point (p, 2). Compiled: the
    solver asks for it some 10,000 times per load (a numpy version took 80 % of the time)."""
    count = points.shape[0]
    segment, parameter, nearest = np.zeros(count, np.int64), np.zeros(count), np.zeros((count, 2))
    for i in range(count):
        best = np.inf
        for j in range(chain.shape[0] - 1):
            dx, dz = chain[j + 1, 0] - chain[j, 0], chain[j + 1, 1] - chain[j, 1]
            u = ((points[i, 0] - chain[j, 0]) * dx + (points[i, 1] - chain[j, 1]) * dz) / (
                dx * dx + dz * dz)
            u = min(max(u, 0.0), 1.0)
            x, z = chain[j, 0] + u * dx, chain[j, 1] + u * dz
            distance = (x - points[i, 0]) ** 2 + (z - points[i, 1]) ** 2
            if distance < best:
                best = distance
                segment[i], parameter[i], nearest[i, 0], nearest[i, 1] = j, u, x, z
    return segment, parameter, nearest


def touching_cantilevers(length: float, gap: float, radius: float, bending_stiffness: float,
                         load: float, segments: int = 100,
                         load_steps: int = 10) -> TouchingCantilevers:
    """Equilibrium of the pair (module docstring) under the tip load ``load`` [N].

    Parameters
    ----------
    length : float
        Length of each beam, root to tip [mm].
    gap : float
        Clear gap between the upright beams' surfaces [mm].
    radius : float
        Radius of each beam's section and of the tip's cap [mm].
    bending_stiffness : float
        EI [N·mm²].
    segments : int
        Springs per beam (errors of order 1/segments²).
    load_steps : int
        Equal load steps from zero, each solve starting from the last.
    """
    bars = _bars(length, segments)
    k = bending_stiffness / (length / segments)
    second_root = 2.0 * radius + gap
    n = segments

    def split(v):
        return v[:n], v[n:]

    def energy(v, force):
        a, b = split(v)
        bend = 0.5 * k * (np.sum(np.diff(a, prepend=0.0) ** 2)
                          + np.sum(np.diff(b, prepend=0.0) ** 2))
        return bend - force * _points(a, bars, 0.0)[-1, 0]

    def gradient(v, force):
        a, b = split(v)
        grad = []
        for angles in (a, b):
            d = np.diff(angles, prepend=0.0)
            grad.append(k * (d - np.append(d[1:], 0.0)))
        grad[0] = grad[0] - force * _point_derivatives(a, bars)[-1, :, 0]
        return np.concatenate(grad)

    last = {"v": None, "geometry": None}  # SLSQP asks for clearances and gradients at one v

    def geometry(v):
        """Every point of either beam (first's, then second's) against the other beam:
        angles, points (2 (n + 2), 2), the nearest points, the segments and parameters
        there."""
        if last["v"] is None or not np.array_equal(last["v"], v):
            last["v"], last["geometry"] = v.copy(), measured(v)
        return last["geometry"]

    def measured(v):
        angles = (v[:n], v[n:])
        chains = (_points(angles[0], bars, 0.0), _points(angles[1], bars, second_root))
        found = [_closest_on_chain(chains[pressing], chains[1 - pressing])
                 for pressing in (0, 1)]
        return (angles, np.vstack(chains), np.vstack([f[2] for f in found]),
                np.concatenate([f[0] for f in found]), np.concatenate([f[1] for f in found]))

    def clearances(v):
        _, points, nearest, _, _ = geometry(v)
        return np.linalg.norm(points - nearest, axis=1) - 2.0 * radius

    def clearance_gradients(v):
        angles, points, nearest, segment, u = geometry(v)
        normal = (points - nearest) / np.linalg.norm(points - nearest, axis=1)[:, None]
        result = np.zeros((len(points), 2 * n))
        for pressing in (0, 1):
            rows = slice(pressing * (n + 2), (pressing + 1) * (n + 2))
            own = _point_derivatives(angles[pressing], bars)
            other = _point_derivatives(angles[1 - pressing], bars)
            index, w, m = segment[rows], u[rows, None, None], normal[rows][:, None, :]
            moved = (1.0 - w) * other[index] + w * other[index + 1]  # (points, n, 2)
            result[rows, pressing * n:(pressing + 1) * n] = np.sum(own * m, axis=2)
            result[rows, (1 - pressing) * n:(2 - pressing) * n] = -np.sum(moved * m, axis=2)
        return result

    constraints = [{"type": "ineq", "fun": clearances, "jac": clearance_gradients}]

    def balance(v, force):
        """The touching points (indices into geometry's points), their multipliers [N]
        from the equilibrium ∇(energy) = Σ λ ∇(clearance) (non-negative least squares),
        the part of ∇(energy) they leave unbalanced, and the largest overlap [mm]."""
        gaps = clearances(v)
        active = np.nonzero(gaps < 1e-6 * length)[0]
        grad = gradient(v, force)
        multipliers, residual = np.zeros(0), np.linalg.norm(grad)
        if len(active):
            multipliers, residual = nnls(clearance_gradients(v)[active].T, grad)
        return active, multipliers, residual, max(-gaps.min(), 0.0)

    def solve(v, start, end, halvings=0):
        """The equilibrium at the load ``end`` from ``v``, the one at ``start``: SLSQP,
        checked by its clearances and its balance (its converged states here balance the
        load to 2e-4 and stay clear to rounding: 1e-3 and 1e-9 L are the bounds); a step
        that fails the check is taken in two halves (SLSQP ran into its iteration limit on
        one machine's rounding and not on another's)."""
        # the energy in units of the load's linear work, P² L³ / 3EI, so that SLSQP's
        # absolute precision goal means the same at every load
        scale = end**2 * length**3 / (3.0 * bending_stiffness)
        found = minimize(lambda x: energy(x, end) / scale, v, method="SLSQP",
                         jac=lambda x: gradient(x, end) / scale, constraints=constraints,
                         options={"maxiter": 2000, "ftol": 3e-15})
        _, _, residual, violation = balance(found.x, end)
        # relative to the load's part of the energy's gradient
        unbalanced = residual / (end * np.linalg.norm(_point_derivatives(found.x[:n], bars)
                                                      [-1, :, 0]))
        if violation <= 1e-9 * length and unbalanced <= 1e-3:
            return found.x
        if halvings < 4:
            middle = 0.5 * (start + end)
            return solve(solve(v, start, middle, halvings + 1), middle, end, halvings + 1)
        raise RuntimeError(f"touching_cantilevers: no equilibrium at P = {end:g} N "
                           f"({found.message}; overlap {violation:.2g} mm, unbalanced "
                           f"{unbalanced:.2g} of the load)")

    v = np.zeros(2 * n)
    steps = load * np.arange(load_steps + 1) / load_steps
    for start, end in zip(steps[:-1], steps[1:], strict=True):
        v = solve(v, start, end)
    first, second = _points(v[:n], bars, 0.0), _points(v[n:], bars, second_root)
    # the contact forces: the touching points' multipliers along their normals
    active, multipliers, _, _ = balance(v, load)
    _, points, nearest, _, _ = geometry(v)
    normal = points[active] - nearest[active]
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    # on the second beam: −normal where the first's point presses, +normal where its own
    sign = np.where(active >= n + 2, 1.0, -1.0)
    total = (multipliers * sign) @ normal
    return TouchingCantilevers(first, second, total)
