"""Units: the package's internal system and the parsing of unit-labelled inputs.

Internally exubrush works in **mm, N, s and tonne** (t). That system is consistent
(1 N = 1 t·mm/s²), so stresses come out in MPa (N/mm²) and densities in t/mm³, and the
paper's contact coefficients (k in N/mm^1.3, c in N·s/mm³) are used as printed.

Inputs from case files and the command line carry their unit as text, e.g. ``"7.5 MPa"``,
and are converted with pint. A dimensional input without a unit is refused rather than
guessed.
"""

from __future__ import annotations

import functools
import math

import pint


class UnitError(ValueError):
    """A value has no unit, an unknown unit or a unit of the wrong dimension."""


@functools.cache
def registry() -> pint.UnitRegistry:
    """Return the package's pint unit registry (created once)."""
    return pint.UnitRegistry()


def to_internal(text: str | float | int, unit: str) -> float:
    """Convert a unit-labelled value to the internal unit ``unit``.

    Parameters
    ----------
    text : str or number
        ``"7.5 MPa"``, ``"1100 kg/m^3"``, ``"100 N/mm^1.3"``... A bare number is accepted only
        when ``unit`` is dimensionless (``"1"``).
    unit : str
        Target unit in the internal system, e.g. ``"mm"``, ``"N/mm^2"``, ``"t/mm^3"``.

    Returns
    -------
    float
        The magnitude in ``unit``.

    Raises
    ------
    UnitError
        If the text has no unit where one is needed, does not parse, or has the wrong
        dimension.
    """
    ureg = registry()
    target = ureg.Unit(unit)
    if isinstance(text, bool):
        raise UnitError(f"expected a number, got {text!r}")
    if isinstance(text, int | float):
        if target.dimensionless:
            return float(text)
        raise UnitError(f"{text!r} has no unit; write it with one, e.g. '{text} {unit}'")
    try:
        quantity: pint.Quantity = ureg.Quantity(str(text).strip())
        if not isinstance(quantity, pint.Quantity):
            quantity = ureg.Quantity(quantity)
        magnitude = float(quantity.magnitude)
    except Exception as err:  # noqa: BLE001 - pint's parser raises many types on free text
        reason = " ".join(str(err).split()) or type(err).__name__
        raise UnitError(f"cannot read {text!r} as a quantity ({reason})") from None
    if not math.isfinite(magnitude):
        raise UnitError(f"{text!r} is not a finite number")
    if quantity.dimensionless and not target.dimensionless:
        raise UnitError(f"{text!r} has no unit; write it with one, e.g. '{text} {unit}'")
    try:
        return float(quantity.to(target).magnitude)
    except pint.errors.DimensionalityError:
        raise UnitError(
            f"{text!r} has unit '{quantity.units:~}', which cannot be converted to '{unit}'"
        ) from None


def format_quantity(value: float, unit: str) -> str:
    """Write ``value`` (in unit ``unit``) as the text a case file uses, e.g. ``"7.5 MPa"``.

    Twelve significant digits: unit conversions leave round-off in the last of the 17
    digits of a double (1100 kg/m³ would print as 1099.9999999999998), which a case file
    should not show.
    """
    return f"{float(value):.12g} {unit}"
