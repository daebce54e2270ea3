"""Load a case by name or from a TOML file, with ``KEY=VALUE`` overrides.

Only the parameters are read and checked here; what needs the physics (the bristles'
reach, the slide CSV's content) is checked by :func:`exubrush.prepared.prepare`.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import replace
from pathlib import Path

from exubrush.parameters.case import BUILT_IN_CASES, Case
from exubrush.parameters.fields import (
    ParameterError,
    apply_override,
    build,
    parse_override,
    to_plain,
)


def case_data(case: str) -> dict:
    """The nested mapping of a built-in case name or a TOML case file."""
    if case in BUILT_IN_CASES:
        return to_plain(BUILT_IN_CASES[case]())
    if Path(case).suffix.lower() != ".toml":
        raise ParameterError(
            f"unknown case {case!r}: use {', '.join(BUILT_IN_CASES)} or the path of a TOML "
            "case file (see 'exubrush case orthogonal')"
        )
    return read_toml(case, "case file")


def read_toml(name: str, kind: str, error: type[ValueError] = ParameterError) -> dict:
    """The TOML file ``name`` (a path as the user gave it) read as UTF-8; ``error`` with
    one line naming the ``kind`` of file ("case file") if it is missing, not a file, not
    UTF-8, not TOML or unreadable."""
    path = Path(name)
    if not path.exists():
        raise error(f"{kind} {name!r} does not exist")
    if not path.is_file():
        raise error(f"{kind} {name!r} is not a file")
    try:
        return tomllib.loads(path.read_bytes().decode("utf-8"))
    except tomllib.TOMLDecodeError as err:
        raise error(f"{path}: not valid TOML ({err})") from None
    except UnicodeDecodeError as err:
        raise error(f"{path}: not UTF-8 text (byte {err.start}); {kind}s are TOML, which "
                    "is UTF-8") from None
    except OSError as err:
        raise error(f"{path}: cannot be read ({err.strerror})") from None


def load_case(case: str, overrides: list[str] | tuple[str, ...] = ()) -> Case:
    """Build a validated :class:`Case` from a name or file and ``KEY=VALUE`` overrides."""
    data = case_data(case)
    for assignment in overrides:
        key, value = parse_override(assignment)
        apply_override(data, Case, key, value)
    built = build(Case, data)
    if built.motion.profile == "csv":
        folder = Path(case).parent if case.endswith(".toml") else None
        built = _with_resolved_slide_csv(built, folder)
    return built


def _with_resolved_slide_csv(case: Case, case_folder: Path | None) -> Case:
    """Resolve ``motion.csv_file`` relative to the case file, as an absolute path (links are
    kept as they are, so that a message names the path the user gave)."""
    path = Path(case.motion.csv_file).expanduser()
    if not path.is_absolute() and case_folder is not None:
        path = case_folder / path
    return replace(case, motion=replace(case.motion, csv_file=os.path.abspath(path)))
