"""Exact post-buckled shape of a column clamped at the root and pinned at the tip.

The inextensible, unshearable elastica of length L and bending stiffness EI: root clamped
at the origin along +x, tip held on the x axis (pinned: free to rotate, no moment) at
x = L - Δ. The tip carries the compressive force P along -x and the lateral reaction R
along -y. With s the arc length over L, θ the tangent angle and α = P L²/EI, ρ = R L²/EI,
the moment about a section, θ' = -ρ(x₁ - x) + α(y₁ - y), gives

    θ'' = ρ cos θ - α sin θ,    x' = cos θ,    y' = sin θ,

    θ(0) = 0,  x(0) = 0,  y(0) = 0,  θ'(1) = 0,  y(1) = 0,  x(1) = 1 - Δ/L,

six conditions for four states and the two unknowns α, ρ. ``scipy.integrate.solve_bvp``
solves it from the first buckling mode, y ∝ β(1 - s) - β cos βs + sin βs with tan β = β,
scaled to the asked shortening. The PRB link's axial law (exubrush.models.buckling) is
fitted to this branch.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_bvp

from exubrush.models.buckling import CLAMPED_PINNED_BETA


def clamped_pinned_load_index(shortening: float) -> float:
    """α = P L²/EI of the clamped-pinned column shortened by ``shortening`` = Δ/L, for
    0 < Δ/L <= 0.6.

    Raises
    ------
    ValueError
        For a shortening outside that range; RuntimeError if the solver fails.
    """
    if not 0.0 < shortening <= 0.6:
        raise ValueError(f"shortening must lie in (0, 0.6], got {shortening!r}")
    beta = CLAMPED_PINNED_BETA
    s = np.linspace(0.0, 1.0, 201)
    slope = -beta + beta**2 * np.sin(beta * s) + beta * np.cos(beta * s)  # y' of the mode
    # amplitude from Δ ≈ ½ ∫ θ² ds, the small-slope shortening
    amplitude = math.sqrt(2.0 * shortening / np.trapezoid(slope**2, s))
    theta = amplitude * slope
    guess = np.vstack([
        theta,
        np.gradient(theta, s),
        np.concatenate([[0.0], np.cumsum(np.cos(0.5 * (theta[1:] + theta[:-1])) * np.diff(s))]),
        np.concatenate([[0.0], np.cumsum(np.sin(0.5 * (theta[1:] + theta[:-1])) * np.diff(s))]),
    ])

    def rhs(_s, y, p):
        alpha, rho = p
        return np.vstack([y[1], rho * np.cos(y[0]) - alpha * np.sin(y[0]), np.cos(y[0]),
                          np.sin(y[0])])

    def bc(ya, yb, p):
        return np.array([ya[0], ya[2], ya[3], yb[1], yb[3], yb[2] - (1.0 - shortening)])

    solution = solve_bvp(rhs, bc, s, guess, p=np.array([beta**2, -amplitude * beta**3]),
                         tol=1e-9, max_nodes=100_000)
    if not solution.success:
        raise RuntimeError(f"clamped-pinned elastica did not converge at Δ/L = "
                           f"{shortening:g}: {solution.message}")
    return float(solution.p[0])
