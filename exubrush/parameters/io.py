"""Load a case by name or from a TOML file, with ``KEY=VALUE`` overrides.

Only the parameters are read and checked here; what needs the physics (the bristles'
reach, the slide CSV's content) is checked by :func:`exubrush.run.prepared.prepare`.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import replace
from pathlib import Path

from exubrush.parameters.case import Case
from exubrush.parameters.catalogue import BUILT_IN_CASES
from exubrush.parameters.fields import (
    ParameterError,
    apply_override,
    build,
    parse_override,
    to_plain,
)
from exubrush.parameters.surface_kinds import MESH
from exubrush.parameters.tuft_table import read_tuft_table


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
        # utf-8-sig: a byte-order mark, which Windows editors write, is not text
        return tomllib.loads(path.read_bytes().decode("utf-8-sig"))
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
    folder = Path(case).parent if case.endswith(".toml") else None
    if built.head.tuft_table:  # the table's tufts replace it, checked as case-file tufts
        tufts = read_tuft_table(_resolved(built.head.tuft_table, folder), built.limits.bristles)
        del data["head"]["tuft_table"]
        data["head"]["tufts"] = [to_plain(tuft) for tuft in tufts]
        built = build(Case, data)
    if built.motion.profile == "csv":
        built = replace(built, motion=replace(
            built.motion, csv_file=_resolved(built.motion.csv_file, folder)))
    if built.motion.pose_csv:
        built = replace(built, motion=replace(
            built.motion, pose_csv=_resolved(built.motion.pose_csv, folder)))
    if built.surface.kind == MESH:
        built = replace(built, surface=replace(
            built.surface, mesh_file=_resolved(built.surface.mesh_file, folder)))
    return built


def _resolved(name: str, case_folder: Path | None) -> str:
    """An input file's path relative to the case file, made absolute (links are kept as
    they are, so that a message names the path the user gave)."""
    path = Path(name).expanduser()
    if not path.is_absolute() and case_folder is not None:
        path = case_folder / path
    return os.path.abspath(path)
