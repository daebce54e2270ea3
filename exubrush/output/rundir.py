"""The result directory of a run: never mixes runs, keeps every finished bristle.

A run writes into one directory. Before it starts:

- a new or empty directory is used as it is;
- a directory holding an unfinished run of the *same* case (same parameters and the same
  profile read from every input file, e.g. a slide CSV) written by the same code
  (exubrush version and, where known, git commit) is resumed: the bristle groups already
  solved are read back, not solved again;
- a checkpoint written by another version of the code is refused with both versions named:
  a model fix that leaves the parameters unchanged must not mix old and new bristles;
- any other exubrush results (another case, or a finished run) are refused unless the
  caller allows overwriting, which removes exubrush's own files and nothing else;
- files exubrush did not write are never removed: such a directory is refused.

While it runs, each finished group is stored in ``.checkpoint/`` as its own file, written
to a temporary name and renamed, so a run stopped in any way (Ctrl-C, kill, power loss)
loses at most the groups in progress.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import math
import re
import shutil
from pathlib import Path

import numpy as np

from exubrush.output.results import RESULT_FILES as SAVED_FILES
from exubrush.parameters.fields import MAGNITUDE, to_plain
from exubrush.run.prepared import PreparedCase
from exubrush.run.sanity import within_bound
from exubrush.run.solution import GroupSolution
from exubrush.run.solution_files import HANDLE_COORDINATES, SOLUTION_FILE
from exubrush.util.files import DamagedFile, atomic_file, read_npz
from exubrush.util.provenance import code_identity

CHECKPOINT = ".checkpoint"
CODE_FILE = "code.json"  # the exubrush version and commit that wrote the checkpoint
# what Results.save writes, run.json, and the solution file exubrush view writes beside
# them (exubrush.output.viewer)
RESULT_FILES = (*SAVED_FILES, "run.json", SOLUTION_FILE)


NAME_LENGTH = 64  # characters of a case name kept in a default directory name


def safe_name(name: str) -> str:
    """``name`` made safe as one directory name: only letters, digits, ``.``, ``_`` and
    ``-`` (anything else becomes ``_``), no leading dot (so never ``..``), at most 64
    characters. So a name can never lead outside the folder it is put in."""
    return re.sub(r"[^A-Za-z0-9._-]", "_", name).lstrip(".")[:NAME_LENGTH] or "case"


def default_directory(case) -> Path:
    """``results/NAME-MODEL``, with the case name made safe (:func:`safe_name`)."""
    return Path("results") / f"{safe_name(case.name)}-{case.model.kind}"


def unusable_directory(path: Path) -> str | None:
    """Why ``path`` cannot be (made) a directory: a file there or above it; None if it can."""
    if path.exists() and not path.is_dir():
        return "is a file, not a directory"
    blocking = next((p for p in path.parents if p.exists() and not p.is_dir()), None)
    if blocking is not None:
        return f"is not a directory (a file is in the way: {blocking})"
    return None


def run_record(directory: Path) -> dict | None:
    """``directory/run.json`` as the object exubrush writes; None if there is no such file.

    Raises
    ------
    OSError, ValueError
        It cannot be read, is not UTF-8 text or not JSON, or is JSON but not an object
        (ValueError "not a JSON object").
    """
    path = directory / "run.json"
    if not path.is_file():
        return None
    record = json.loads(path.read_text(encoding="utf-8"))
    if not isinstance(record, dict):
        raise ValueError("not a JSON object")
    return record


def recorded_status(directory: Path) -> str | None:
    """The ``status`` in ``directory/run.json``; None if there is none or it is unreadable."""
    try:
        record = run_record(directory)
    except (OSError, ValueError):
        return None
    return None if record is None else record.get("status")


def _unreadable_record(directory: Path) -> bool:
    """Whether ``directory`` has a run.json that is not a readable JSON object."""
    try:
        run_record(directory)
    except (OSError, ValueError):
        return True
    return False


class RunDirectoryError(ValueError):
    """The output directory cannot be used for this run without losing or mixing data."""


class GroupFileError(ValueError):
    """A finished group's file in the checkpoint does not hold a group of this run."""


