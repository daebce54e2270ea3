"""Physical bounds that a brushing result must respect (pure).

The largest force a real bristle can put on the plane is reached when it stays straight
and is compressed along its axis by the whole interference δ = l + r - d: E·A·δ/l. Any
bent shape carries less. A load applied suddenly can at most double a static response, so
a head force beyond 2·Σ E·A·δ/l (over the bristles that reach) is not physics but a
numerical failure or a model that cannot bend (a jammed PRB link).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from exubrush.models.geometry import BristleGeometry, can_reach
from exubrush.parameters.case import Case

DYNAMIC_FACTOR = 2.0  # a suddenly applied load at most doubles the static response


def static_force_limits(case: Case, bristles: Sequence[BristleGeometry]) -> tuple[float, ...]:
    """E·A·δ/l of each bristle [N]: its force straight and fully compressed (0 if it cannot
    reach the surface)."""
    d = case.motion.interaction_distance
    return tuple(b.material.youngs_modulus * b.section.area * (b.length + b.tip_radius - d)
                 / b.length if can_reach(b, d) else 0.0 for b in bristles)


def normal_force_bound(limits: Sequence[float]) -> float:
    """Upper bound of the normal force [N] of bristles with :func:`static_force_limits`
    ``limits`` (see module docstring)."""
    total = 0.0
    for limit in limits:
        total += limit
    return DYNAMIC_FACTOR * total


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
    return (f"normal force {force:.4g} N at t = {t:.6g} s exceeds the physical bound "
            f"{bound:.4g} N (every bristle straight and fully compressed, x2): {cause}")
