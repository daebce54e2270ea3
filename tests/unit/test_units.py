"""Unit conversion without pint where it is not needed, checked against pint; every unit a
frequency, an angle, a length and a time may be written in, against hand-computed values;
angles as a dimension of their own (pint counts the radian as the number 1)."""

import dataclasses
import math
import typing

import pytest
from hypothesis import given
from hypothesis import strategies as st

from exubrush.parameters.case import Case
from exubrush.util.units import (
    CONVERSION_FACTORS,
    MissingUnitError,
    UnitError,
    convert,
    registry,
    to_internal,
)


def declared_pairs(cls: type) -> set[tuple[str, str]]:
    """Every (internal unit, display unit) a parameter dataclass tree declares."""
    pairs = set()
    hints = typing.get_type_hints(cls)
    for field in dataclasses.fields(cls):
        annotation = hints[field.name]
        entries = typing.get_args(annotation)
        if dataclasses.is_dataclass(annotation):
            pairs |= declared_pairs(annotation)
        elif entries and dataclasses.is_dataclass(entries[0]):
            pairs |= declared_pairs(entries[0])
        elif field.metadata["unit"] not in ("1", "text"):
            pairs.add((field.metadata["unit"], field.metadata["display"]))
    return pairs


def test_every_declared_display_unit_converts_without_pint():
    different = {pair for pair in declared_pairs(Case) if pair[0] != pair[1]}
    assert different, "the walk found no display unit: it does not read the fields"
    both_ways = different | {(display, unit) for unit, display in different}
    assert both_ways <= set(CONVERSION_FACTORS), both_ways - set(CONVERSION_FACTORS)


@pytest.mark.parametrize("pair", sorted(CONVERSION_FACTORS))
def test_factors_are_pints_to_the_last_bit(pair):
    unit, target = pair
    assert CONVERSION_FACTORS[pair] == registry().Quantity(1.0, unit).to(target).magnitude


def pints_reading(text: str, unit: str) -> float:
    return float(registry().Quantity(text).to(unit).magnitude)


@given(number=st.floats(min_value=-1e15, max_value=1e15, allow_nan=False),
       pair=st.sampled_from(sorted(CONVERSION_FACTORS) + [("MPa", "MPa"), ("mm", "mm")]))
def test_unit_text_reads_to_pints_double(number, pair):
    written, unit = pair
    for text in (f"{number!r} {written}", f"{number:.12g} {written}", f" {number:e}  {written} "):
        assert to_internal(text, unit) == pints_reading(text, unit), text


def test_case_file_forms_read_as_pint_reads_them():
    for text, unit in (("1100 kg/m^3", "t/mm^3"), ("0.5 deg", "rad"), ("7.5 MPa", "MPa"),
                       ("100 N/mm^1.3", "N/mm^1.3"), ("5e-05 s", "s"), ("-.5 deg", "rad"),
                       ("2 ms", "s"), ("1.5 GB", "B"), ("3 cm", "mm"), ("2*3 mm", "mm")):
        assert to_internal(text, unit) == pints_reading(text, unit), text


def test_other_units_fall_back_to_pint():
    assert convert(2.0, "mm", "cm") == pytest.approx(0.2, rel=1e-15)
    assert convert(3.5, "mm", "mm") == 3.5


def test_bare_numbers_only_where_dimensionless():
    assert to_internal(3, "1") == 3.0
    with pytest.raises(ValueError, match="has no unit"):
        to_internal(3, "mm")



