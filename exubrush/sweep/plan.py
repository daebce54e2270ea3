"""A sweep file read into the list of runs it asks for (no Exudyn: parameters only).

A sweep file is TOML (``exubrush sweep --example`` prints a commented one)::

    [sweep]            base case, overrides for every run, seeds, a bound on the run count
    [grid]             parameters and their values: every combination is run
    [sample]           count, seed and [sample.ranges]: a Latin hypercube, crossed with the grid
    [execution]        scheduler ("local" or tcp://HOST:PORT), workers, timeout

Every value is checked here, before anything is written: [sweep] and [execution] are
parameter tables (exubrush.sweep.settings) read like a case file's sections, each run's case
is built and validated like a case file, and a fault ends in one line that names the sweep
file, the key and what to write instead.
"""

from __future__ import annotations

import itertools
import json
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, get_origin

import numpy as np

from exubrush.parameters.case import Case
from exubrush.parameters.catalogue import BUILT_IN_CASES
from exubrush.parameters.fields import ParameterError, build, describe_key
from exubrush.parameters.io import load_case, read_toml
from exubrush.sweep.settings import Execution, SweepSettings
from exubrush.util.units import UnitError, convert, to_internal

SECTIONS = {
    "sweep": SweepSettings,
    "grid": None,  # any parameter key
    "sample": ("count", "seed", "ranges"),
    "execution": Execution,
}
RANGE_KEYS = ("from", "to", "count", "scale")
SCALES = ("linear", "log")
NAME_VALUE_DIGITS = 4  # significant digits of a value in a run's folder name


class SweepError(ValueError):
    """A sweep file that cannot be used: the message names the file and the key."""


@dataclass(frozen=True)
class Swept:
    """One varied parameter: its dotted key and the unit its values are given in ("" for
    numbers without a unit and for text)."""

    key: str
    unit: str


@dataclass(frozen=True)
class Varied:
    """What one [grid] entry, the [sample] or the seeds vary: the parameters (columns) and,
    per value, the (key, value) pairs a run gets."""

    columns: tuple[Swept, ...]
    values: list[list[tuple[str, Any]]]


@dataclass(frozen=True)
class SweepRun:
    """One run of a sweep: its folder name, the swept values (in the parameters' display
    units, or text) and its validated case."""

    number: int
    name: str
    values: tuple[tuple[str, Any], ...]
    case: Case = field(repr=False)


@dataclass(frozen=True)
class SweepPlan:
    """A sweep file read and expanded into its runs."""

    name: str
    source: Path
    swept: tuple[Swept, ...]
    runs: tuple[SweepRun, ...]
    execution: Execution


def read_sweep(path: str | Path) -> SweepPlan:
    """Read, check and expand the sweep file ``path`` (SweepError naming what is wrong)."""
    path = Path(path)
    data = read_toml(str(path), "sweep file", SweepError)
    where = path.name
    for section, value in data.items():
        if section not in SECTIONS:
            raise SweepError(f"{where}: unknown section [{section}]; a sweep file has "
                             f"{', '.join(f'[{s}]' for s in SECTIONS)}")
        if not isinstance(value, dict):
            raise SweepError(f"{where}: {section} must be a table [{section}]")
        allowed = SECTIONS[section]
        if isinstance(allowed, tuple):
            unknown = [key for key in value if key not in allowed]
            if unknown:
                raise SweepError(f"{where}: [{section}] {unknown[0]}: unknown key; known "
                                 f"keys: {', '.join(allowed)}")
    settings = _table(SweepSettings, data, "sweep", where)
    execution = _table(Execution, data, "execution", where)
    base = _base_case(settings, path)
    common = list(settings.set)
    seeds = _seeds(settings, "seeds" in data.get("sweep", {}), where)
    limit = settings.max_runs
    grid = data.get("grid", {})
    sample = data.get("sample")
    if not grid and sample is None and seeds is None:
        raise SweepError(f"{where}: nothing varies; give [grid] values, a [sample] or "
                         "sweep.seeds (see 'exubrush sweep --example')")
    varied = [_grid_values(key, value, f"{where}: grid.{key}", limit)
              for key, value in grid.items()]
    if sample is not None:
        varied.append(_sampled(sample, where, set(grid), limit))
    if seeds is not None:
        if "head.seed" in grid:
            raise SweepError(f"{where}: head.seed is in [grid] and in sweep.seeds; use one")
        varied.append(Varied((Swept("head.seed", ""),), [[("head.seed", s)] for s in seeds]))
    swept = tuple(column for group in varied for column in group.columns)
    _check_no_conflict(common, [column.key for column in swept], where)
    expanded = math.prod(len(group.values) for group in varied)  # before making them
    if expanded > limit:
        raise SweepError(f"{where}: expands to {expanded} runs, more than "
                         f"sweep.max_runs = {limit}; check the counts or raise sweep.max_runs")
    combinations = [[pair for part in combo for pair in part]
                    for combo in itertools.product(*(group.values for group in varied))]
    runs = tuple(_run(number, values, base, common, where)
                 for number, values in enumerate(combinations))
    return SweepPlan(settings.name or path.stem, path, swept, runs, execution)


