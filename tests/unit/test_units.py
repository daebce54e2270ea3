"""Unit conversion without pint where it is not needed, checked against pint."""

import dataclasses
import typing

import pytest
from hypothesis import given
from hypothesis import strategies as st

from exubrush.parameters.case import Case
from exubrush.util.units import CONVERSION_FACTORS, convert, registry, to_internal


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

