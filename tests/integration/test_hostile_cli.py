"""Hostile input and faults at the command line: one line on standard error, the documented
exit status (2 input, 1 run or write failure, 130 interrupted), never a traceback, and
nothing written outside the output directory.

Each command runs with the test's folder as working directory, the refusals in this
interpreter (conftest's ``cli_here``), the runs and signals in a fresh one; the folder is
listed before and after, and only the output directory may have changed.
"""

import errno
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from exubrush.output.results import Results

TINY = ["--quiet", "--segments", "2", "--periods", "0.02", "--set", "head.rows=1",
        "--set", "head.columns=1"]


def _tree(root):
    return {str(p.relative_to(root)): (p.is_dir() or p.lstat().st_size)
            for p in sorted(root.rglob("*"))}


def _only_changed(before, after, prefix):
    changed = {k for k in set(before) | set(after) if before.get(k) != after.get(k)}
    return all(k == prefix or k.startswith(prefix + os.sep) for k in changed), changed


@pytest.fixture(scope="module")
def saved_run(tmp_path_factory):
    """A saved run to copy into each test's folder (saving it draws its plot: 0.3-1 s)."""
    directory = tmp_path_factory.mktemp("saved")
    t = np.linspace(0.0, 2.0, 201)
    Results(t, np.sin(t), np.ones_like(t), 0.5 * np.ones_like(t), np.zeros_like(t),
            np.zeros(0), np.zeros((0, 0, 0, 3)),
            metadata={"case": "made-up", "model": "dfm", "status": "completed"}).save(directory)
    return directory


@pytest.mark.parametrize("args, status, message", [
    (["run", "orthogonal", "--out", "plain.txt/run"], 2,
     "exubrush: error: --out plain.txt/run: is not a directory (a file is in the way: "
     "plain.txt)"),
    (["run", "orthogonal", "--out", "plain.txt"], 2, "--out plain.txt: is a file, not a "
     "directory"),
    (["run", "orthogonal", "--set", "motion.periods=1e5"], 2, "more than limits.steps = "
     "20,000,000; to run it anyway, --set limits.steps=600000600"),
    (["run", "orthogonal", "--set", "head.rows=100000", "--set", "head.columns=100000"], 2,
     "the head has 10,000,000,000 bristles, more than limits.bristles = 10,000"),
    (["run", "orthogonal", "--set", "solver.step_size='20 s'"], 2,
     "solver.step_size 20 s does not resolve the motion"),
    (["run", "binary.toml"], 2, "binary.toml: not UTF-8 text (byte 0)"),
    (["case", "binary.toml"], 2, "binary.toml: not UTF-8 text (byte 0)"),
    (["run", "folder.toml"], 2, "case file 'folder.toml' is not a file"),
    (["compare", "saved", "binary.csv"], 2, "measured CSV 'binary.csv' is not UTF-8 text"),
    (["compare", "saved", "folder.toml"], 2, "measured CSV 'folder.toml' is not a file"),
    (["compare", "saved", "dangling.csv"], 2, "does not exist (a link to nothing)"),
    (["compare", "saved", "measured.csv", "--out", "plain.txt/compare"], 2,
     "plain.txt/compare: Not a directory"),
    (["frames", "plain.txt"], 2, "'plain.txt' holds no run.json"),
    (["view", "plain.txt/run"], 2, "'plain.txt/run' holds no run.json"),
    (["frames", "garbled"], 2, "'garbled/run.json' is not UTF-8 text (byte 0)"),
    (["compare", "garbled", "measured.csv"], 2, "'garbled/run.json' is not UTF-8 text"),
])
def test_a_fault_ends_in_one_line(tmp_path, saved_run, cli_here, args, status, message):
    (tmp_path / "plain.txt").write_text("not a directory\n")
    (tmp_path / "binary.toml").write_bytes(b"\xff\xfe\x00\x01")
    (tmp_path / "binary.csv").write_bytes(b"\xff\xfe\x00\x01")
    (tmp_path / "folder.toml").mkdir()
    os.symlink(tmp_path / "nowhere.csv", tmp_path / "dangling.csv")
    (tmp_path / "measured.csv").write_text(
        "time [s],slider_position [mm],normal_force [N],tangential_force [N]\n"
        + "".join(f"{t:.2f},{np.sin(t):.6f},1,0.5\n" for t in np.linspace(0, 2, 201)))
    shutil.copytree(saved_run, tmp_path / "saved")
    (tmp_path / "garbled").mkdir()
    (tmp_path / "garbled" / "run.json").write_bytes(b"\xff\xfe\x00\x01")
    before = _tree(tmp_path)
    done = cli_here(*args, cwd=tmp_path)
    assert done.returncode == status, done.stderr
    assert message in done.stderr, done.stderr
    assert "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert _tree(tmp_path) == before  # a refused command writes nothing


