"""files.read_npz: a damaged archive is one DamagedFile naming it, whatever the damage."""

import io
import zipfile

import numpy as np
import pytest

from exubrush.util.files import DamagedFile, read_npz


def archive_with_member(path, member: bytes) -> None:
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("time.npy", member)


def test_a_header_dict_cut_open_is_a_damaged_file(tmp_path):
    """NumPy's header parser meets an unclosed dict in Python's tokenizer, which raises
    tokenize.TokenError, not ValueError (a property test found this one)."""
    buffer = io.BytesIO()
    np.save(buffer, np.zeros(4))
    good = buffer.getvalue()
    cut = good.replace(b"}", b" ", 1)
    path = tmp_path / "tips.npz"
    archive_with_member(path, cut)
    with pytest.raises(DamagedFile, match="tips.npz"):
        read_npz(path, {"time": 1})
