"""The math back end for plain Python floats.

Force laws that Exudyn also runs as symbolic (C++) user functions are written once against
a small "math back end": an object providing ``sqrt``, ``abs``, ``sign``, ``min``, ``max``
and ``IfThenElse``. :data:`FLOAT_MATH` evaluates them on floats; ``exudyn.symbolic``
records them into an expression tree.
"""

from __future__ import annotations

import math
from types import SimpleNamespace


def _float_if(condition, if_true, if_false):
    return if_true if condition else if_false


FLOAT_MATH = SimpleNamespace(
    sqrt=math.sqrt,
    abs=abs,
    sign=lambda x: (x > 0) - (x < 0),
    min=min,
    max=max,
    IfThenElse=_float_if,
)
"""Math back end for plain Python floats."""
