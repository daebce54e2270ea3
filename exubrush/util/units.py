"""Units: the package's internal system and the parsing of unit-labelled inputs.

Internally exubrush works in **mm, N, s and tonne** (t). That system is consistent
(1 N = 1 t·mm/s²), so stresses come out in MPa (N/mm²) and densities in t/mm³, and the
paper's contact coefficients (k in N/mm^1.3, c in N·s/mm³) are used as printed.

Inputs from case files and the command line carry their unit as text, e.g. ``"7.5 MPa"``,
and are converted with pint. A dimensional input without a unit is refused rather than
guessed.

pint is imported only where a unit-labelled text is read or an unusual unit converted:
its import and registry cost about 0.9 s, which ``exubrush case`` and a run of a built-in
case would otherwise pay for nothing (they read no unit text and show values in the few
units of :data:`CONVERSION_FACTORS`).
"""

from __future__ import annotations

import functools
import math
import re
from typing import TYPE_CHECKING, cast

if TYPE_CHECKING:
    import pint
    from pint.facets.plain import PlainUnit

# value in unit b = value in unit a x factor, for the units the case parameters declare
# and display. The factors are pint's own, to the last bit (pint composes them from its
# definitions: 1.0000000000000002e-12, not 1e-12, for kg/m^3 -> t/mm^3), so that a case
# reads to the same doubles with or without pint; tests/unit/test_units.py checks each
# against pint and that every pair the parameters declare is here.
CONVERSION_FACTORS = {
    ("rad", "deg"): 57.29577951308232,
    ("deg", "rad"): 0.017453292519943295,
    ("s", "ms"): 1000.0,
    ("ms", "s"): 0.001,
    ("s", "us"): 1000000.0,
    ("us", "s"): 1e-06,
    ("mm", "um"): 1000.0,
    ("um", "mm"): 0.001,
    ("t/mm^3", "kg/m^3"): 999999999999.9999,
    ("kg/m^3", "t/mm^3"): 1.0000000000000002e-12,
    ("B", "GB"): 1e-09,
    ("GB", "B"): 1000000000.0,
}
# "<decimal number> <unit>", the form exubrush writes and its case files use
_NUMBER_AND_UNIT = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s+(\S+)\s*")


FREQUENCY = {"[time]": -1}  # pint's dimensionality of Hz


class UnitError(ValueError):
    """A value has no unit, an unknown unit or a unit of the wrong dimension."""


class MissingUnitError(UnitError):
    """A value that needs a unit is a bare number (``90``, ``"0.5"``, ``"1 1"``, ``"5 %"``)."""


@functools.cache
def registry() -> pint.UnitRegistry:
    """Return the package's pint unit registry (created once)."""
    import pint

    return pint.UnitRegistry()


def convert(value: float, unit: str, target: str) -> float:
    """``value`` in ``unit`` expressed in ``target`` (both pint unit texts), e.g.
    ``convert(0.5, "s", "ms") == 500.0``; the pairs of :data:`CONVERSION_FACTORS` and equal
    units without pint."""
    if unit == target:
        return float(value)
    factor = CONVERSION_FACTORS.get((unit, target))
    if factor is not None:
        return float(value) * factor
    return float(registry().Quantity(value, unit).to(target).magnitude)


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
        If the text has no unit where one is needed (MissingUnitError), does not parse, or
        has the wrong dimension. An angle is a dimension here, as it is not in pint: a bare
        number is no angle, an angle no number. An angle per time (rpm, rad/s) is read as a
        frequency [Hz] in turns per time.
    """
    if isinstance(text, bool):
        raise UnitError(f"expected a number, got {text!r}")
    if isinstance(text, int | float) and unit == "1":
        return float(text)
    if isinstance(text, str):
        known = _known_quantity(text, unit)
        if known is not None:
            return known
    import pint

    ureg = registry()
    target = ureg.Unit(unit)
    wanted = _angle_power(target)
    if isinstance(text, int | float):
        if target.dimensionless and wanted == 0:
            return float(text)
        raise MissingUnitError(f"{text!r} has no unit; write it with one, e.g. "
                        f"{_example(text, unit, wanted)}")
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
    if not re.search(r"\d", str(text)):  # pint reads "deg" as 1 deg, "mm" as 1 mm
        raise UnitError(f"{text!r} has no number; write one with its unit, e.g. '2 {unit}'")
    given = _angle_power(quantity.units)
    if quantity.unitless and not (target.dimensionless and wanted == 0):
        raise MissingUnitError(f"{text!r} has no unit; write it with one, e.g. "
                        f"{_example(magnitude, unit, wanted)}")
    if given == wanted + 1 and target.dimensionality == FREQUENCY:
        # an angle per time (rpm, rad/s, deg/s) as a frequency: the turns it makes per
        # time, 1 rpm = 1/60 Hz, 1 rad/s = 1/(2π) Hz (docs/motion.md, "Units")
        target = ureg.turn * target
    elif given != wanted and quantity.dimensionality == target.dimensionality:
        # pint counts the radian as dimensionless: '2 rad' would be the number 2
        raise UnitError(f"{text!r} has unit '{quantity.units:~}', which cannot be converted "
                        f"to '{unit}' (an angle is not a number in exubrush)")
    try:
        return float(quantity.to(target).magnitude)
    except pint.errors.DimensionalityError:
        raise UnitError(
            f"{text!r} has unit '{quantity.units:~}', which cannot be converted to '{unit}'"
        ) from None


def _angle_power(unit: PlainUnit) -> float:
    """The power of the radian in ``unit`` written in pint's root units: 1 for deg, turn and
    rpm (rad/s), 0 for Hz, mm or a bare number. pint counts the radian as dimensionless, so
    its own dimension check lets a bare number stand for an angle; this one does not."""
    root = registry().Quantity(1.0, unit).to_root_units()
    return cast(float, dict(root.unit_items()).get("radian", 0.0))  # pint types it Number


def _example(number: float, unit: str, angle: float) -> str:
    """How to write ``number`` with a unit that converts to ``unit`` (an angle: in deg or
    rad, for the user to say which is meant)."""
    if angle == 1 and registry().Unit(unit).dimensionless:
        return f"'{number:.12g} deg' or '{number:.12g} rad'"
    return f"'{number:.12g} {unit}'"


def _known_quantity(text: str, unit: str) -> float | None:
    """``text`` in ``unit`` where it is a plain "<number> <unit>" whose unit is ``unit`` or
    converts to it by :data:`CONVERSION_FACTORS` (pint gives the same double); None for
    anything else, which pint then reads."""
    match = _NUMBER_AND_UNIT.fullmatch(text)
    if match is None:
        return None
    number, written = float(match[1]), match[2]
    factor = 1.0 if written == unit else CONVERSION_FACTORS.get((written, unit))
    if factor is None or not math.isfinite(number):
        return None
    return number * factor


def format_quantity(value: float, unit: str) -> str:
    """Write ``value`` (in unit ``unit``) as the text a case file uses, e.g. ``"7.5 MPa"``.

    Twelve significant digits: unit conversions leave round-off in the last of the 17
    digits of a double (1100 kg/m³ would print as 1099.9999999999998), which a case file
    should not show.
    """
    return f"{float(value):.12g} {unit}"
