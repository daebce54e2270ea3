"""The math back end for plain Python floats.

Force laws that Exudyn also runs as symbolic (C++) user functions are written once against
a small "math back end": an object providing ``sqrt``, ``abs``, ``sign``, ``min``, ``max``,
``floor``, ``square`` and ``IfThenElse``. :data:`FLOAT_MATH` evaluates them on floats,
:data:`ARRAY_MATH` element-wise on numpy arrays (both branches of ``IfThenElse`` are
computed there); exubrush.contact.exudyn_contact.SYMBOLIC_MATH records them into an Exudyn
expression tree.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np


def _float_if(condition, if_true, if_false):
    return if_true if condition else if_false


FLOAT_MATH = SimpleNamespace(
    sqrt=math.sqrt,
    abs=abs,
    sign=lambda x: 1.0 if x > 0 else -1.0 if x < 0 else 0.0,
    min=min,
    max=max,
    floor=math.floor,
    square=lambda x: x * x,  # inf past the float range, as a product (x**2 raises)
    IfThenElse=_float_if,
)
"""Math back end for plain Python floats."""

ARRAY_MATH = SimpleNamespace(
    sqrt=np.sqrt,
    abs=np.abs,
    sign=np.sign,
    min=np.minimum,
    max=np.maximum,
    floor=np.floor,
    square=np.square,
    IfThenElse=np.where,
)
"""Math back end for numpy arrays, element-wise."""