def test_a_fresh_interpreter_refuses_in_one_line_too(tmp_path, cli):
    # the refusals above run in this interpreter: the installed command's own start
    (tmp_path / "binary.toml").write_bytes(b"\xff\xfe\x00\x01")
    done = cli("run", "binary.toml", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith("exubrush: error: binary.toml: not UTF-8 text (byte 0)")
    assert len(done.stderr.splitlines()) == 1, done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["binary.toml"]


@pytest.mark.slow  # a real run
def test_a_case_name_never_leads_outside_results(tmp_path, cli):
    work = tmp_path / "work"
    work.mkdir()
    before = _tree(tmp_path)
    done = cli("run", "orthogonal", *TINY, "--set", "name='../../../x'", cwd=work)
    assert done.returncode == 0, done.stderr
    assert (work / "results" / "_.._.._x-dfm" / "run.json").is_file()
    inside, changed = _only_changed(before, _tree(tmp_path), os.path.join("work", "results"))
    assert inside, changed


@pytest.mark.slow  # a real run
def test_a_full_disk_while_saving_keeps_the_checkpoint_and_says_so(tmp_path, monkeypatch):
    from click.testing import CliRunner

    from exubrush.cli import main

    def full(self, directory):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(directory))

    monkeypatch.setattr(Results, "save", full)
    out = tmp_path / "run"
    done = CliRunner().invoke(main, ["run", "orthogonal", *TINY, "--out", str(out)])
    assert done.exit_code == 1, done.output
    assert ("results not written: " + str(out) + ": No space left on device; the finished "
            "bristles stay in") in " ".join(done.output.split())
    assert list((out / ".checkpoint").glob("group-*.npz"))  # resumable
    assert not (out / "run.json").exists()


def test_a_directory_that_cannot_be_written(tmp_path, monkeypatch):
    from click.testing import CliRunner

    from exubrush.cli import main

    # the operating system's refusal, injected: root (as CI runs) may write into a
    # directory of mode 0o500, so the mode alone would test nothing there
    locked = tmp_path / "locked"
    locked.mkdir()
    real_mkdir = os.mkdir

    def refused(path, *args, **kwargs):
        if os.path.dirname(os.path.abspath(path)) == str(locked):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), os.fspath(path))
        return real_mkdir(path, *args, **kwargs)

    monkeypatch.setattr(os, "mkdir", refused)
    monkeypatch.chdir(tmp_path)
    done = CliRunner().invoke(main, ["run", "orthogonal", *TINY, "--out", "locked/run"])
    assert done.exit_code == 2, done.output
    assert done.output.strip() == "exubrush: error: locked/run: Permission denied", done.output
    assert list(locked.iterdir()) == []


@pytest.mark.slow
def test_sigterm_to_the_process_group_then_resume_equals_an_uninterrupted_run(tmp_path, cli):
    small = ["run", "orthogonal", "--segments", "2", "--periods", "0.25", "--quiet",
             "--set", "head.rows=1", "--set", "head.columns=6"]
    whole = cli(*small, "--out", "whole", cwd=tmp_path)
    assert whole.returncode == 0, whole.stderr
    process = subprocess.Popen([sys.executable, "-m", "exubrush", *small, "--out", "cut"],
                               cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, start_new_session=True)
    checkpoint = tmp_path / "cut" / ".checkpoint"
    start = time.monotonic()
    while not list(checkpoint.glob("group-*.npz")):
        assert process.poll() is None and time.monotonic() - start < 120, "no group finished"
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGTERM)  # parent and workers alike
    os.killpg(process.pid, signal.SIGTERM)  # twice
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 130, stderr
    assert "Traceback" not in stderr
    resumed = cli(*small, "--out", "cut", cwd=tmp_path)
    assert resumed.returncode == 0, resumed.stderr
    assert "resuming:" in resumed.stderr
    assert ((tmp_path / "cut" / "forces.csv").read_bytes()
            == (tmp_path / "whole" / "forces.csv").read_bytes())


@pytest.mark.parametrize("table, message", [
    (None, "head.tuft_table '{folder}/tufts.csv' does not exist"),
    ("x,y [mm]\n0,0\n", "column 'x' has no unit; write 'x [mm]'"),
    ("x [mm],y [mm],bristle_colour\n0,0,red\n", "unknown column 'bristle_colour'"),
    ("x [mm],y [mm]\n0,0\n0.5,0\n", "overlap by 1.1 mm"),
    ("x [mm],y [mm],filaments,diameter [mm]\n0,0,37,1\n", "37 filaments of 0.2 mm need a "
     "tuft of 1.4 mm in hexagonal packing, the tuft is 1 mm"),
])
def test_a_bad_tuft_table_ends_in_one_line_with_exit_2_and_nothing_written(tmp_path, cli_here,
                                                                             table, message):
    (tmp_path / "head.toml").write_text('name = "t"\n[head]\nlayout = "tufts"\n'
                                        'tuft_table = "tufts.csv"\n')
    if table is not None:
        (tmp_path / "tufts.csv").write_text(table)
    before = _tree(tmp_path)
    done = cli_here("run", "head.toml", "--out", "out", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert message.format(folder=tmp_path) in done.stderr, done.stderr
    assert "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert _tree(tmp_path) == before
