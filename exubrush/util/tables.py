"""Reading unit-labelled CSV tables (slide profiles, measured forces).

A table is a CSV file whose header names every column with its unit in brackets, e.g.
``time [s],slider_position [mm],normal_force [N]``. Blank lines and lines starting with
``#`` (provenance, comments) are skipped, and so is a UTF-8 byte-order mark at the file's
start. A column without a unit is refused, not guessed, and so are two columns of one label
(``x [mm]`` and ``x [cm]``), a label that differs from a column's only in case (``Y [mm]``)
and a row with more cells than the header (a decimal comma); the
unit is converted with pint, so ``[ms]``, ``[m]`` or ``[mN]`` are read as well.
"""

from __future__ import annotations

import csv
from collections.abc import Collection
from pathlib import Path

import numpy as np


def read_unit_table(path: str | Path, columns: dict[str, str], what: str,
                    optional: Collection[str] = ()) -> dict[str, np.ndarray]:
    """Read the named columns of a unit-labelled CSV, converted to internal units.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    columns : dict
        Column label -> internal unit, e.g. ``{"time": "s", "normal_force": "N"}``. Other
        columns of the file are ignored.
    what : str
        What the file is, for messages (e.g. ``"slide CSV"``).
    optional : collection of str
        Labels of ``columns`` the file may lack; a missing one is left out of the result.
        A present one is read as any other (its unit is required).

    Returns
    -------
    dict
        Label -> values (float array) in the internal unit, for each column the file has.

    Raises
    ------
    ValueError
        With the file, line and column at fault: missing file, too few rows, a missing
        column or unit, two columns of one label, a label that differs from one of
        ``columns`` only in case, a unit of the wrong dimension, a row with more cells than
        the header has columns, a cell that is not a number.
    """
    name = f"{what} {str(path)!r}"
    rows = read_rows(path, what)
    if len(rows) < 3:
        raise ValueError(f"{name} needs a header and at least two rows, found {len(rows)} lines")
    labels = split_header(rows[0][1])
    _check_layout(name, rows, labels, columns, optional)
    data = {}
    for label, target in columns.items():
        same = [cell.strip() for cell, (other, _) in zip(rows[0][1], labels, strict=True)
                if other == label]
        if len(same) > 1:
            raise ValueError(f"{name} has {len(same)} columns for '{label}' "
                             f"({', '.join(map(repr, same))}); keep one")
        index = next((k for k, (other, _) in enumerate(labels) if other == label), None)
        if index is None:  # optional (_check_layout refused a required one missing)
            continue
        data[label] = _column(name, rows, index, label, labels[index][1], target)
    return data


def _check_layout(name: str, rows: list[tuple[int, list[str]]],
                  labels: list[tuple[str, str]], columns: dict[str, str],
                  optional: Collection[str]) -> None:
    """Refuse a header label that differs from one of ``columns`` only in case, a required
    column (not ``optional``) missing, and a row with more cells than the header has
    columns (ValueError naming the file ``name``), in that order: a file that is no such
    table at all is told by its missing column, not by the cells of some line."""
    wanted = {label.casefold(): label for label in columns}
    for label, unit in labels:  # 'Y [mm]' beside 'x [mm]' would be ignored as another column
        meant = wanted.get(label.casefold())
        if meant is not None and meant != label:
            raise ValueError(f"{name}: column '{label}' is not '{meant}' (labels are case "
                             f"sensitive); write '{meant} [{unit or columns[meant]}]'")
    present = {label for label, _ in labels}
    missing = [label for label in columns if label not in present and label not in optional]
    if missing:
        raise ValueError(f"{name} has no column '{missing[0]} [unit]'")
    for line, row in rows[1:]:  # "1,5" for 1.5 would shift the cells after it
        if any(cell.strip() for cell in row[len(labels):]):
            raise ValueError(f"{name}: line {line} has {len(row)} cells for {len(labels)} "
                             "columns (a decimal comma? write 1.5, not 1,5)")


def _column(name: str, rows: list[tuple[int, list[str]]], index: int, label: str, unit: str,
            target: str) -> np.ndarray:
    """The cells of column ``index`` (``label [unit]``) of the data ``rows`` in the internal
    unit ``target`` (ValueError naming the file ``name``, line and column at fault)."""
    from exubrush.util.units import MissingUnitError, UnitError, to_internal

    if not unit:
        raise ValueError(f"{name}: column '{label}' has no unit; write '{label} [{target}]'")
    try:
        factor = to_internal(f"1 {unit}", target)
    except MissingUnitError:  # [1], [%]: a number where an angle or length is meant
        raise ValueError(f"{name}: column '{label} [{unit}]' has no unit of '{target}'; "
                         f"write '{label} [{target}]' or another unit of that "
                         "dimension") from None
    except UnitError as err:
        raise ValueError(f"{name}: column '{label}': {err}") from None
    values = []
    for line, row in rows[1:]:
        try:
            values.append(float(row[index]))
        except (ValueError, IndexError):
            cell = row[index] if index < len(row) else ""
            raise ValueError(
                f"{name}: line {line}, column '{label}': {cell!r} is not a number"
            ) from None
    with np.errstate(over="ignore"):  # 1e308 km: inf, which the caller refuses
        return np.array(values) * factor


def read_rows(path: str | Path, what: str) -> list[tuple[int, list[str]]]:
    """(line number, cells) of every row of a CSV file that is neither blank nor a ``#``
    comment, the header first.

    Raises
    ------
    ValueError
        Naming the file: missing, not a file, not UTF-8 text or unreadable.
    """
    path = Path(path)
    name = f"{what} {str(path)!r}"
    if not path.exists():
        broken = " (a link to nothing)" if path.is_symlink() else ""
        raise ValueError(f"{name} does not exist{broken}")
    if not path.is_file():
        raise ValueError(f"{name} is not a file")
    try:
        # utf-8-sig: a byte-order mark, which spreadsheet programs write, is not text
        with path.open(newline="", encoding="utf-8-sig") as handle:
            return [
                (line, row)
                for line, row in enumerate(csv.reader(handle), start=1)
                if any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#")
            ]
    except UnicodeDecodeError as err:
        raise ValueError(f"{name} is not UTF-8 text (byte {err.start})") from None
    except (OSError, csv.Error) as err:
        raise ValueError(f"{name} cannot be read ({getattr(err, 'strerror', None) or err})"
                         ) from None


def split_header(cells: list[str]) -> list[tuple[str, str]]:
    """(label, unit) of each header cell ``label [unit]``; the unit is "" if none is given."""
    header = []
    for cell in cells:
        label, _, unit = cell.strip().partition("[")
        header.append((label.strip(), unit.rstrip("]").strip()))
    return header


def check_time_axis(times: np.ndarray, *values: np.ndarray) -> None:
    """Refuse non-finite samples and times that do not increase strictly (ValueError)."""
    if not all(np.all(np.isfinite(v)) for v in (times, *values)):
        raise ValueError("a table must hold finite numbers only")
    steps = np.flatnonzero(np.diff(times) <= 0.0)
    if steps.size:
        k = steps[0] + 1
        raise ValueError(f"times must increase strictly, but sample {k + 1} is at "
                         f"{times[k]:g} s after {times[k - 1]:g} s")
