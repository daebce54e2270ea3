"""The result directory of a run: never mixes runs, keeps every finished bristle.

A run writes into one directory. Before it starts:

- a new or empty directory is used as it is;
- a directory holding an unfinished run of the *same* case (same parameters and exubrush
  version) is resumed: the bristle groups already solved are read back, not solved again;
- any other exubrush results (another case, or a finished run) are refused unless the
  caller allows overwriting, which removes exubrush's own files and nothing else;
- files exubrush did not write are never removed: such a directory is refused.

While it runs, each finished group is stored in ``.checkpoint/`` as its own file, written
to a temporary name and renamed, so a run stopped in any way (Ctrl-C, kill, power loss)
loses at most the groups in progress.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

import exubrush
from exubrush.parameters.case import Case
from exubrush.parameters.fields import to_plain

CHECKPOINT = ".checkpoint"
# exubrush view writes exudyn-solution.txt beside the results (exubrush.viewer)
RESULT_FILES = ("forces.csv", "run.json", "forces.png", "shapes.npz", "exudyn-solution.txt")
ARRAYS = ("time", "reaction", "nodes", "coordinates")  # coordinates: only if kept


class RunDirectoryError(ValueError):
    """The output directory cannot be used for this run without losing or mixing data."""


def case_fingerprint(case: Case) -> str:
    """Hash of every parameter and the exubrush version: equal means the same run."""
    text = json.dumps({"case": to_plain(case), "exubrush": exubrush.__version__},
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


class RunDirectory:
    """Checks and prepares ``path`` for ``case``; stores and reloads finished groups."""

    def __init__(self, path: str | Path, case: Case, overwrite: bool = False):
        self.path = Path(path)
        self.checkpoint = self.path / CHECKPOINT
        self.fingerprint = case_fingerprint(case)
        self.resumed = 0
        self._prepare(overwrite)

    def _prepare(self, overwrite: bool) -> None:
        if self.path.exists() and not self.path.is_dir():
            raise RunDirectoryError(f"--out {self.path}: is a file, not a directory")
        present = {p.name for p in self.path.iterdir()} if self.path.is_dir() else set()
        foreign = sorted(present - {*RESULT_FILES, CHECKPOINT} - _temporaries(present))
        if foreign:
            raise RunDirectoryError(
                f"--out {self.path}: holds files exubrush did not write ({', '.join(foreign[:3])}"
                f"{', ...' if len(foreign) > 3 else ''}); choose a new or empty directory"
            )
        stored = self._stored_fingerprint()
        if present and not overwrite:
            if stored == self.fingerprint and not self._finished_run():
                self.resumed = len(self.stored_groups())
                return
            what = "complete results" if self._finished_run() else "results of another case"
            raise RunDirectoryError(
                f"--out {self.path}: already holds {what}; choose another directory or "
                "pass --overwrite to replace them"
            )
        for name in present:
            target = self.path / name
            shutil.rmtree(target) if target.is_dir() else target.unlink()
        self.checkpoint.mkdir(parents=True, exist_ok=True)
        (self.checkpoint / "fingerprint").write_text(self.fingerprint)

    def _stored_fingerprint(self) -> str | None:
        path = self.checkpoint / "fingerprint"
        return path.read_text().strip() if path.is_file() else None

    def _finished_run(self) -> bool:
        path = self.path / "run.json"
        if not path.is_file():
            return False
        try:
            return json.loads(path.read_text()).get("status") == "completed"
        except (OSError, ValueError):
            return False

    def stored_groups(self) -> dict[int, dict]:
        """Finished groups on disk, by group index."""
        groups = {}
        for file in sorted(self.checkpoint.glob("group-*.npz")):
            with np.load(file) as data:
                output = {key: data[key] for key in ARRAYS if key in data}
                output.update(json.loads(str(data["scalars"])))
            groups[int(file.stem.split("-")[1])] = output
        return groups

    def keep(self, index: int, output: dict) -> None:
        """Store a finished group atomically (temporary file, then rename)."""
        scalars = {k: v for k, v in output.items() if k not in ARRAYS}
        arrays = {k: output[k] for k in ARRAYS if k in output}
        fd, temporary = tempfile.mkstemp(dir=self.checkpoint, prefix=".group-", suffix=".npz")
        with os.fdopen(fd, "wb") as handle:
            np.savez(handle, scalars=json.dumps(scalars), **arrays)
        os.replace(temporary, self.checkpoint / f"group-{index:05d}.npz")

    def close(self) -> None:
        """Remove the checkpoint once complete results are on disk."""
        shutil.rmtree(self.checkpoint, ignore_errors=True)


def _temporaries(names: set[str]) -> set[str]:
    """Leftovers of an interrupted atomic write (``.forces.csv.xyz``), safe to remove."""
    return {n for n in names if any(n.startswith(f".{f}.") for f in RESULT_FILES)}
