"""Files written whole or not at all, and read back whole or refused."""

from __future__ import annotations

import csv
import math
import os
import tempfile
import tokenize
import zipfile
import zlib
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import numpy as np


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


class DamagedFile(ValueError):
    """A file exubrush wrote earlier cannot be read back: truncated, corrupted or foreign."""


# What reading a damaged or foreign .npz raises: numpy's format errors and refused pickles
# (ValueError), zipfile's (BadZipFile; NotImplementedError for an unknown compression,
# RuntimeError for an encrypted member), zlib's, a member cut short (EOFError), a member
# that is not there (KeyError), the file system's (OSError), and a header asking for an
# array larger than memory (MemoryError); a header whose dict is cut open fails in NumPy's
# tokenizer before its own check (tokenize.TokenError; found by the property test).
_NPZ_FAULTS = (OSError, ValueError, EOFError, KeyError, zipfile.BadZipFile, zlib.error,
               NotImplementedError, RuntimeError, MemoryError, tokenize.TokenError)


def read_npz(path: str | Path, required: Mapping[str, int | None],
             optional: Mapping[str, int | None] | None = None,
             largest: float = math.inf) -> dict[str, np.ndarray]:
    """The arrays of an ``.npz`` archive (numpy.savez), each read whole.

    ``required`` and ``optional`` map each array's name to its number of dimensions, or to
    None for an array of any shape and type; an array with a number of dimensions must
    hold finite 64-bit floats, as exubrush writes them (numpy would cast booleans,
    integers, complex numbers and shorter floats without a word, and with them values
    exubrush never wrote), none of magnitude beyond ``largest``. Pickled objects are never
    loaded.

    Raises
    ------
    DamagedFile
        Naming the file and what is wrong: not an .npz archive, truncated or corrupted, an
        array missing, of the wrong kind, or holding a value that is not finite.
    """
    path = Path(path)
    name = repr(str(path))
    optional = optional or {}
    try:
        if not zipfile.is_zipfile(path):
            raise DamagedFile(f"{name}: not a whole .npz archive (cut short, or another "
                              "kind of file)")
        with np.load(path, allow_pickle=False) as archive:
            present = set(archive.files)
            missing = sorted(set(required) - present)
            if missing:
                raise DamagedFile(f"{name}: has no array {missing[0]!r}")
            arrays = {key: archive[key] for key in {**required, **optional} if key in present}
    except DamagedFile:
        raise
    except _NPZ_FAULTS as err:
        reason = " ".join(str(err).split())[:200] or type(err).__name__
        raise DamagedFile(f"{name}: cannot be read ({reason})") from None
    for key, array in arrays.items():
        dimensions = {**optional, **required}[key]
        if dimensions is None:
            continue
        if array.ndim != dimensions or array.dtype != np.float64:
            raise DamagedFile(f"{name}: array {key!r} is {array.ndim}-dimensional "
                              f"{array.dtype}, not {dimensions}-dimensional float64")
        if not np.all(np.isfinite(array)):
            raise DamagedFile(f"{name}: array {key!r} holds a value that is not finite "
                              "(NaN or infinite), which exubrush never writes")
        if array.size and np.max(np.abs(array)) > largest:
            raise DamagedFile(f"{name}: array {key!r} holds a value beyond {largest:g}, "
                              "which exubrush never writes")
    return arrays
