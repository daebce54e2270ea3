"""The pure layers type-check: mypy on the files listed under [tool.mypy] in pyproject.toml
(the parameters, the pure models, the contact laws and kernels, the surfaces, the
references, the sweep plan and the units)."""

from pathlib import Path

import pytest
from mypy import api

ROOT = Path(__file__).parents[2]  # pyproject.toml lists the files relative to it


def _mypy(*args: str) -> tuple[int, str]:
    stdout, stderr, status = api.run(["--config-file", str(ROOT / "pyproject.toml"), *args])
    return status, stdout + stderr


@pytest.mark.slow  # 10 s on a cold mypy cache (a fresh clone): full run only
def test_the_pure_layers_type_check(monkeypatch):
    monkeypatch.chdir(ROOT)
    status, report = _mypy()
    assert status == 0, report
    assert "no issues found in" in report


def test_a_type_error_fails_the_check(monkeypatch, tmp_path):
    monkeypatch.chdir(ROOT)
    wrong = tmp_path / "wrong.py"
    wrong.write_text("def half(x: float) -> float:\n    return x / 2\n\n\nhalf('one')\n")
    status, report = _mypy(str(wrong))
    assert status == 1 and "[arg-type]" in report, report