# Every unit a case file or a table may use for a frequency, an angle, a length and a time,
# with its value worked out by hand from the unit's definition (not from pint): 1 in is
# 25.4 mm exactly, a turn 2π rad, 1 rpm a turn a minute (1/60 Hz), 1 rad/s 1/(2π) Hz.
HAND_COMPUTED = [
    # frequency [Hz]: a sine's cycles per second; an angle per time is its turns per time
    ("260 Hz", "Hz", 260.0),
    ("1.5 kHz", "Hz", 1500.0),
    ("7600 1/min", "Hz", 7600.0 / 60.0),
    ("7600 rpm", "Hz", 7600.0 / 60.0),
    ("7600 revolution/minute", "Hz", 7600.0 / 60.0),
    ("2 rps", "Hz", 2.0),
    ("260 turn/s", "Hz", 260.0),
    ("260 cycle/s", "Hz", 260.0),
    ("100 rad/s", "Hz", 100.0 / (2.0 * math.pi)),
    ("360 deg/s", "Hz", 1.0),
    ("50 1/s", "Hz", 50.0),
    ("3 1/ms", "Hz", 3000.0),
    # angle [rad]
    ("0.5 rad", "rad", 0.5),
    ("90 deg", "rad", math.pi / 2.0),
    ("90 degree", "rad", math.pi / 2.0),
    ("0.25 turn", "rad", math.pi / 2.0),
    ("0.25 revolution", "rad", math.pi / 2.0),
    ("60 arcmin", "rad", math.pi / 180.0),
    ("3600 arcsec", "rad", math.pi / 180.0),
    ("20 mrad", "rad", 0.02),
    # length [mm]
    ("3 mm", "mm", 3.0),
    ("3 cm", "mm", 30.0),
    ("0.003 m", "mm", 3.0),
    ("300 um", "mm", 0.3),
    ("300 µm", "mm", 0.3),
    ("1 in", "mm", 25.4),
    ("1 inch", "mm", 25.4),
    ("1 ft", "mm", 304.8),
    ("1 thou", "mm", 0.0254),
    # time [s]
    ("2 s", "s", 2.0),
    ("2 ms", "s", 0.002),
    ("250 us", "s", 0.00025),
    ("250 µs", "s", 0.00025),
    ("1.5 min", "s", 90.0),
    ("0.5 h", "s", 1800.0),
]


@pytest.mark.parametrize("text, unit, value", HAND_COMPUTED)
def test_every_unit_reads_to_its_hand_computed_value(text, unit, value):
    # a unit conversion: one or two roundings of a product or quotient
    assert to_internal(text, unit) == pytest.approx(value, rel=4e-16, abs=0)


@pytest.mark.parametrize("value", ["90", "0.5", " 90 ", "1 1", "50 %", "5 mm/m", "2*3", 90,
                                   0.5])
def test_a_number_is_no_angle_in_any_form(value):
    # pint counts the radian as the number 1: it would read each of these as radians
    with pytest.raises(MissingUnitError, match="has no unit.*e.g. '.* deg' or '.* rad'"):
        to_internal(value, "rad")


@pytest.mark.parametrize("text, unit", [("2 rad", "1"), ("0.5 turn", "1"), ("1 sr", "rad"),
                                        ("3 mm*rad", "mm"), ("2 rad*s", "s"),
                                        ("5 rad^2/s", "Hz"), ("5 1/rad/s", "Hz")])
def test_an_angle_is_no_number(text, unit):
    with pytest.raises(UnitError, match="cannot be converted.*an angle is not a number"):
        to_internal(text, unit)


@pytest.mark.parametrize("text, unit", [("20 deg", "Hz"), ("7600 rpm", "1"), ("1 Hz", "rad"),
                                        ("7600 rpm", "rad")])
def test_an_angle_per_time_is_a_frequency_only(text, unit):
    with pytest.raises(UnitError, match="cannot be converted to"):
        to_internal(text, unit)


@pytest.mark.parametrize("text, unit", [("deg", "rad"), ("mm", "mm"), (" Hz ", "Hz")])
def test_a_unit_without_a_number_is_refused(text, unit):
    # pint reads a unit alone as one of it: "deg" would be a phase of 1°
    with pytest.raises(UnitError, match="has no number"):
        to_internal(text, unit)
