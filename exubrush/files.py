"""Files written whole or not at all."""

from __future__ import annotations

import csv
import math
import os
import tempfile
from collections.abc import Iterable, Sequence
from pathlib import Path


class atomic_file:
    """Open a temporary file beside ``path`` and rename it onto ``path`` on success.

    A reader therefore sees either the complete old file, the complete new one, or none;
    an exception inside the block removes the temporary file and leaves ``path`` as it was.
    """

    def __init__(self, path: Path, mode: str, **kwargs):
        self.path, self.mode, self.kwargs = Path(path), mode, kwargs

    def __enter__(self):
        fd, self.temporary = tempfile.mkstemp(dir=self.path.parent, prefix=f".{self.path.name}.")
        self.handle = os.fdopen(fd, self.mode, **self.kwargs)
        return self.handle

    def __exit__(self, exc_type, exc, tb):
        self.handle.close()
        if exc_type is None:
            os.chmod(self.temporary, 0o644)
            os.replace(self.temporary, self.path)
        else:
            os.unlink(self.temporary)
        return False


def write_csv(path: Path, header: Sequence[str], rows: Iterable[Sequence]) -> None:
    """A CSV table written whole (:class:`atomic_file`): numbers to 9 significant digits,
    NaN and None as empty cells, anything else as it is."""
    def cell(value):
        if value is None or (isinstance(value, float) and math.isnan(value)):
            return ""
        return f"{value:.9g}" if isinstance(value, float) else value

    with atomic_file(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows([cell(v) for v in row] for row in rows)
