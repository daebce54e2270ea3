"""Physical bounds that a brushing result must respect (pure).

The largest force a real bristle can put on the plane is reached when it stays straight
and is compressed along its axis by the whole interference δ = l + r - d: E·A·δ/l. Any
bent shape carries less. A load applied suddenly can at most double a static response, so
a head force beyond 2·Σ E·A·δ/l (over the bristles that reach) is not physics but a
numerical failure or a model that cannot bend (a jammed PRB link).
"""

from __future__ import annotations

from exubrush.models.geometry import BristleGeometry, can_reach
from exubrush.parameters.case import Case

DYNAMIC_FACTOR = 2.0  # a suddenly applied load at most doubles the static response


def normal_force_bound(case: Case, bristles: list[BristleGeometry]) -> float:
    """Upper bound of the head's normal force [N] (see module docstring)."""
    d = case.motion.interaction_distance
    E = case.head.material.youngs_modulus
    total = 0.0
    for b in bristles:
        if can_reach(b, d):
            interference = b.length + b.tip_radius - d
            total += E * b.section.area * interference / b.length
    return DYNAMIC_FACTOR * total
