"""Axial spring of the PRB link: a pushed bristle buckles and its chord shortens.

Howell's pseudo-rigid-body link has a fixed length γl. A real bristle pushed along its
chord (tip ahead of the root after a stroke reversal) buckles into an S shape, its chord
shortens at a nearly constant force, and the tip passes under the root: the bristle snaps
through. A link of fixed length cannot pass under its pivot when γl exceeds the pivot's
height above the tip-centre plane, and stays pushed. So the link gets one more degree of
freedom, a slide along its axis, held by this spring (compression positive: ``s`` > 0
shortens the link, ``F`` > 0 pushes the tip towards the pivot):

    F(s) = smin(k_a s,  P_b q(x)) - F(0),    x = (s - s_b) / L,   s_b = P_b / k_a,

- ``k_a = EA / L``: the straight bristle's axial stiffness (the PRB stub is rigid, so the
  whole bristle's axial compliance sits in the link);
- ``P_b = β² EI_min / L²`` with β = 4.4934 (tan β = β): Euler's load of a column clamped at
  the root and pinned at the tip (Timoshenko & Gere, *Theory of Elastic Stability*, 2nd ed.
  1961, §2.5). The PRB link's rotation already is the clamped-free, C-shaped mode; what it
  cannot represent is the S-shaped mode of a bristle whose tip is held on the surface by
  contact and friction, which is this one;
- ``q(x)``: the post-buckling branch of that column, P/P_b against the chord shortening
  past the onset, from the exact elastica (exubrush.reference.buckled_column): it rises to
  1.1396 at x = 0.4536 and falls beyond, as the tip closes in on the root. The law takes a
  cubic least-squares fit with zero slope at the peak (:data:`POSTBUCKLING_CUBIC`, within
  0.2 % of the exact branch up to the peak), holds the peak beyond it (6 % above the exact
  value at x = 0.6, where the real bristle has long snapped through), and continues
  linearly for x < 0, so that q is smooth (C¹) everywhere;
- ``smin(a, b) = (a + b - sqrt((a - b)² + ε²)) / 2`` with ε = 5 % of P_b: the linear and
  the buckled branch joined smoothly (a kink would stall Newton's method), and ``F(0)``
  subtracted so that the unloaded link keeps its length.

Below P_b the link is as stiff as the bristle is in compression; in tension F = k_a s. The
law is written against a math back end (exubrush.util.float_math.FLOAT_MATH or
``exudyn.symbolic``) so that the same code runs on floats and in Exudyn's C++ expressions.
Units: mm, N.
"""

from __future__ import annotations

from exubrush.util.float_math import FLOAT_MATH

CLAMPED_PINNED_BETA = 4.493409457909064  # smallest positive root of tan β = β
SMOOTHING = 0.05  # ε / P_b of the smooth minimum
# q(x) = 1 + c1 x + c2 x² + c3 x³ on 0 <= x <= PEAK_SHORTENING, with q'(PEAK_SHORTENING) = 0:
# least squares on 100 exact shortenings 0.005 ... 0.4536 (tests/unit/test_buckling.py)
POSTBUCKLING_CUBIC = (0.32078207, 0.58765712, -1.38317402)
PEAK_SHORTENING = 0.45364950


def clamped_pinned_load(bending_stiffness: float, length: float) -> float:
    """Euler's buckling load P_b = β² EI / L² [N] of a column clamped at one end and pinned
    at the other (``bending_stiffness`` EI [N·mm²], ``length`` L [mm])."""
    return CLAMPED_PINNED_BETA**2 * bending_stiffness / length**2


def postbuckling_ratio(x, m=FLOAT_MATH):
    """q(x) = P/P_b of the buckled column at the chord shortening past the onset x = Δ/L
    (module text; ``m`` the math back end)."""
    c1, c2, c3 = POSTBUCKLING_CUBIC
    held = m.min(x, PEAK_SHORTENING)
    return m.IfThenElse(x > 0.0, 1.0 + held * (c1 + held * (c2 + held * c3)), 1.0 + c1 * x)


def _smooth_minimum(a, b, width, m):
    return 0.5 * (a + b - m.sqrt((a - b) * (a - b) + width * width))


def axial_force(shortening, axial_stiffness: float, buckling_load: float, length: float,
                m=FLOAT_MATH):
    """Compressive force F [N] of the link's axial spring at the link ``shortening`` s [mm]
    (negative: stretched), for k_a [N/mm], P_b [N] and the bristle length L [mm]."""
    def law(s, backend):
        onset = buckling_load / axial_stiffness
        buckled = buckling_load * postbuckling_ratio((s - onset) / length, backend)
        return _smooth_minimum(axial_stiffness * s, buckled, SMOOTHING * buckling_load, backend)

    return law(shortening, m) - law(0.0, FLOAT_MATH)