def _table(cls: type, data: dict, section: str, where: str) -> Any:
    """The [section] table read into the parameter dataclass ``cls`` (defaults if absent)."""
    try:
        return build(cls, data.get(section, {}), f"{section}.")
    except ParameterError as err:
        raise SweepError(f"{where}: {err}") from None


def _base_case(settings: SweepSettings, path: Path) -> str:
    """The base case: a built-in name, or a case file relative to the sweep file."""
    if not settings.base:
        raise SweepError(f"{path.name}: sweep.base is missing: name a built-in case "
                         f"({', '.join(BUILT_IN_CASES)}) or a TOML case file")
    if settings.base in BUILT_IN_CASES:
        return settings.base
    return str(path.parent / settings.base)


def _whole(value: Any, where: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise SweepError(f"{where}: expected a whole number >= {minimum}, got {value!r}")
    return value


def _at_most(count: int, limit: int, where: str) -> int:
    """``count`` values, refused before they are made if more than the sweep may run."""
    if count > limit:
        raise SweepError(f"{where}: {count} values are more than sweep.max_runs = {limit} "
                         "runs; lower it or raise sweep.max_runs")
    return count


def _seeds(settings: SweepSettings, given: bool, where: str) -> tuple[int, ...] | None:
    """The seeds to repeat every run with; None if sweep.seeds is left out."""
    if not given:
        return None
    if not settings.seeds:
        raise SweepError(f"{where}: sweep.seeds must be a non-empty list of whole numbers, "
                         "e.g. [1, 2, 3]")
    return settings.seeds


def _parameter(key: str, where: str) -> tuple[Any, Mapping[str, Any]]:
    """Type and metadata of a parameter a sweep may vary."""
    if key == "name":
        raise SweepError(f"{where}: the case name is not a parameter to vary")
    try:
        return describe_key(Case, key, label=where)
    except ParameterError as err:
        raise SweepError(str(err)) from None


def _grid_values(key: str, value: Any, where: str, limit: int) -> Varied:
    """The values of one grid entry: a list or a range (of at most ``limit`` values)."""
    annotation, meta = _parameter(key, where)
    if isinstance(value, dict):
        unit, values = _range_values(value, annotation, meta, where, limit)
        return Varied((Swept(key, unit),), [[(key, v)] for v in values])
    if not isinstance(value, list) or not value:
        raise SweepError(f"{where}: expected a non-empty list of values or a range "
                         "{ from = ..., to = ..., count = ... }")
    if len({json.dumps(v) for v in value}) != len(value):
        raise SweepError(f"{where}: a value is listed twice")
    dimensioned = meta["unit"] not in ("1", "text") and annotation not in (bool, int)
    return Varied((Swept(key, meta["display"] if dimensioned else ""),),
                  [[(key, v)] for v in value])


def _range_values(spec: dict, annotation: Any, meta: Mapping[str, Any], where: str,
                  limit: int) -> tuple[str, list]:
    """Evenly spaced values (linear or logarithmic) of a range, as display-unit texts."""
    unknown = [k for k in spec if k not in RANGE_KEYS]
    if unknown:
        raise SweepError(f"{where}: {unknown[0]}: unknown range key; a range has "
                         f"{', '.join(RANGE_KEYS)}")
    count = spec.get("count")
    if count is None:
        raise SweepError(f"{where}: a range needs count (how many values, >= 2)")
    count = _at_most(_whole(count, f"{where}.count", minimum=2), limit, f"{where}.count")
    low, high, scale, unit = _bounds(spec, annotation, meta, where)
    values = np.geomspace(low, high, count) if scale == "log" else np.linspace(low, high, count)
    return unit, [_quantity(v, unit) for v in values]


def _bounds(spec: dict, annotation: Any, meta: Mapping[str, Any], where: str):
    """from, to (display unit), scale and unit of a range, checked."""
    if annotation in (bool, int) or meta["unit"] == "text" or get_origin(annotation) is tuple:
        kind = ("whole number" if annotation is int else "choice" if meta["unit"] == "text"
                else "true/false" if annotation is bool else "vector")
        raise SweepError(f"{where}: a {kind} parameter takes a list of values, not a range")
    missing = [k for k in ("from", "to") if k not in spec]
    if missing:
        raise SweepError(f"{where}: a range needs {' and '.join(missing)}")
    unit = meta["display"] if meta["unit"] != "1" else ""
    low, high = (_magnitude(spec[k], meta, f"{where}.{k}") for k in ("from", "to"))
    if not low < high:
        raise SweepError(f"{where}: from ({spec['from']}) must be below to ({spec['to']})")
    if not math.isfinite(high - low):
        raise SweepError(f"{where}: from ({spec['from']}) to ({spec['to']}) spans more than a "
                         "number can hold")
    scale = spec.get("scale", "linear")
    if scale not in SCALES:
        raise SweepError(f"{where}.scale: {scale!r} is not one of {', '.join(SCALES)}")
    if scale == "log" and low <= 0.0:
        raise SweepError(f"{where}: a log range needs from > 0")
    return low, high, scale, unit


def _magnitude(value: Any, meta: Mapping[str, Any], where: str) -> float:
    """``value`` (text with a unit, or a number where the parameter has none) in the
    parameter's display unit."""
    try:
        internal = to_internal(value, meta["unit"])
    except UnitError as err:
        raise SweepError(f"{where}: {err}") from None
    if not math.isfinite(internal):
        raise SweepError(f"{where}: {value!r} is not a finite number")
    return convert(internal, meta["unit"], meta["display"])


def _quantity(magnitude: float, unit: str) -> Any:
    """A generated value as a case file writes it (12 significant digits: no round-off
    tails such as 4.2000000000000002 in names and tables)."""
    rounded = float(f"{magnitude:.12g}")
    return f"{rounded!r} {unit}" if unit else rounded


def _sampled(sample: dict, where: str, grid_keys: set[str], limit: int) -> Varied:
    """Latin hypercube points over [sample.ranges] (scipy.stats.qmc), seeded."""
    count = _at_most(_whole(sample.get("count"), f"{where}: sample.count", minimum=1), limit,
                     f"{where}: sample.count")
    seed = _whole(sample.get("seed", 0), f"{where}: sample.seed", minimum=0)
    ranges = sample.get("ranges")
    if not isinstance(ranges, dict) or not ranges:
        raise SweepError(f"{where}: [sample.ranges] must name at least one parameter with "
                         "{ from = ..., to = ... }")
    bounds = []
    for key, spec in ranges.items():
        label = f"{where}: sample.ranges.{key}"
        if key in grid_keys:
            raise SweepError(f"{label}: also in [grid]; vary a parameter in one place")
        if not isinstance(spec, dict):
            raise SweepError(f"{label}: expected {{ from = ..., to = ... }}")
        if "count" in spec:
            raise SweepError(f"{label}: count belongs to [sample], not to one range")
        annotation, meta = _parameter(key, label)
        bounds.append((key, *_bounds(spec, annotation, meta, label)))
    from scipy.stats import qmc

    points = qmc.LatinHypercube(d=len(bounds), rng=np.random.default_rng(seed)).random(count)
    rows = []
    for point in points:
        row = []
        for u, (key, low, high, scale, unit) in zip(point, bounds, strict=True):
            value = (math.exp(math.log(low) + u * math.log(high / low)) if scale == "log"
                     else low + u * (high - low))
            row.append((key, _quantity(value, unit)))
        rows.append(row)
    return Varied(tuple(Swept(key, unit) for key, *_, unit in bounds), rows)


def _check_no_conflict(common: list[str], keys: list[str], where: str) -> None:
    for assignment in common:
        key = assignment.partition("=")[0].strip()
        if key in keys:
            raise SweepError(f"{where}: sweep.set sets {key}, which the sweep varies; "
                             "remove one of them")


def _run(number: int, values: list, base: str, common: list[str], where: str) -> SweepRun:
    overrides = [*common, *(f"{key}={_toml_value(value)}" for key, value in values)]
    try:
        case = load_case(base, overrides)
    except (ParameterError, UnitError) as err:
        shown = ", ".join(f"{key} = {value}" for key, value in values)
        raise SweepError(f"{where}: run {number} ({shown}): {err}") from None
    return SweepRun(number, run_name(number, values), tuple(values), case)


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)  # a TOML basic string
    return repr(value)


def run_name(number: int, values: list[tuple[str, Any]]) -> str:
    """``003-length=4.5-seed=2``: the run's number, then each swept parameter's last name
    and value (units are in summary.csv), only letters, digits and ``.=_-``."""
    parts = [f"{number:03d}"]
    for key, value in values:
        shown = ("_".join(_name_value(v) for v in value) if isinstance(value, list)
                 else _name_value(value))  # a vector (motion.pivot): its components
        parts.append(f"{key.split('.')[-1]}={shown}")
    return re.sub(r"[^A-Za-z0-9.=_-]", "_", "-".join(parts))[:120]


def _name_value(value: Any) -> str:
    """A value as a run's name shows it: a number (of a quantity) to 4 digits, without
    its unit; anything else as it is."""
    if isinstance(value, str):
        try:
            return f"{float(value.split(' ')[0]):.{NAME_VALUE_DIGITS}g}"
        except ValueError:
            return value
    if isinstance(value, float):
        return f"{value:.{NAME_VALUE_DIGITS}g}"
    return str(value)

