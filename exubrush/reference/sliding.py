"""Exact normal force of a bristle sliding steadily on a plane with Coulomb friction.

A straight bristle of length ``L`` and bending stiffness ``EI`` is clamped with its axis
normal to the plane. Its tip sphere (radius ``r``) slides steadily on the plane with
Coulomb friction μ, so the plane pushes on the contact point with the normal force ``N``
and the friction force μN against the sliding direction: a force of fixed direction,
applied a distance ``r`` beyond the tip centre along the plane normal. Inertia and rates
play no part in steady sliding, so the bristle is an Euler elastica (inextensible,
unshearable) with that tip load.

In the elastica frame of :mod:`exubrush.reference.elastica` (clamp at the origin, axis
along +x towards the plane, lengths scaled by ``L``, α = P L²/EI, force P(cos a, sin a)),
the load has a = π - atan(μ) (compressive, with the transverse part along +y), and the
contact point lies at (x₁ + ρ, y₁), ρ = r/L. Moment equilibrium of the part beyond a
section gives the same equation as without the offset, θ'' = -α sin(a - θ), with the
boundary conditions

    θ(0) = 0,   θ'(1) = α ρ sin a   (the friction force's moment about the tip centre),

and the height condition x(1) = h, h = (root-to-tip-centre distance) / L, fixes α. The
boundary-value problem is solved with ``scipy.integrate.solve_bvp`` (tolerance 1e-10),
started from the exact elastica without the offset (:func:`solve_cantilever`, its load
found by bisection on the height), which keeps it on the primary branch; then
N = P cos(atan μ).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_bvp


def _guess_without_offset(h: float, angle: float):
    """α and centreline of the elastica without the tip offset reaching x(1) = h."""
    from scipy.optimize import brentq

    from exubrush.reference.elastica import solve_cantilever

    def shortfall(alpha):
        return solve_cantilever(alpha, angle).tip_x - h

    high = 1.0
    while shortfall(high) > 0.0:
        high *= 2.0
        if high > 1e4:
            raise RuntimeError(f"no load shortens the bristle to h = {h:g}")
    alpha = brentq(shortfall, 0.0, high, xtol=1e-13, rtol=1e-13)
    return alpha, solve_cantilever(alpha, angle)


def _solve_with_offset(h: float, angle: float, rho: float):
    alpha, shape = _guess_without_offset(h, angle)
    s = shape.s
    curvature = np.gradient(shape.theta, s)
    guess = np.vstack([shape.theta, curvature, shape.x])

    def rhs(_s, y, p):
        return np.vstack([y[1], -p[0] * np.sin(angle - y[0]), np.cos(y[0])])

    def bc(ya, yb, p):
        return np.array([ya[0], ya[2], yb[1] - p[0] * rho * math.sin(angle), yb[2] - h])

    return solve_bvp(rhs, bc, s, guess, p=np.array([alpha]), tol=1e-10, max_nodes=100_000)


def sliding_load_index(height_ratio: float, friction: float, offset_ratio: float) -> float:
    """Load index α = P L²/EI of the steadily sliding bristle [-].

    Parameters
    ----------
    height_ratio : float
        Distance from the root to the tip-sphere centre along the plane normal, over L, in
        (0.3, 1): the bristle is pressed shorter than its length.
    friction : float
        Coulomb friction coefficient μ > 0.
    offset_ratio : float
        Tip radius over length, r/L >= 0 (the contact point's offset from the tip centre).

    Raises
    ------
    ValueError
        For arguments outside their ranges; RuntimeError if the solve fails.
    """
    if not 0.3 < height_ratio < 1.0:
        raise ValueError(f"height_ratio must lie in (0.3, 1), got {height_ratio!r}")
    if not friction > 0.0:
        raise ValueError(f"friction must be positive, got {friction!r}")
    if not offset_ratio >= 0.0:
        raise ValueError(f"offset_ratio must be non-negative, got {offset_ratio!r}")
    solution = sliding_shape(height_ratio, friction, offset_ratio)
    return float(solution.p[0])


def sliding_shape(height_ratio: float, friction: float, offset_ratio: float):
    """The solved boundary-value problem (``scipy`` BVP result: ``sol(s)`` gives θ, θ', x;
    ``p[0]`` is α) for arguments already checked by :func:`sliding_load_index`."""
    angle = math.pi - math.atan(friction)
    solution = _solve_with_offset(height_ratio, angle, offset_ratio)
    if not solution.success:
        raise RuntimeError(f"sliding elastica did not converge at h = {height_ratio:.4f}: "
                           f"{solution.message}")
    return solution


def sliding_normal_force(height: float, friction: float, length: float,
                         bending_stiffness: float, tip_radius: float = 0.0) -> float:
    """Normal force N [N] of a bristle sliding steadily with its tip centre at ``height``.

    Parameters
    ----------
    height : float
        Root-to-tip-centre distance along the plane normal [mm].
    friction : float
        Coulomb friction coefficient μ [-].
    length : float
        Free length L, root to tip-sphere centre [mm].
    bending_stiffness : float
        EI about the bending axis [N·mm²].
    tip_radius : float
        Tip sphere radius r [mm] (the contact point lies r beyond the tip centre).
    """
    alpha = sliding_load_index(height / length, friction, tip_radius / length)
    return alpha * bending_stiffness / length**2 * math.cos(math.atan(friction))
