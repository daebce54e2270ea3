"""Quantities derived from force and slide series (pure, mm-N-s units)."""

from __future__ import annotations

import numpy as np

NO_CONTACT_FORCE = 1e-6  # N; below this the head does not touch and μ_eff is undefined


def travelled_distance(slider_position: np.ndarray) -> np.ndarray:
    """Cumulative slide path Σ|Δs| [mm] of a slider position series [mm]."""
    return np.concatenate([[0.0], np.cumsum(np.abs(np.diff(slider_position)))])


def friction_coefficient(normal_force: np.ndarray, tangential_force: np.ndarray) -> np.ndarray:
    """|F_t| / F_n [-], NaN where F_n is below :data:`NO_CONTACT_FORCE` (undefined)."""
    ratio = np.full_like(normal_force, np.nan, dtype=float)
    touching = normal_force > NO_CONTACT_FORCE
    ratio[touching] = np.abs(tangential_force[touching]) / normal_force[touching]
    return ratio
