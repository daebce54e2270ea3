"""Sweeps on a local Dask cluster of 2 processes: the same forces as separate runs, bit for
bit, also when a worker is killed mid-task or the sweep is interrupted and resumed.

The sweep: 3 interaction distances of a 1 x 2 head on a short, fast slide (1 s period, two
periods: whole strokes in both directions, so every metric is defined).
"""

import dataclasses
import json
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

from exubrush.execution import Executor
from exubrush.execution.cluster import dask_executor
from exubrush.execution.local import SerialExecutor
from exubrush.sweep.plan import read_sweep
from exubrush.sweep.runner import run_sweep

pytestmark = pytest.mark.slow

COMMON = ["motion.period='1 s'", "motion.amplitude='3 mm'", "motion.periods=2",
          "head.rows=1", "head.columns=2"]
DISTANCES = ("4.0 mm", "4.2 mm", "4.4 mm")
SWEEP = """
[sweep]
name = "three-distances"
base = "orthogonal"
set = ["motion.period='1 s'", "motion.amplitude='3 mm'", "motion.periods=2",
       "head.rows=1", "head.columns=2"]
[grid]
"motion.interaction_distance" = { from = "4.0 mm", to = "4.4 mm", count = 3 }
"""
RUNS = ("000-interaction_distance=4", "001-interaction_distance=4.2",
        "002-interaction_distance=4.4")


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "three.toml"
    path.write_text(SWEEP)
    return path


@pytest.fixture(scope="module")
def separate_runs(tmp_path_factory, cli):
    """The three runs, each its own 'exubrush run'."""
    root = tmp_path_factory.mktemp("separate")
    for name, distance in zip(RUNS, DISTANCES, strict=True):
        done = cli("run", "orthogonal", "--quiet", "--out", str(root / name),
                         *(f"--set={s}" for s in COMMON),
                         f"--set=motion.interaction_distance='{distance}'")
        assert done.returncode == 0, done.stderr
    return root


def _assert_same_forces(sweep_folder, separate_runs):
    for name in RUNS:
        swept = (sweep_folder / name / "forces.csv").read_bytes()
        assert swept == (separate_runs / name / "forces.csv").read_bytes(), name


def test_sweep_equals_separate_runs_bit_for_bit(tmp_path, sweep_file, separate_runs, cli):
    out = tmp_path / "sweep"
    done = cli("sweep", str(sweep_file), "--workers", "2", "--out", str(out),
                     "--quiet")
    assert done.returncode == 0, done.stderr
    assert "local Dask cluster of 2 worker processes; dashboard http" in done.stderr
    _assert_same_forces(out, separate_runs)
    rows = (out / "summary.csv").read_text().splitlines()
    assert rows[0].startswith("run,status,motion.interaction_distance [mm],")
    assert [row.split(",")[:3] for row in rows[1:]] == [
        [name, "completed", value] for name, value in zip(RUNS, ("4", "4.2", "4.4"),
                                                          strict=True)]
    assert (out / "summary-motion.interaction_distance.png").stat().st_size > 0
    pandas = pytest.importorskip("pandas")  # summary.parquet is written where it is installed
    pytest.importorskip("pyarrow")
    table = pandas.read_parquet(out / "summary.parquet")
    assert list(table.columns) == rows[0].split(",")
    assert list(table["run"]) == list(RUNS)
    assert (out / "sensitivity.csv").is_file()
    # every metric of every run is defined (two whole strokes, both directions) but the
    # tooth row's gap depth (the sweep brushes the plane) and the reversal peak's duration
    # where no later reversal rises above the flat mean (R <= 1: these short stiff bristles)
    header = rows[0].split(",")
    depth = header.index("interdental_depth [mm]")
    duration = header.index("reversal_peak_duration [s]")
    ratio = header.index("reversal_ratio [-]")
    for row in rows[1:]:
        cells = row.split(",")
        assert cells[depth] == ""
        assert (cells[duration] == "") == (float(cells[ratio]) <= 1.0)
        assert "" not in [c for i, c in enumerate(cells) if i not in (depth, duration)]
    again = cli("sweep", str(sweep_file), "--workers", "2", "--out", str(out),
                      "--quiet")
    assert again.returncode == 0 and "(3 done before)" in again.stdout


class _Counting(Executor):
    """Passes every call on and counts the solutions handed back per (run, group)."""

    def __init__(self, inner):
        self.inner, self.handed = inner, []

    @property
    def workers(self):
        return self.inner.workers

    def run(self, tasks, solved, advance):
        def counted(task, solution):
            self.handed.append((task.run, task.index))
            solved(task, solution)

        return self.inner.run(tasks, counted, advance)


