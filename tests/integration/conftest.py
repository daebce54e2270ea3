"""Fixtures shared by the command-line tests."""

import subprocess
import sys

import pytest


def _exubrush(*args, timeout=300):
    return subprocess.run([sys.executable, "-m", "exubrush", *args], capture_output=True,
                          text=True, timeout=timeout)


@pytest.fixture(scope="session")
def cli():
    """Run the ``exubrush`` command line in a fresh interpreter: ``cli("run", ...)``."""
    return _exubrush


@pytest.fixture(scope="session")
def two_model_runs(tmp_path_factory):
    """A DFM and a PRB run of a 1 x 2 head through the approach and a short slide, with the
    node coordinates kept for the viewer (``root/dfm``, ``root/prb``)."""
    root = tmp_path_factory.mktemp("two-models")
    for model in ("dfm", "prb"):
        done = _exubrush("run", "orthogonal", "--model", model, "--periods", "0.1", "--quiet",
                        "--viewer", "--set", "head.rows=1", "--set", "head.columns=2",
                        "--out", str(root / model))
        assert done.returncode == 0, done.stderr
    return root
