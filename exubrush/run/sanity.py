"""Physical bounds that a brushing result must respect (pure).

The largest force a real bristle can put on the plane is reached when it stays straight
and is compressed along its axis by the whole interference δ = l + r - d: E·A·δ/l. Any
bent shape carries less. A load applied suddenly can at most double a static response, so
a head force beyond 2·Σ E·A·δ/l (over the bristles that reach) is not physics but a
numerical failure or a model that cannot bend (a jammed PRB link).

The drive's reaction also carries inertia: the handle's own m·a (removed from the head's
force afterwards, but not from the reaction a solve checks as it goes) and the bristles'
mass carried along. A group whose bristles cannot reach the surface has a contact bound
of 0 N and pushes with nothing but that inertia (2.6e-6 N on one filament's handle during
the approach). :func:`inertia_allowance` adds INERTIA_FACTOR times the rigid m·a of the
handle and the bristles at the head's largest acceleration: the integration's
error of the handle's m·a is a share of m·a itself (docs/motion.md: up to 94 % of a
side force's RMS at 20 steps a cycle), and a free filament driven at its first bending
resonance swings with an amplification of about 1/(2ζ) = 9 (ζ = ω τ/2 = 0.055 for a
0.2 mm nylon filament at 348.6 Hz and the 0.05 ms damping time), so 10 covers both. A
blow-up's forces are orders of magnitude beyond it (1e8 N).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from exubrush.models.geometry import BristleGeometry, can_reach
from exubrush.parameters.case import Case

DYNAMIC_FACTOR = 2.0  # a suddenly applied load at most doubles the static response
INERTIA_FACTOR = 10.0  # the inertia allowance over rigid m·a (see module docstring)
# the words every message of a solve stopped beyond its bound contains
BEYOND_BOUND = "exceeds the physical bound"


def static_force_limits(case: Case, bristles: Sequence[BristleGeometry],
                        distances: Sequence[float] | None = None) -> tuple[float, ...]:
    """E·A·δ/l of each bristle [N]: its force straight and fully compressed (0 if it cannot
    reach the surface), δ = l + r - d with d its root's distance from the surface at its
    closest [mm] (``distances``, one per bristle: exubrush.run.prepared.root_distances;
    default: motion.interaction_distance for every root)."""
    if distances is None:
        distances = [case.motion.interaction_distance] * len(bristles)
    return tuple(b.material.youngs_modulus * b.section.area * (b.length + b.tip_radius - d)
                 / b.length if can_reach(b, d) else 0.0
                 for b, d in zip(bristles, distances, strict=True))


def normal_force_bound(limits: Sequence[float]) -> float:
    """Upper bound of the normal force [N] of bristles with :func:`static_force_limits`
    ``limits`` (see module docstring)."""
    total = 0.0
    for limit in limits:
        total += limit
    return DYNAMIC_FACTOR * total


def bristle_mass(bristles: Sequence[BristleGeometry]) -> float:
    """Mass of the bristles' free lengths [t]: ρ A l summed (tip spheres left out)."""
    total = 0.0
    for b in bristles:
        total += b.material.density * b.section.area * b.length
    return total


def inertia_allowance(mass: float, peak_acceleration: float) -> float:
    """What a drive's reaction may carry beyond the contact forces [N]: INERTIA_FACTOR
    times ``mass`` [t] at ``peak_acceleration`` [mm/s²] (see module docstring)."""
    return INERTIA_FACTOR * mass * peak_acceleration


def within_bound(reaction: np.ndarray, bound: float) -> np.ndarray:
    """Per sample, whether the normal force of a drive's ``reaction`` (n, 3) [N], its z
    component, is within the physical ``bound`` [N] (a NaN counts as within: finiteness is
    checked apart, and told apart in the message)."""
    return np.abs(np.nan_to_num(reaction[:, 2])) <= bound


def beyond_bound_message(model: str, t: float, force: float, bound: float) -> str:
    """Why a solve stopped at a normal force [N] beyond the ``bound`` [N], and what to do."""
    if model == "prb":
        cause = ("the rigid PRB link jams where a real bristle would buckle (high friction or "
                 "deep interference); use the DFM model for this case")
    else:
        cause = "a numerical blow-up; try a smaller solver.step_size or a softer contact"
    return (f"normal force {force:.4g} N at t = {t:.6g} s {BEYOND_BOUND} "
            f"{bound:.4g} N (every bristle straight and fully compressed, x2, and "
            f"{INERTIA_FACTOR:g} x the rigid m a of the handle and bristles): {cause}")
