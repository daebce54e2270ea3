"""Results are never lost, half-written or mixed: kill, interrupt, resume, refuse.

Runs are tiny (a few two-segment DFM bristles, a fraction of a period) so that a kill can
land while some bristles are finished and others are still running.
"""

import csv
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

SMALL = ["run", "orthogonal", "--segments", "2", "--periods", "0.25", "--quiet",
         "--set", "head.rows=1", "--set", "head.columns=6"]


def _small(periods):
    return [*SMALL[:5], periods, *SMALL[6:]]


def _start(out):
    return subprocess.Popen([sys.executable, "-m", "exubrush", *SMALL, "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)


def _wait_for_first_finished_group(out, process, limit=120.0):
    start = time.monotonic()
    while time.monotonic() - start < limit:
        if list((out / ".checkpoint").glob("group-*.npz")):
            return
        assert process.poll() is None, "the run ended before any group was stored"
        time.sleep(0.05)
    raise AssertionError("no finished group appeared")


def _read_forces(path):
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    assert all(len(row) == len(rows[0]) for row in rows), "a truncated row"
    return np.array([[float(cell) if cell else np.nan for cell in row] for row in rows[1:]])


@pytest.fixture(scope="module")
def uninterrupted(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("reference") / "run"
    done = cli(*SMALL, "--out", str(out))
    assert done.returncode == 0, done.stderr
    return _read_forces(out / "forces.csv")


@pytest.mark.slow
def test_sigterm_keeps_complete_marked_results_and_the_rerun_resumes(cli, tmp_path, uninterrupted):
    out = tmp_path / "run"
    process = _start(out)
    _wait_for_first_finished_group(out, process)
    process.send_signal(signal.SIGTERM)
    _, stderr = process.communicate(timeout=120)
    assert process.returncode == 130, stderr
    assert "Traceback" not in stderr and "run the same command again to resume" in stderr
    meta = json.loads((out / "run.json").read_text())
    assert meta["status"] == "interrupted" and not meta["completed"]
    assert meta["derived"]["systems_finished"] >= 1
    if (out / "forces.csv").exists():  # partial series: complete rows, up to where all got
        partial = _read_forces(out / "forces.csv")
        assert partial[-1, 0] == pytest.approx(meta["simulated_time_s"])
        assert np.all(np.isfinite(partial[:, [0, 1, 3, 4]]))
    again = cli(*SMALL, "--out", str(out))
    assert again.returncode == 0, again.stderr
    assert "resuming:" in again.stderr
    assert json.loads((out / "run.json").read_text())["status"] == "completed"
    assert not (out / ".checkpoint").exists()
    # stored groups are the exact arrays of their solve, and each group is deterministic
    np.testing.assert_array_equal(_read_forces(out / "forces.csv"), uninterrupted)


@pytest.mark.slow
def test_sigkill_leaves_no_half_written_file_and_the_rerun_resumes(cli, tmp_path, uninterrupted):
    out = tmp_path / "run"
    process = _start(out)
    _wait_for_first_finished_group(out, process)
    os.killpg(process.pid, signal.SIGKILL)  # the parent and its workers, no clean-up at all
    process.communicate(timeout=60)
    names = {p.name for p in out.iterdir()}
    assert names == {".checkpoint"}, names  # nothing but the finished groups
    for group in (out / ".checkpoint").glob("group-*.npz"):
        with np.load(group) as data:
            assert np.all(np.isfinite(data["reaction"]))
    again = cli(*SMALL, "--out", str(out))
    assert again.returncode == 0, again.stderr
    np.testing.assert_array_equal(_read_forces(out / "forces.csv"), uninterrupted)


@pytest.mark.slow
def test_existing_results_are_never_mixed(cli, tmp_path):
    out = tmp_path / "run"
    first = cli(*_small("0.02"), "--out", str(out))
    assert first.returncode == 0, first.stderr
    same = cli(*_small("0.02"), "--out", str(out))
    assert same.returncode == 2 and "already holds complete results" in same.stderr
    other = cli(*_small("0.03"), "--out", str(out))
    assert other.returncode == 2 and "pass --overwrite" in other.stderr
    replaced = cli(*_small("0.03"), "--out", str(out), "--overwrite")
    assert replaced.returncode == 0, replaced.stderr
    meta = json.loads((out / "run.json").read_text())
    assert meta["parameters"]["motion"]["periods"] == 0.03
    (out / "notes.txt").write_text("mine")
    foreign = cli(*_small("0.02"), "--out", str(out), "--overwrite")
    assert foreign.returncode == 2 and "files exubrush did not write (notes.txt)" in foreign.stderr
    assert (out / "notes.txt").read_text() == "mine"


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_failed_solve_keeps_its_partial_results_with_the_reason(cli, tmp_path):
    out = tmp_path / "run"
    # a contact 1000x stiffer than the paper's with no step reduction cannot converge
    done = cli("run", "orthogonal", "--segments", "2", "--periods", "0.2", "--quiet",
                     "--set", "head.rows=1", "--set", "head.columns=1",
                     "--set", "solver.step_size='0.01 s'",
                     "--set", "solver.minimum_step_size='0.01 s'",
                     "--set", "contact.stiffness='1e5 N/mm^1.3'", "--out", str(out))
    assert done.returncode == 1
    assert "Traceback" not in done.stderr
    meta = json.loads((out / "run.json").read_text())
    assert meta["status"] == "failed" and "stopped at t = " in meta["message"]
    assert "solver.step_size" in meta["message"]  # says what to change
    forces = _read_forces(out / "forces.csv")
    assert forces[-1, 0] == pytest.approx(meta["simulated_time_s"])
    assert 0.0 < forces[-1, 0] < meta["derived"]["end_time_s"]
    assert np.all(np.isfinite(forces[:, [0, 1, 3, 4]]))


@pytest.mark.slow
@pytest.mark.parametrize("signal_number", [signal.SIGINT, signal.SIGTERM])
def test_a_single_process_run_stops_cleanly_on_ctrl_c_or_kill(tmp_path, signal_number):
    out = tmp_path / "run"
    # one bristle: solved in the main process, where the signal lands inside Exudyn's solve
    process = subprocess.Popen(
        [sys.executable, "-m", "exubrush", "run", "orthogonal", "--segments", "2", "--quiet",
         "--periods", "300", "--set", "head.rows=1", "--set", "head.columns=1", "--out",
         str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    # past start-up, well inside the solve: 20 periods of this bristle took 4.7 s of solve
    # on this 2-core machine (6.5 s with start-up), so the test's former 20 periods could
    # end before the signal; 300 take over a minute
    time.sleep(6.0)
    assert process.poll() is None, "the run ended before the signal"
    process.send_signal(signal_number)
    _, stderr = process.communicate(timeout=120)
    assert process.returncode == 130, stderr
    assert "Traceback" not in stderr
    meta = json.loads((out / "run.json").read_text())
    assert meta["status"] == "interrupted", meta["message"]
    assert 0.0 < meta["simulated_time_s"] < meta["derived"]["end_time_s"]


def test_a_resumed_group_keeps_the_coordinates_for_the_viewer(tmp_path):
    from exubrush.output.rundir import RunDirectory
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare
    from exubrush.run.solution import GroupSolution, SolverStatistics

    case = prepare(load_case("orthogonal", ["output.solution_file=true"]))
    # a finished solve's times: every output interval from 0 to the run's end
    interval = case.case.output.interval
    steps = round(case.motion.end_time / interval) + 1
    time = np.arange(steps) * interval
    shapes = case.case.output.shape_samples(steps)
    # rows (time, the handle's 6 coordinates, the bristle's 6 nodes of 7)
    coordinates = np.column_stack([time[::case.case.output.shape_stride],
                                   np.arange(48.0 * shapes).reshape(shapes, 48)])
    solution = GroupSolution(
        time=time, reaction=np.zeros((steps, 3)),
        tips=np.full((steps, 1, 3), 2.0), nodes=np.zeros((shapes, 1, 6, 3)),
        tip_force=np.ones((steps, 1, 3)), coordinates=coordinates,
        statistics=SolverStatistics(steps=7),
        completed=True, message="", wall_time=0.5, contacts=1, handle_mass=1e-6)
    RunDirectory(tmp_path, case).keep(0, solution)
    stored = RunDirectory(tmp_path, case).stored_groups()[0]
    np.testing.assert_array_equal(stored.coordinates, solution.coordinates)
    np.testing.assert_array_equal(stored.tip_force, solution.tip_force)
    np.testing.assert_array_equal(stored.tips, solution.tips)
    assert stored.statistics == solution.statistics
    assert (stored.wall_time, stored.contacts, stored.handle_mass) == (0.5, 1, 1e-6)


def test_a_checkpoint_of_another_exubrush_version_is_refused(tmp_path):
    from exubrush.output.rundir import CODE_FILE, RunDirectory, RunDirectoryError
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare

    case = prepare(load_case("orthogonal"))
    first = RunDirectory(tmp_path, case)
    code = json.loads((first.checkpoint / CODE_FILE).read_text())
    assert code["exubrush"] == first.code["exubrush"]
    RunDirectory(tmp_path, case)  # the same code resumes
    (first.checkpoint / CODE_FILE).write_text(json.dumps({**code, "exubrush": "0.1.9"}))
    with pytest.raises(RunDirectoryError, match="written by exubrush 0.1.9.*--overwrite"):
        RunDirectory(tmp_path, case)
    (first.checkpoint / CODE_FILE).unlink()  # a checkpoint from before versions were kept
    with pytest.raises(RunDirectoryError, match="older than 0.2.0"):
        RunDirectory(tmp_path, case)
    RunDirectory(tmp_path, case, overwrite=True)  # starts afresh
