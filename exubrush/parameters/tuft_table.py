"""Reading a head's tufts from a CSV table (``head.tuft_table``).

One row per tuft, one column per :class:`~exubrush.parameters.head.Tuft` field, the unit of
every quantity in the header, e.g.::

    # name,x [mm],y [mm],diameter [mm],filaments,material
    name,x [mm],y [mm],diameter [mm],filaments,material
    front,-8,0,1.6,37,nylon

Text columns (name, packing, section, material) and the count ``filaments`` take no unit
(``[-]`` or ``[1]`` is accepted for the count). Columns that are left out, and empty cells,
take the field's default; ``x`` and ``y`` are required. Every cell is read and checked like
the same key in a case file (units converted with pint, ranges and choices enforced), and a
message names the file, the line and the column.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from exubrush.parameters.fields import ParameterError, build
from exubrush.parameters.head import Tuft
from exubrush.util.tables import read_rows, split_header

REQUIRED = ("x", "y")
COUNT_UNITS = ("", "1", "-")


def read_tuft_table(path: str | Path, most: int) -> tuple[Tuft, ...]:
    """The tufts of a CSV tuft table (see module docstring), each named after its ``name``
    cell or, without one, after the file and line.

    Raises
    ------
    ParameterError
        One line naming the file and, where it applies, the line and column: a file that
        cannot be read, more than ``most`` tufts (limits.bristles: each tuft has a filament
        at least), a column without a unit or of an unknown name, a cell that is not a
        number of the column's unit or is out of range.
    """
    name = f"head.tuft_table {str(path)!r}"
    try:
        rows = read_rows(path, "head.tuft_table")
    except ValueError as err:
        raise ParameterError(str(err)) from None
    if len(rows) < 2:
        raise ParameterError(f"{name} needs a header and at least one tuft row, found "
                             f"{len(rows)} lines")
    if len(rows) - 1 > most:
        raise ParameterError(f"{name} has {len(rows) - 1:,} tufts, more than limits.bristles "
                             f"= {most:,}; to read it anyway, --set "
                             f"limits.bristles={len(rows) - 1}")
    header = split_header(rows[0][1])
    _check_header(name, header)
    tufts = []
    for line, cells in rows[1:]:
        if len(cells) > len(header):
            raise ParameterError(f"{name}, line {line}: {len(cells)} cells for {len(header)} "
                                 "columns")
        data = {}
        for (label, unit), cell in zip(header, cells, strict=False):
            if cell.strip():
                data[label] = _value(name, line, label, unit, cell.strip())
        data.setdefault("name", f"{Path(path).name} line {line}")
        try:
            tufts.append(build(Tuft, data, "tuft."))
        except ParameterError as err:
            raise ParameterError(f"{name}, line {line}: {err}") from None
    return tuple(tufts)


def _kinds() -> dict[str, str]:
    """Field name -> "text", "count" or the internal unit of a quantity."""
    kinds = {}
    for f in dataclasses.fields(Tuft):
        unit = f.metadata["unit"]
        kinds[f.name] = "count" if f.type in ("int", int) else unit
    return kinds


def _check_header(name: str, header: list[tuple[str, str]]) -> None:
    kinds = _kinds()
    labels = [label for label, _ in header]
    for label, unit in header:
        if label not in kinds:
            raise ParameterError(f"{name}: unknown column {label!r}; known columns: "
                                 f"{', '.join(kinds)}")
        if labels.count(label) > 1:
            raise ParameterError(f"{name}: column {label!r} appears twice")
        kind = kinds[label]
        if kind == "text" and unit:
            raise ParameterError(f"{name}: column {label!r} holds text and takes no unit, "
                                 f"got [{unit}]")
        if kind == "count" and unit not in COUNT_UNITS:
            raise ParameterError(f"{name}: column {label!r} is a count and takes no unit, "
                                 f"got [{unit}]")
        if kind not in ("text", "count") and not unit:
            raise ParameterError(f"{name}: column {label!r} has no unit; write "
                                 f"'{label} [{kind}]' (or another unit of that dimension)")
    missing = [label for label in REQUIRED if label not in labels]
    if missing:
        raise ParameterError(f"{name} has no column {' or '.join(repr(m) for m in missing)}; "
                             "every tuft needs its position 'x [mm]' and 'y [mm]'")


def _value(name: str, line: int, label: str, unit: str, cell: str):
    """A cell as the case file would hold it: text, a whole number or 'value unit'."""
    kind = _kinds()[label]
    if kind == "text":
        return cell
    if kind == "count":
        try:
            return int(cell)
        except ValueError:
            raise ParameterError(f"{name}, line {line}, column {label!r}: {cell!r} is not a "
                                 "whole number") from None
    try:
        float(cell)
    except ValueError:
        raise ParameterError(f"{name}, line {line}, column {label!r}: {cell!r} is not a "
                             "number") from None
    return f"{cell} {unit}"