def _kill_a_worker_mid_task(client, pids: dict, killed: list) -> None:
    """SIGKILL the first worker seen solving a bristle group (still on it 0.2 s later)."""
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        for address, keys in client.processing().items():
            if any("group" in str(key) for key in keys):
                time.sleep(0.2)
                if any("group" in str(key) for key in client.processing().get(address, ())):
                    killed.append(pids[address])
                    os.kill(pids[address], signal.SIGKILL)
                    return
        time.sleep(0.02)


def test_a_worker_killed_mid_task_loses_and_duplicates_nothing(tmp_path, sweep_file,
                                                              separate_runs):
    plan = read_sweep(sweep_file)
    killed = []
    with dask_executor("local", 2) as executor:
        pids = executor.client.run(os.getpid)
        scratch = executor.client.run(lambda dask_worker: dask_worker.local_directory)
        killer = threading.Thread(target=_kill_a_worker_mid_task,
                                  args=(executor.client, pids, killed))
        killer.start()
        counting = _Counting(executor)
        outcome = run_sweep(plan, tmp_path / "sweep", counting, progress=False)
        killer.join()
        survivors = list(executor.client.run(os.getpid).values())
    assert killed and killed[0] not in survivors  # its nanny started a new worker
    assert not any(os.path.exists(path) for path in scratch.values())  # workers' files gone
    assert outcome.counts == {"completed": 3, "failed": 0, "interrupted": 0}
    assert sorted(counting.handed) == [(run, group) for run in range(3) for group in range(2)]
    _assert_same_forces(tmp_path / "sweep", separate_runs)


def test_an_interrupted_sweep_resumes_to_the_same_forces(tmp_path, sweep_file, separate_runs, cli):
    out = tmp_path / "sweep"
    process = subprocess.Popen([sys.executable, "-m", "exubrush", "sweep", str(sweep_file),
                                "--workers", "1", "--out", str(out), "--quiet"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    deadline = time.monotonic() + 300
    # Ctrl-C (to the whole process group) as soon as the first of the 6 groups is stored:
    # one worker stops within a second, long before the other five are solved
    while not list(out.glob("*/.checkpoint/group-*.npz")) and time.monotonic() < deadline:
        time.sleep(0.02)
    os.killpg(process.pid, signal.SIGINT)
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 130, stderr
    assert "interrupted: finished runs are kept" in stderr
    unfinished = [name for name in RUNS if not (out / name / "run.json").is_file()]
    assert unfinished
    done = cli("sweep", str(sweep_file), "--workers", "1", "--out", str(out), "--quiet")
    assert done.returncode == 0, done.stderr
    assert f"({3 - len(unfinished)} done before)" in done.stdout
    _assert_same_forces(out, separate_runs)


def test_run_on_a_dask_cluster_equals_the_process_pool(tmp_path, separate_runs, cli):
    out = tmp_path / "run"
    done = cli("run", "orthogonal", "--quiet", "--scheduler", "local", "--workers", "2",
                     "--out", str(out), *(f"--set={s}" for s in COMMON),
                     f"--set=motion.interaction_distance='{DISTANCES[1]}'")
    assert done.returncode == 0, done.stderr
    assert "solving on a local Dask cluster" in done.stderr
    assert (out / "forces.csv").read_bytes() == (separate_runs / RUNS[1] / "forces.csv"
                                                 ).read_bytes()



class _FailingRun(SerialExecutor):
    """Solves in this process, but hands run ``failing``'s groups back as failed."""

    def __init__(self, failing):
        self.failing = failing

    def run(self, tasks, solved, advance):
        def maybe_failed(task, solution):
            if task.run == self.failing:
                solution = dataclasses.replace(solution, completed=False,
                                               message="failed on purpose")
            solved(task, solution)

        return super().run(tasks, maybe_failed, advance)


def test_a_failed_run_is_kept_and_solved_again_only_when_asked(tmp_path, sweep_file,
                                                               separate_runs):
    plan = read_sweep(sweep_file)
    out = tmp_path / "sweep"
    first = run_sweep(plan, out, _FailingRun(failing=1), progress=False)
    assert first.counts == {"completed": 2, "failed": 1, "interrupted": 0}
    record = json.loads((out / RUNS[1] / "run.json").read_text())
    assert record["status"] == "failed" and "failed on purpose" in record["message"]
    kept = run_sweep(plan, out, _FailingRun(failing=None), progress=False)
    assert kept.skipped == 3 and kept.counts["failed"] == 1
    retried = run_sweep(plan, out, _FailingRun(failing=None), retry_failed=True,
                        progress=False)
    assert retried.skipped == 2 and retried.counts == {"completed": 3, "failed": 0,
                                                       "interrupted": 0}
    _assert_same_forces(out, separate_runs)
    summary = (out / "summary.csv").read_text()
    assert summary.count(",completed,") == 3
