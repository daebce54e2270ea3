"""Fixtures shared by the command-line tests."""

import contextlib
import inspect
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

CHECKOUT = Path(__file__).resolve().parents[2]


def _exubrush(*args, cwd=None, timeout=300):
    # this checkout's exubrush, as the tests in this interpreter import it (pyproject's
    # pythonpath), whatever the working directory: not a copy installed elsewhere, whose
    # numba kernels would compile into a cache of their own
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(CHECKOUT), *filter(None, [os.environ.get("PYTHONPATH")])])}
    return subprocess.run([sys.executable, "-m", "exubrush", *map(str, args)],
                          capture_output=True, text=True, timeout=timeout, cwd=cwd,
                          env=environment)


def _exubrush_here(*args, cwd=None):
    from exubrush.cli import main

    # Click 8.1 mixes standard error into the output unless told not to; 8.2 keeps both
    separate = ({"mix_stderr": False}
                if "mix_stderr" in inspect.signature(CliRunner).parameters else {})
    with contextlib.chdir(cwd or os.getcwd()):
        done = CliRunner(**separate).invoke(main, [str(a) for a in args],
                                            catch_exceptions=False)
    return subprocess.CompletedProcess(["exubrush", *args], done.exit_code, done.stdout,
                                       done.stderr)


@pytest.fixture(scope="session")
def cli():
    """Run the ``exubrush`` command line in a fresh interpreter: ``cli("run", ...)``
    (``cwd=`` a working directory, ``timeout=`` [s])."""
    return _exubrush


@pytest.fixture(scope="session")
def cli_here():
    """Run the command line in this interpreter, as ``python -m exubrush`` does after its
    start (Click's test runner; ``cwd=`` a working directory): a check of what a command
    refuses, without the 0.3-0.4 s start of a fresh interpreter. An exception that escapes
    the commands is raised in the test, as a fresh interpreter would print its traceback.
    Returns a subprocess.CompletedProcess, as ``cli`` does."""
    return _exubrush_here


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
