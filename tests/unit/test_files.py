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


@pytest.mark.parametrize(("values", "fault"), [
    (np.array([1.0, np.nan]), "not finite"),
    (np.array([1.0, -np.inf]), "not finite"),
    (np.array([1 + 2j, 3j]), "complex128, not 1-dimensional float64"),
    (np.array([True, False]), "bool, not 1-dimensional float64"),
    (np.array([1, 2]), "int64, not 1-dimensional float64"),
    (np.array([0.1, 0.2], dtype=np.float16), "float16, not 1-dimensional float64"),
    (np.array(["1", "2"]), "not 1-dimensional float64"),
])
def test_an_array_of_values_exubrush_never_writes_is_refused(tmp_path, values, fault):
    """numpy would cast booleans, integers, complex numbers and shorter floats to 64-bit
    floats (with a warning, or none): a file holding them, or NaN, is refused by name,
    not read as data."""
    path = tmp_path / "shapes.npz"
    np.savez(path, time=values)
    with pytest.raises(DamagedFile, match=fault) as refused:
        read_npz(path, {"time": 1})
    assert "shapes.npz" in str(refused.value)


def test_arrays_of_any_type_are_read_where_asked_for(tmp_path):
    path = tmp_path / "tips.npz"
    np.savez(path, part=np.arange(3), force=np.zeros((3, 2)))
    arrays = read_npz(path, {"part": None, "force": 2})
    assert arrays["part"].tolist() == [0, 1, 2] and arrays["force"].shape == (3, 2)


def test_a_value_beyond_the_largest_asked_for_is_refused(tmp_path):
    path = tmp_path / "shapes.npz"
    np.savez(path, time=np.array([0.0, -2e20]))
    assert read_npz(path, {"time": 1})["time"][1] == -2e20  # no bound unless asked
    with pytest.raises(DamagedFile, match="'time' holds a value beyond 1e"):
        read_npz(path, {"time": 1}, largest=1e20)
