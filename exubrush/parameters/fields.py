"""Typed, unit-aware parameter dataclasses: declaration, reading, validation, TOML output.

A parameter is a field of a frozen dataclass declared with :func:`param`, which records its
internal unit, the unit shown to users, a one-line description and its allowed range. The
generic functions here walk such dataclasses, so a case file, ``--set KEY=VALUE`` and
``exubrush case`` all use the same dotted keys, units and checks.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import tomllib
import typing
from collections.abc import Mapping
from typing import Any

import tomlkit

from exubrush.util.units import UnitError, convert, format_quantity, to_internal


class ParameterError(ValueError):
    """A parameter value is missing, malformed, of the wrong unit or out of range."""


# every number exubrush computes with stays within these magnitudes (internal units), so
# that products and powers of parameters stay finite; 0 is always allowed
MAGNITUDE = (1e-20, 1e20)
C_INT = 2**31 - 1  # Exudyn takes counts as C ints


def param(
    default: Any,
    doc: str,
    unit: str = "1",
    display: str | None = None,
    minimum: float | None = None,
    above: float | None = None,
    below: float | None = None,
    choices: tuple[str, ...] | None = None,
) -> Any:
    """Declare a parameter field.

    Parameters
    ----------
    default : value
        Default, in the internal unit ``unit``. A field annotated ``tuple[E, ...]`` with E
        a number or text is a list of values (a tuple default), each checked against
        ``unit``, the range and ``choices``.
    doc : str
        One-line description shown in case files.
    unit : str
        Internal unit ("1" for dimensionless numbers, "text" for strings).
    display : str, optional
        Unit used when writing the case file (default: ``unit``).
    minimum, above, below : float, optional
        Allowed range: value >= minimum, value > above, value < below (internal unit).
    choices : tuple of str, optional
        Allowed values of a text parameter.
    """
    metadata = {
        "doc": doc,
        "unit": unit,
        "display": display or unit,
        "minimum": minimum,
        "above": above,
        "below": below,
        "choices": choices,
    }
    if isinstance(default, list | dict):
        raise TypeError("use a tuple or a default_factory for container defaults")
    return dataclasses.field(default=default, metadata=metadata)


_FIELD_TYPES: dict[type, dict[str, Any]] = {}


def _field_types(cls: type) -> dict[str, Any]:
    """The resolved annotations of a parameter dataclass (read-only; kept per class: building
    a case resolves them for every entry of its lists, and a case of 100,000
    [[motion.sine]] terms took 11.5 s to load, 3.3 s with them kept)."""
    if cls not in _FIELD_TYPES:
        _FIELD_TYPES[cls] = typing.get_type_hints(cls)
    return _FIELD_TYPES[cls]


def _section_class(annotation: Any) -> type | None:
    """``annotation`` if it is a dataclass (a section or a list's entry), else None."""
    if isinstance(annotation, type) and dataclasses.is_dataclass(annotation):
        return annotation
    return None


def _nested_entry_type(annotation: Any) -> type | None:
    """Return E for ``tuple[E, ...]`` with E a dataclass, else None."""
    if typing.get_origin(annotation) is tuple:
        args = typing.get_args(annotation)
        if args:
            return _section_class(args[0])
    return None


def _list_item_type(annotation: Any) -> Any:
    """Return E for ``tuple[E, ...]`` with E a scalar (a list of values, each checked like
    a scalar parameter of the field's unit and range), else None."""
    if typing.get_origin(annotation) is tuple and _nested_entry_type(annotation) is None:
        return typing.get_args(annotation)[0]
    return None


def _read_scalar(key: str, value: Any, meta: Mapping[str, Any], annotation: Any) -> Any:
    unit = meta["unit"]
    if annotation is bool:
        if not isinstance(value, bool):
            raise ParameterError(f"{key}: expected true or false, got {value!r}")
        return value
    if unit == "text":
        if not isinstance(value, str):
            raise ParameterError(f"{key}: expected text, got {value!r}")
        if meta["choices"] and value not in meta["choices"]:
            raise ParameterError(
                f"{key}: {value!r} is not one of {', '.join(map(repr, meta['choices']))}"
            )
        return value
    if annotation is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ParameterError(f"{key}: expected a whole number, got {value!r}")
        if abs(value) > C_INT:
            raise ParameterError(f"{key}: {value} does not fit a 32-bit integer (at most "
                                 f"{C_INT})")
        number: float = value
    else:
        if isinstance(value, int | float) and not isinstance(value, bool) and unit != "1":
            example = f"{value} {meta['display']}"
            raise ParameterError(f'{key}: {value!r} has no unit; write it with a unit, "{example}"')
        try:
            number = to_internal(value, unit)
        except UnitError as err:
            raise ParameterError(f"{key}: {err}") from None
        if not math.isfinite(number):
            raise ParameterError(f"{key}: {value!r} is not a finite number")
    _check_range(key, number, value if isinstance(value, str) else repr(value), meta)
    return number


def _check_range(key: str, number: float, shown: str, meta: Mapping[str, Any]) -> None:
    """Refuse ``number`` (internal unit) outside the field's range; ``shown`` is how the
    user wrote it."""
    if number != 0 and not MAGNITUDE[0] <= abs(number) <= MAGNITUDE[1]:
        unit = "" if meta["unit"] == "1" else f" {meta['unit']}"
        raise ParameterError(f"{key}: {shown} is outside the magnitudes exubrush computes "
                             f"with ({MAGNITUDE[0]:g} to {MAGNITUDE[1]:g}{unit})")
    for bound, fails, relation in (
        ("minimum", lambda b: number < b, ">="),
        ("above", lambda b: number <= b, ">"),
        ("below", lambda b: number >= b, "<"),
    ):
        if meta[bound] is not None and fails(meta[bound]):
            raise ParameterError(f"{key}: {shown} must be {relation} {_bound_text(meta, bound)}")


def _bound_text(meta: Mapping[str, Any], bound: str) -> str:
    """A range bound written in the unit users see."""
    if meta["unit"] == "1":
        return f"{meta[bound]:g}"
    magnitude = convert(meta[bound], meta["unit"], meta["display"])
    return f"{magnitude:g} {meta['display']}"


def build(cls: type, data: dict | None, prefix: str = "") -> Any:
    """Create dataclass ``cls`` from a (TOML-like) mapping, checking keys, units and ranges.

    Missing keys take their defaults; unknown keys are refused.
    """
    data = {} if data is None else data
    if not isinstance(data, dict):
        raise ParameterError(f"{prefix.rstrip('.') or 'case'}: expected a table, got {data!r}")
    types = _field_types(cls)
    names = {f.name for f in dataclasses.fields(cls)}
    renamed = getattr(cls, "RENAMED", {})
    for key in data:
        if key in renamed:
            raise ParameterError(f"{prefix}{key}: {renamed[key]}")
        if key not in names:
            shown = prefix + key if (prefix + key).isprintable() else repr(prefix + key)
            raise ParameterError(
                f"{shown}: unknown key; known keys here: {', '.join(sorted(names))}"
            )
    values = {}
    for f in dataclasses.fields(cls):
        key = prefix + f.name
        annotation = types[f.name]
        entry_type = _nested_entry_type(annotation)
        section = _section_class(annotation)
        if section is not None:
            values[f.name] = build(section, data.get(f.name), key + ".")
        elif entry_type is not None:
            raw = data.get(f.name, [])
            if not isinstance(raw, list):
                raise ParameterError(f"{key}: expected a list of tables")
            values[f.name] = tuple(
                build(entry_type, item, f"{key}[{i}].") for i, item in enumerate(raw)
            )
        elif f.name in data:
            values[f.name] = _read_value(key, data[f.name], f.metadata, annotation)
    return _checked(cls(**values), prefix.rstrip(".") or "case")


def _read_value(key: str, value: Any, meta: Mapping[str, Any], annotation: Any) -> Any:
    """A scalar, or a list of them read item by item (``key[i]`` in messages)."""
    item_type = _list_item_type(annotation)
    if item_type is None:
        return _read_scalar(key, value, meta, annotation)
    if not isinstance(value, list):
        raise ParameterError(f"{key}: expected a list [...], got {value!r}")
    return tuple(_read_scalar(f"{key}[{i}]", item, meta, item_type)
                 for i, item in enumerate(value))


def _checked(instance: Any, label: str) -> Any:
    """``instance`` after its own cross-field rules (``check()``, if it has one) passed;
    a broken rule becomes a ParameterError that starts with ``label``."""
    check = getattr(instance, "check", None)
    if check is not None:
        try:
            check()
        except ValueError as err:
            raise ParameterError(f"{label}: {err}") from None
    return instance


def dotted_keys(cls: type, prefix: str = "") -> list[str]:
    """All scalar parameter keys of ``cls`` in dotted form (lists of tables excluded)."""
    keys = []
    types = _field_types(cls)
    for f in dataclasses.fields(cls):
        annotation = types[f.name]
        section = _section_class(annotation)
        if section is not None:
            keys += dotted_keys(section, prefix + f.name + ".")
        elif _nested_entry_type(annotation) is None:
            keys.append(prefix + f.name)
    return keys


def _display_value(value: Any, meta: Mapping[str, Any]) -> Any:
    if isinstance(value, tuple):
        return [_display_value(item, meta) for item in value]
    if meta["unit"] in ("1", "text") or isinstance(value, int) and meta["unit"] == "1":
        return value
    display = meta["display"]
    magnitude = convert(value, meta["unit"], display)
    return format_quantity(magnitude, display)


def to_plain(instance: Any) -> dict:
    """Dataclass -> nested dict of TOML values (quantities as unit-labelled text)."""
    out: dict[str, Any] = {}
    types = _field_types(type(instance))
    for f in dataclasses.fields(instance):
        value = getattr(instance, f.name)
        annotation = types[f.name]
        if dataclasses.is_dataclass(annotation):
            out[f.name] = to_plain(value)
        elif _nested_entry_type(annotation) is not None:
            out[f.name] = [to_plain(item) for item in value]
        else:
            out[f.name] = _display_value(value, f.metadata)
    return out


def to_toml(instance: Any) -> str:
    """Write a parameter dataclass as commented TOML that :func:`build` reads back."""
    document = tomlkit.document()
    _fill_table(document, instance)
    return tomlkit.dumps(document)


def _fill_table(table: Any, instance: Any) -> None:
    types = _field_types(type(instance))
    nested = []
    for f in dataclasses.fields(instance):
        annotation = types[f.name]
        value = getattr(instance, f.name)
        if dataclasses.is_dataclass(annotation) or _nested_entry_type(annotation) is not None:
            nested.append((f.name, annotation, value))
            continue
        item = tomlkit.item(_display_value(value, f.metadata))
        unit = f.metadata["display"]
        hint = f"[{unit}]" if unit not in ("1", "text") else "[-]" if unit == "1" else ""
        if isinstance(value, bool):
            hint = "; true or false"
        choices = f.metadata["choices"]
        if choices:
            hint = "; one of " + ", ".join(choices)
        item.comment(f"{f.metadata['doc']} {hint}".strip())
        table.add(f.name, item)
    for name, annotation, value in nested:
        if dataclasses.is_dataclass(annotation):
            sub = tomlkit.table()
            _fill_table(sub, value)
            table.add(name, sub)
        else:
            array = tomlkit.aot()
            for item in value:
                sub = tomlkit.table()
                _fill_table(sub, item)
                array.append(sub)
            table.add(name, array)


def parse_override(assignment: str) -> tuple[str, Any]:
    """Split ``KEY=VALUE`` and read VALUE as a TOML value, or as text if it is not one."""
    key, sep, text = assignment.partition("=")
    key = key.strip()
    if not sep or not key:
        raise ParameterError(f"--set {assignment!r}: expected KEY=VALUE")
    try:
        value = tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        value = text.strip()
    return key, value


def describe_key(cls: type, key: str, label: str | None = None) -> tuple[Any, Mapping[str, Any]]:
    """The type annotation and field metadata (unit, range, choices) of the dotted scalar
    parameter ``key`` of ``cls``; a ParameterError starting with ``label`` (default
    ``--set KEY``) if there is no such parameter, with the nearest names."""
    label = label or f"--set {key}"
    known = dotted_keys(cls)
    *parents, leaf = key.split(".")
    owner = _owner_class(cls, parents)
    renamed = getattr(owner, "RENAMED", {})
    if leaf in renamed:
        raise ParameterError(f"{label}: {renamed[leaf]}")
    if owner is not None and leaf in {f.name for f in dataclasses.fields(owner)}:
        entry = _nested_entry_type(_field_types(owner)[leaf])
        if entry is not None:  # a list of tables, e.g. head.tufts, motion.sine
            raise ParameterError(f"{label}: {key} is a list of tables: give its entries in a "
                                 f"case file as [[{key}]] (see 'exubrush case')")
    if key not in known or owner is None:  # no owner: the key is not known either
        close = ([k for k in known if k.split(".")[-1] == key.split(".")[-1]]
                 or difflib.get_close_matches(key, known, n=1))
        hint = f"; did you mean {' or '.join(close)}?" if close else "; see 'exubrush case'"
        raise ParameterError(f"{label}: unknown parameter{hint}")
    field = next(f for f in dataclasses.fields(owner) if f.name == leaf)
    return _field_types(owner)[leaf], field.metadata


def apply_override(data: dict, cls: type, key: str, value: Any) -> None:
    """Set dotted ``key`` in the nested mapping ``data`` after checking it exists in ``cls``."""
    describe_key(cls, key)
    *parents, leaf = key.split(".")
    table = data
    for part in parents:
        table = table.setdefault(part, {})
    table[leaf] = value


def _owner_class(cls: type, parents: list[str]) -> type | None:
    """The parameter dataclass reached from ``cls`` through the section names ``parents``."""
    for name in parents:
        section = _section_class(_field_types(cls).get(name))
        if section is None:
            return None
        cls = section
    return cls


class Parameters:
    """Base of the parameter dataclasses: a typed, validated ``replace``.

    ``RENAMED`` maps a former key of the section to the message that names its successor;
    a case file or ``--set`` that still uses it is refused with that message.
    """

    RENAMED: typing.ClassVar[dict[str, str]] = {}
    if typing.TYPE_CHECKING:  # every subclass is a dataclass; this says so to type checkers
        __dataclass_fields__: typing.ClassVar[dict[str, dataclasses.Field[Any]]]

    def replace(self, **changes: Any) -> Any:
        """A copy with ``changes``, checked like a case file (type, range, choices and the
        section's own rules). Values are in the internal units (mm, N, s, t, rad); a
        section is replaced by an instance of its class, e.g.
        ``case.replace(solver=case.solver.replace(step_size=1e-3))``.

        Raises
        ------
        ParameterError
            If a name is unknown or a value is of the wrong type or out of range.
        """
        section = type(self).__name__
        fields = {f.name: f for f in dataclasses.fields(self)}
        types = _field_types(type(self))
        for name, value in changes.items():
            key = f"{section}.{name}"
            if name in self.RENAMED:
                raise ParameterError(f"{key}: {self.RENAMED[name]}")
            if name not in fields:
                raise ParameterError(f"{key}: unknown; known: {', '.join(sorted(fields))}")
            _check_value(key, value, fields[name].metadata, types[name])
        return _checked(dataclasses.replace(self, **changes), section)


def _check_value(key: str, value: Any, meta: Mapping[str, Any], annotation: Any) -> None:
    """Check a value given in the internal unit (:meth:`Parameters.replace`)."""
    entry_type = _nested_entry_type(annotation)
    if dataclasses.is_dataclass(annotation) or entry_type is not None:
        wanted = annotation if entry_type is None else entry_type
        items = [value] if entry_type is None else value
        if (entry_type is not None and not isinstance(value, tuple)) or not all(
                isinstance(item, wanted) for item in items):
            shape = wanted.__name__ if entry_type is None else f"a tuple of {wanted.__name__}"
            raise ParameterError(f"{key}: expected {shape}, got {value!r}")
        return
    if _list_item_type(annotation) is not None:
        if not isinstance(value, tuple):
            raise ParameterError(f"{key}: expected a tuple, got {value!r}")
        for i, item in enumerate(value):
            _check_value(f"{key}[{i}]", item, meta, _list_item_type(annotation))
        return
    if annotation in (bool, int) or meta["unit"] == "text":  # no unit to read: same path
        _read_scalar(key, value, meta, annotation)
        return
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(f"{key}: expected a number in {meta['unit']}, got {value!r}")
    if not math.isfinite(value):
        raise ParameterError(f"{key}: {value!r} is not a finite number")
    _check_range(key, value, repr(value), meta)
