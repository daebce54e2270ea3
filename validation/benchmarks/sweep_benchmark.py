"""What Dask costs a sweep on this machine: the same runs through each executor.

    python validation/benchmarks/sweep_benchmark.py [--runs 4] [--periods 1] [--repeat 2]
        [--tiny-tasks 48] [--out validation/results/benchmarks]

Rows (every row solves the same runs of the default head, orthogonal case, one seed each,
``--periods`` slide periods after the approach; wall time from the first task to the last
file written, median of ``--repeat``, the variants taking turns so that a drift of the
machine's speed hits them alike):

- ``runs one after another, process pool``: what a user did before sweeps existed, one
  ``simulate`` per run, each with its own pool of 2 processes;
- ``sweep, process pool (2)``: exubrush.sweep.runner.run_sweep with one pool for all runs;
- ``sweep, Dask local cluster (2)`` and ``(1)``: the same on a local Dask cluster of 2 and
  1 worker processes, the cluster's start and stop included (the scaling from 1 to 2);

and the per-task overhead: ``--tiny-tasks`` one-bristle tasks of a 0.2 s approach-only run,
solved in this process (no overhead) and by one Dask worker; the difference per task is
what Dask adds to each task (scheduling, sending the task and its solution back).

The forces of every sweep row are checked bit for bit against the first row's.
Output: ``sweep-dask.md`` and ``.csv`` in ``--out``.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import os
import platform
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from exubrush.execution import SolveTask
from exubrush.execution.cluster import dask_executor
from exubrush.execution.local import ProcessExecutor, SerialExecutor
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.simulation import simulate
from exubrush.sweep.plan import read_sweep
from exubrush.sweep.runner import prepare_runs, run_sweep

SWEEP = """
[sweep]
name = "benchmark"
base = "orthogonal"
set = ["motion.periods={periods}"]
[grid]
"motion.interaction_distance" = {{ from = "4.0 mm", to = "4.4 mm", count = {runs} }}
"""


def sequential_pool(plan, folder: Path) -> None:
    for run in plan.runs:
        simulate(run.case, progress=False, workers=2).save(folder / run.name)


def swept(executor_factory):
    def run(plan, folder: Path) -> None:
        with executor_factory() as executor:
            outcome = run_sweep(plan, folder, executor, progress=False)
        assert outcome.counts["completed"] == len(plan.runs), outcome.counts
    return run


VARIANTS = {
    "runs one after another, process pool (2)": sequential_pool,
    "sweep, process pool (2)": swept(lambda: contextlib.nullcontext(ProcessExecutor(2))),
    "sweep, Dask local cluster (2)": swept(lambda: dask_executor("local", 2)),
    "sweep, Dask local cluster (1)": swept(lambda: dask_executor("local", 1)),
}


def forces(folder: Path, plan) -> list[bytes]:
    return [(folder / run.name / "forces.csv").read_bytes() for run in plan.runs]


def task_overhead(count: int) -> dict:
    """Wall time per tiny task in this process and on one Dask worker [s]."""
    case = load_case("orthogonal", ["head.rows=1", f"head.columns={count}",
                                    "motion.approach_duration='0.2 s'",
                                    "motion.hold_duration='0 s'", "motion.periods=0.01",
                                    "motion.period='1 s'"])
    prepared = prepare(case)
    tasks = [SolveTask(prepared, i, group) for i, group in enumerate(prepared.groups)]
    start = time.perf_counter()
    SerialExecutor().run(tasks, lambda *_: None, lambda _: None)
    serial = time.perf_counter() - start
    with dask_executor("local", 1) as executor:
        executor.run(tasks[:2], lambda *_: None, lambda _: None)  # warm the worker's imports
        start = time.perf_counter()
        executor.run(tasks, lambda *_: None, lambda _: None)
        dask = time.perf_counter() - start
    return {"tasks": count, "serial_s": serial, "dask_s": dask,
            "per_task_ms": 1000 * (dask - serial) / count,
            "task_ms": 1000 * serial / count}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=4)
    parser.add_argument("--periods", type=float, default=1.0)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--tiny-tasks", type=int, default=48)
    parser.add_argument("--only", nargs="*", choices=sorted(VARIANTS), metavar="VARIANT")
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).parent.parent / "results" / "benchmarks")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="exubrush-sweep-bench-"))
    sweep_file = work / "benchmark.toml"
    sweep_file.write_text(SWEEP.format(periods=args.periods, runs=args.runs))
    plan = read_sweep(sweep_file)
    prepare_runs(plan)  # the PRB-free default head prepares in milliseconds; not timed
    names = args.only or list(VARIANTS)
    walls = {name: [] for name in names}
    reference = None
    for repeat in range(args.repeat):
        for name in names:
            folder = work / f"{repeat}-{len(walls[name])}-{names.index(name)}"
            start = time.perf_counter()
            VARIANTS[name](plan, folder)
            walls[name].append(time.perf_counter() - start)
            got = forces(folder, plan)
            reference = reference or got
            same = got == reference
            print(f"{name}: {walls[name][-1]:.1f} s, forces bit-identical: {same}", flush=True)
            assert same, name
            shutil.rmtree(folder)
    overhead = task_overhead(args.tiny_tasks) if args.tiny_tasks else None
    machine = f"{platform.node()}, {os.cpu_count()} cores, Python {platform.python_version()}"
    first = statistics.median(walls[names[0]])
    with open(args.out / "sweep-dask.csv", "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["variant", "wall_time_s", "wall_times_s", "against_first"])
        for name in names:
            median = statistics.median(walls[name])
            writer.writerow([name, f"{median:.2f}", " ".join(f"{w:.2f}" for w in walls[name]),
                             f"{median / first - 1:+.3f}"])
    lines = [f"# Sweep of {args.runs} runs, default head, orthogonal, {args.periods:g} periods",
             "", f"Machine: {machine}. Median of {args.repeat}, variants in turn.", "",
             f"| variant | wall (median) | runs | against '{names[0]}' |",
             "| --- | --- | --- | --- |"]
    for name in names:
        median = statistics.median(walls[name])
        lines.append(f"| {name} | {median:.1f} s | "
                     f"{', '.join(f'{w:.1f}' for w in walls[name])} | "
                     f"{100 * (median / first - 1):+.1f} % |")
    if overhead:
        lines += ["", f"Per-task overhead: {overhead['tasks']} one-bristle tasks of "
                  f"{overhead['task_ms']:.0f} ms each: {overhead['serial_s']:.2f} s in this "
                  f"process, {overhead['dask_s']:.2f} s on one Dask worker: "
                  f"{overhead['per_task_ms']:.1f} ms per task."]
    (args.out / "sweep-dask.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
