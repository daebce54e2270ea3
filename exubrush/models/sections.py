"""Cross-section properties of a straight bristle (pure functions, mm units).

Axes: x along the bristle; the section's y axis is the head's long axis (width ``b``) and
its z axis runs across the head (height ``h``). ``I_y`` resists bending that moves the tip
along z (across the head), ``I_z`` bending that moves it along y (along the head).

The torsion constant is Saint-Venant's J, not the polar moment: the paper's PRB torsion
spring uses the polar moment, which overestimates the torsional stiffness of a 0.6 x 0.9 mm
blade by about 1.8x (docs/model.md, Torsion). References: Roark's Formulas for Stress and
Strain, 8th ed., table 10.7 (rectangle, ellipse); Cowper (1966) for the shear coefficient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from exubrush.parameters.choices import SECTION_SHAPES


@dataclass(frozen=True)
class SectionProperties:
    """Geometric properties of a cross-section.

    Attributes
    ----------
    area : float
        A [mm²].
    second_moment_y, second_moment_z : float
        I_y = ∫ z² dA and I_z = ∫ y² dA [mm⁴].
    torsion_constant : float
        Saint-Venant torsion constant J [mm⁴].
    shear_coefficient : float
        κ [-]; the shear area is κ·A (the paper's "shear area ratio" is 1/κ).
    """

    area: float
    second_moment_y: float
    second_moment_z: float
    torsion_constant: float
    shear_coefficient: float

    @property
    def polar_moment(self) -> float:
        """I_p = I_y + I_z [mm⁴] (what the paper calls the polar moment of inertia)."""
        return self.second_moment_y + self.second_moment_z


def rectangle_torsion_constant(long_side: float, short_side: float, terms: int = 50) -> float:
    """Saint-Venant torsion constant of a solid rectangle [mm⁴].

    Series solution of the Prandtl stress function (Timoshenko & Goodier, Theory of
    Elasticity, §109): J = a b³ / 3 · (1 - 192/π⁵ · b/a · Σ tanh(nπa/2b)/n⁵, n odd),
    with a the long side and b the short side.
    """
    a, b = max(long_side, short_side), min(long_side, short_side)
    series = sum(
        math.tanh(n * math.pi * a / (2.0 * b)) / n**5 for n in range(1, 2 * terms, 2)
    )
    return a * b**3 / 3.0 * (1.0 - 192.0 / math.pi**5 * b / a * series)


def section_properties(shape: str, width: float, height: float) -> SectionProperties:
    """Section properties of a rectangle or ellipse of ``width`` (y) and ``height`` (z).

    Parameters
    ----------
    shape : {"rectangle", "ellipse", "circle"}
        ``"circle"`` requires ``width == height`` (the diameter).
    width, height : float
        Full extent of the section along y and z [mm].
    """
    if shape not in SECTION_SHAPES:
        raise ValueError(f"unknown section shape {shape!r}; use one of "
                         f"{', '.join(SECTION_SHAPES)}")
    if width <= 0 or height <= 0:
        raise ValueError(f"section width and height must be positive, got {width}, {height}")
    b, h = width, height
    if shape == "rectangle":
        return SectionProperties(
            area=b * h,
            second_moment_y=b * h**3 / 12.0,
            second_moment_z=h * b**3 / 12.0,
            torsion_constant=rectangle_torsion_constant(b, h),
            shear_coefficient=5.0 / 6.0,
        )
    if shape == "circle" and not math.isclose(b, h):
        raise ValueError(f"a circular section needs width == height, got {width} and {height}")
    a_y, a_z = b / 2.0, h / 2.0  # semi-axes
    return SectionProperties(
        area=math.pi * a_y * a_z,
        second_moment_y=math.pi * a_y * a_z**3 / 4.0,
        second_moment_z=math.pi * a_z * a_y**3 / 4.0,
        # exact for an ellipse (Roark table 10.7, case 3); reduces to π r⁴/2 for a circle
        torsion_constant=math.pi * a_y**3 * a_z**3 / (a_y**2 + a_z**2),
        # Cowper (1966): 6(1+ν)/(7+6ν) for a solid circle, 0.89-0.90 for ν = 0.3-0.5;
        # 0.9 is used for ellipses as well
        shear_coefficient=0.9,
    )