def case_fingerprint(prepared: PreparedCase) -> str:
    """Hash of every parameter but the limits (they change no result) and of the data read
    from every input file: equal means the same run (the code is checked apart)."""
    parameters = to_plain(prepared.case)
    parameters.pop("limits", None)
    text = json.dumps({"case": parameters, "inputs": dict(prepared.inputs)}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _describe(code: dict | None) -> str:
    if not code:
        return "an exubrush older than 0.2.0"
    commit = f" (commit {code['commit'][:12]})" if code.get("commit") else ""
    return f"exubrush {code.get('exubrush')}{commit}"


class RunDirectory:
    """Checks and prepares ``path`` for a run of ``prepared``; stores and reloads finished
    groups. ``afresh`` ends a refusal of a damaged or foreign checkpoint: how the caller's
    user starts the run afresh (a sweep has no --overwrite)."""

    def __init__(self, path: str | Path, prepared: PreparedCase, overwrite: bool = False,
                 afresh: str = "pass --overwrite to start afresh"):
        self.path = Path(path)
        self.afresh = afresh  # how the caller's user starts the run afresh (messages)
        self.checkpoint = self.path / CHECKPOINT
        self.fingerprint = case_fingerprint(prepared)
        self.group_sizes = [len(group) for group in prepared.groups]
        # each group's bound given its handles' mass, as its solve checked it
        self.bounds = [functools.partial(prepared.group_bound, group)
                       for group in prepared.groups]
        self.output = prepared.case.output
        self.shape_nodes = prepared.case.model.shape_nodes
        self.bristle_coordinates = prepared.case.model.bristle_coordinates
        self.end_time = prepared.motion.end_time
        self.code = code_identity()
        self.resumed = 0
        self._prepare(overwrite)

    def _prepare(self, overwrite: bool) -> None:
        reason = unusable_directory(self.path)
        if reason:
            raise RunDirectoryError(f"--out {self.path}: {reason}")
        present = {p.name for p in self.path.iterdir()} if self.path.is_dir() else set()
        foreign = sorted(present - {*RESULT_FILES, CHECKPOINT} - _temporaries(present))
        if foreign:
            raise RunDirectoryError(
                f"--out {self.path}: holds files exubrush did not write ({', '.join(foreign[:3])}"
                f"{', ...' if len(foreign) > 3 else ''}); choose a new or empty directory"
            )
        if present and not overwrite:
            stored = self._stored_fingerprint()
            finished = self._finished_run()
            if stored is not None and not finished:
                self._check_code()
            if stored == self.fingerprint and not finished:
                self.resumed = len(self.stored_groups())
                return
            what = ("complete results" if finished else
                    f"results whose {self.path / 'run.json'} cannot be read (damaged, or not "
                    "exubrush's)" if stored is None and _unreadable_record(self.path) else
                    "an unfinished run of another case, or of the same case with other "
                    "input files (e.g. a changed slide CSV)")
            raise RunDirectoryError(
                f"--out {self.path}: already holds {what}; choose another directory or "
                "pass --overwrite to replace them"
            )
        for name in present:
            target = self.path / name
            shutil.rmtree(target) if target.is_dir() else target.unlink()
        self.checkpoint.mkdir(parents=True, exist_ok=True)
        with atomic_file(self.checkpoint / CODE_FILE, "w") as handle:
            json.dump(self.code, handle)
        (self.checkpoint / "fingerprint").write_text(self.fingerprint)

    def _check_code(self) -> None:
        """Refuse a checkpoint of the same case written by other code."""
        path = self.checkpoint / CODE_FILE
        try:
            stored = json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None
        except (OSError, ValueError) as err:  # ValueError: not UTF-8 text, not JSON
            raise RunDirectoryError(f"--out {self.path}: {path} cannot be read ({err}): the "
                                    f"checkpoint is damaged; {self.afresh}") from None
        if stored is not None and not isinstance(stored, dict):
            raise RunDirectoryError(f"--out {self.path}: {path} is not the record exubrush "
                                    f"writes; {self.afresh}")
        same = stored is not None and stored.get("exubrush") == self.code["exubrush"] and (
            None in (stored.get("commit"), self.code["commit"])
            or stored.get("commit") == self.code["commit"])
        if not same:
            raise RunDirectoryError(
                f"--out {self.path}: its checkpoint was written by {_describe(stored)}, this "
                f"is {_describe(self.code)}; resuming would mix bristles solved by two "
                f"versions of the code: {self.afresh}")

    def _stored_fingerprint(self) -> str | None:
        path = self.checkpoint / "fingerprint"
        try:
            return path.read_text(encoding="utf-8").strip() if path.is_file() else None
        except (OSError, UnicodeDecodeError) as err:
            raise RunDirectoryError(f"--out {self.path}: {path} cannot be read ({err}): the "
                                    f"checkpoint is damaged; {self.afresh}") from None

    def _finished_run(self) -> bool:
        return recorded_status(self.path) == "completed"

    def stored_groups(self) -> dict[int, GroupSolution]:
        """Finished groups on disk, by group index.

        Raises
        ------
        RunDirectoryError
            Naming a group file that cannot be read back whole (truncated, corrupted,
            another format) or that does not fit the run's groups.
        """
        groups = {}
        for file in sorted(self.checkpoint.glob("group-*.npz")):
            try:
                groups[self._group_index(file)] = self._read_group(file)
            except (DamagedFile, GroupFileError) as err:
                raise RunDirectoryError(
                    f"--out {self.path}: {err}; delete that file to solve its bristle group "
                    f"again, or {self.afresh}") from None
        return groups

    def _group_index(self, file: Path) -> int:
        index = file.stem.removeprefix("group-")
        if not index.isdigit() or int(index) >= len(self.group_sizes):
            raise GroupFileError(f"{str(file)!r} is not a group of this run (it has "
                                 f"{len(self.group_sizes)} groups, numbered from 00000)")
        return int(index)

    def _read_group(self, file: Path) -> GroupSolution:
        arrays = read_npz(file, {"scalars": None, "time": 1, "reaction": 2, "tips": 3,
                                 "nodes": 4, "tip_force": 3}, {"coordinates": 2, "drive_moment": 2},
                          MAGNITUDE[1])  # no value beyond what exubrush computes with
        if arrays["scalars"].dtype.kind != "U" or arrays["scalars"].ndim != 0:
            raise GroupFileError(f"{str(file)!r}: its 'scalars' are not one text")
        try:
            solution = GroupSolution.from_arrays(arrays)
        except (ValueError, TypeError, KeyError):  # ValueError: not JSON
            solution = None
        if solution is None or not _plain_scalars(solution):
            raise GroupFileError(f"{str(file)!r}: its 'scalars' are not those of a finished "
                                 "group of this exubrush")
        steps, bristles = solution.time.size, self.group_sizes[self._group_index(file)]
        shapes = self.output.shape_samples(steps)
        moment = solution.drive_moment
        if not (solution.reaction.shape == (steps, 3)
                and (moment is None or moment.shape == (steps, 3))
                and solution.tips.shape == (steps, bristles, 3)
                and solution.nodes.shape == (shapes, bristles, self.shape_nodes, 3)
                and solution.tip_force.shape == (steps, bristles, 3)):
            raise GroupFileError(f"{str(file)!r}: its arrays do not fit {steps} times of "
                                 f"{bristles} bristles of {self.shape_nodes} nodes: the file "
                                 "is of another run")
        self._check_sane(file, solution)
        self._check_coordinates(file, solution, shapes, bristles)
        return solution

    def _check_coordinates(self, file: Path, solution: GroupSolution, shapes: int,
                           bristles: int) -> None:
        """Node coordinates where the run keeps them (output.solution_file), and only
        there: a row (time, the handle's coordinates, each bristle's) at each shape
        sample."""
        coordinates = solution.coordinates
        kept = self.output.solution_file
        if (coordinates is None) == kept:
            raise GroupFileError(f"{str(file)!r}: " + (
                "lacks the node coordinates its run keeps (output.solution_file)" if kept
                else "holds node coordinates, but its run keeps none (output.solution_file)"))
        if coordinates is None:
            return
        columns = 1 + HANDLE_COORDINATES + bristles * self.bristle_coordinates
        times = solution.time[::self.output.shape_stride]
        # both are multiples of an output interval computed apart: equal to rounding
        if not (coordinates.shape == (shapes, columns)
                and np.allclose(coordinates[:, 0], times, rtol=1e-9, atol=1e-12)):
            raise GroupFileError(f"{str(file)!r}: its node coordinates {coordinates.shape} are "
                                 f"not a row of {columns} (time, handle, {bristles} bristles) "
                                 f"at each of its {shapes} shape samples: the file is of "
                                 "another run")

    def _check_sane(self, file: Path, solution: GroupSolution) -> None:
        """The checks a fresh solve passes before its group is kept (exubrush.run.solve):
        it reached the end, on the output grid (the multiples of output.interval), and its
        normal force stays within the group's physical bound (finiteness: files.read_npz)."""
        bound = self.bounds[self._group_index(file)](solution.handle_mass)
        if not solution.completed:
            raise GroupFileError(f"{str(file)!r}: says its solve did not finish; exubrush "
                                 "keeps finished groups only")
        interval, times = self.output.interval, solution.time
        if not (times.size and np.array_equal(times, np.arange(times.size) * interval)
                and times[-1] >= self.end_time - interval):
            raise GroupFileError(f"{str(file)!r}: its times are not those of a finished solve "
                                 f"(every output.interval = {interval:g} s from 0 to the run's "
                                 f"end, {self.end_time:g} s)")
        sane = within_bound(solution.reaction, bound)
        if not sane.all():
            k = int(np.argmin(sane))
            raise GroupFileError(f"{str(file)!r}: its normal force "
                                 f"{abs(solution.reaction[k, 2]):.4g} N at t = "
                                 f"{solution.time[k]:.6g} s exceeds the group's physical bound "
                                 f"{bound:.4g} N, which a solve never keeps")

    def keep(self, index: int, solution: GroupSolution) -> None:
        """Store a finished group atomically (temporary file, then rename)."""
        with atomic_file(self.checkpoint / f"group-{index:05d}.npz", "wb") as handle:
            np.savez(handle, **solution.to_arrays())

    def close(self) -> None:
        """Remove the checkpoint once complete results are on disk."""
        shutil.rmtree(self.checkpoint, ignore_errors=True)


def _plain_scalars(solution: GroupSolution) -> bool:
    """Whether a group read back has the scalars a solve writes: of the types written,
    finite (JSON lets NaN and Infinity through), the counts, times and sizes not negative
    and the handle's mass positive (a NaN mass made every head force empty)."""
    counts = [getattr(solution, f.name) for f in dataclasses.fields(solution)
              if f.name not in (*solution.ARRAYS, "statistics", "completed", "message",
                                "handle_inertia", "retried")]
    counts += list(dataclasses.astuple(solution.statistics))
    inertia = solution.handle_inertia
    if not (isinstance(inertia, list) and len(inertia) == 3
            and all(isinstance(row, list) and len(row) == 3 for row in inertia)):
        return False
    numbers = [*counts, *(n for row in inertia for n in row)]
    return (isinstance(solution.completed, bool) and isinstance(solution.retried, bool)
            and isinstance(solution.message, str)
            and all(isinstance(n, int | float) and not isinstance(n, bool)
                    and math.isfinite(n) for n in numbers)
            and min(counts) >= 0 and solution.handle_mass > 0.0)


def _temporaries(names: set[str]) -> set[str]:
    """Leftovers of an interrupted atomic write (``.forces.csv.xyz``), safe to remove."""
    return {n for n in names if any(n.startswith(f".{f}.") for f in RESULT_FILES)}
