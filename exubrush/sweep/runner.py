"""Run a sweep: every run an ordinary run folder, all their bristle groups in one queue.

The sweep folder holds ``sweep.json`` (which sweep it is), one run folder per run (the
files of ``exubrush run``: forces.csv, run.json, forces.png, shapes.npz), and the summary
(summary.csv, summary.parquet where pandas and pyarrow are installed, sensitivity.csv,
one summary-PARAMETER.png per swept parameter).

Resuming: the same sweep in the same folder skips the runs whose run.json says completed,
and inside unfinished runs the bristle groups already in their checkpoint (the run
directory's own resume, exubrush.output.rundir). Failed runs are kept as they are unless asked
to retry them. A folder that holds another sweep, or files exubrush did not write, is
refused before anything is written.

Every file is written by this process (workers only compute), whole or not at all; a run's
files are written as soon as its last group is back, so a stopped sweep keeps every run
that finished.
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from exubrush.execution import Executor, SolveTask
from exubrush.execution.progress import SimulatedTimeBar
from exubrush.output.assemble import RunFacts, assemble_results
from exubrush.output.results import REMAKE, ResultsError, read_results
from exubrush.output.rundir import (
    RunDirectory,
    case_fingerprint,
    recorded_status,
    run_record,
    safe_name,
    unusable_directory,
)
from exubrush.parameters.case import Case
from exubrush.parameters.fields import ParameterError, describe_key
from exubrush.run.prepared import PreparedCase, prepare
from exubrush.sweep.plan import SweepError, SweepPlan, SweepRun
from exubrush.sweep.plots import plot_summary
from exubrush.sweep.summary import METRICS, run_metrics, sensitivities, write_parquet
from exubrush.util.files import atomic_file, write_csv
from exubrush.util.units import UnitError, convert

SWEEP_FILE = "sweep.json"
SUMMARY_FILES = ("summary.csv", "summary.parquet", "sensitivity.csv")


@dataclass
class RunState:
    """A run of the sweep while it goes on."""

    run: SweepRun
    prepared: PreparedCase
    folder: Path
    status: str = "pending"  # pending, completed, failed, interrupted
    store: RunDirectory | None = None
    solutions: list = field(default_factory=list)
    returned: int = 0
    metrics: dict = field(default_factory=dict)


@dataclass(frozen=True)
class SweepOutcome:
    """What a sweep did: run counts by status and the files it wrote."""

    counts: dict[str, int]
    skipped: int
    interrupted: bool
    wall_time: float
    written: tuple[str, ...]


def prepare_runs(plan: SweepPlan) -> list[PreparedCase]:
    """Prepare every run before anything is written (SweepError naming the run)."""
    prepared = []
    for run in plan.runs:
        try:
            prepared.append(prepare(run.case))
        except (ParameterError, UnitError) as err:
            raise SweepError(f"{plan.source.name}: run {run.name}: {err}") from None
    return prepared


def default_folder(plan: SweepPlan) -> Path:
    """``results/sweeps/NAME`` with the name made safe as one directory name."""
    return Path("results") / "sweeps" / safe_name(plan.name)


def sweep_identity(plan: SweepPlan, prepared: list[PreparedCase]) -> dict:
    """What makes two sweeps the same: every run's name and identity as a single run's
    resume knows it (exubrush.output.rundir.case_fingerprint: its parameters but the limits,
    and the data read from every input file, e.g. a pose CSV, a mesh), hashed in
    ``fingerprint``; ``inputs`` keeps each run's input-file hashes, to say which changed."""
    runs = [[run.name, case_fingerprint(case)] for run, case in zip(plan.runs, prepared,
                                                                    strict=True)]
    return {"fingerprint": hashlib.sha256(json.dumps(runs).encode()).hexdigest()[:16],
            "inputs": {run.name: dict(case.inputs) for run, case in zip(plan.runs, prepared,
                                                                       strict=True)}}


def _changed_inputs(stored: dict, identity: dict) -> str:
    """``; KEY of run RUN has other content ...`` for the first run whose input file
    ``stored`` (sweep.json) hashes otherwise; empty if none does (or it holds no hashes)."""
    before = stored.get("inputs")
    for name, inputs in identity["inputs"].items():
        old = before.get(name) if isinstance(before, dict) else None
        changed = [key for key, digest in inputs.items()
                   if isinstance(old, dict) and old.get(key) not in (None, digest)]
        if changed:
            return f"; {changed[0]} of run {name} has other content than when it was solved"
    return ""


def check_folder(folder: Path, plan: SweepPlan, prepared: list[PreparedCase]) -> None:
    """Refuse (SweepError) a folder that is a file, holds another sweep (or this one with
    other parameters or input files: :func:`sweep_identity`), or holds files this sweep
    does not write. Writes nothing."""
    reason = unusable_directory(folder)
    if reason:
        raise SweepError(f"--out {folder}: {reason}")
    present = {p.name for p in folder.iterdir()} if folder.is_dir() else set()
    record = folder / SWEEP_FILE
    if present and SWEEP_FILE not in present:
        raise SweepError(f"--out {folder}: holds files that are not an exubrush sweep "
                         f"({', '.join(sorted(present)[:3])}); choose a new or empty directory")
    if record.is_file():
        identity = sweep_identity(plan, prepared)
        try:
            stored = json.loads(record.read_text())
        except (OSError, ValueError):
            stored = None
        stored = stored if isinstance(stored, dict) else {}
        if stored.get("fingerprint") != identity["fingerprint"]:
            raise SweepError(f"--out {folder}: holds another sweep (or this sweep file, or a "
                             "file its runs read, was changed since"
                             f"{_changed_inputs(stored, identity)}); sweeps never share a "
                             "folder: choose another --out")
    ours = {SWEEP_FILE, *SUMMARY_FILES, *(run.name for run in plan.runs)}
    foreign = sorted(n for n in present - ours
                     if not (n.startswith("summary-") and n.endswith(".png"))
                     and not n.startswith("."))
    if foreign:
        raise SweepError(f"--out {folder}: holds files this sweep did not write "
                         f"({', '.join(foreign[:3])}); move them or choose another --out")
    for run in plan.runs:
        _check_run_folder(folder / run.name)


def _check_run_folder(directory: Path) -> None:
    """Refuse (SweepError) a run folder whose run.json, or whose completed results (the
    summary reads them), cannot be read back: the sweep would stop on it later."""
    remake = f"; delete {directory} and run the sweep again to solve that run anew"
    try:
        record = run_record(directory)
    except (OSError, ValueError) as err:  # not text, not JSON, not an object
        raise SweepError(f"{directory / 'run.json'}: not a run record of exubrush ({err})"
                         f"{remake}") from None
    if record is not None and record.get("status") == "completed":
        try:
            read_results(directory)
        except ResultsError as err:
            raise SweepError(f"{str(err).removesuffix(REMAKE)}{remake}") from None


def claim_folder(folder: Path, plan: SweepPlan, prepared: list[PreparedCase]) -> None:
    """:func:`check_folder`, then mark the folder as this sweep's (sweep.json)."""
    check_folder(folder, plan, prepared)
    folder.mkdir(parents=True, exist_ok=True)
    with atomic_file(folder / SWEEP_FILE, "w") as handle:
        json.dump({"name": plan.name, **sweep_identity(plan, prepared),
                   "sweep_file": str(plan.source), "runs": [r.name for r in plan.runs]},
                  handle, indent=2)


def run_sweep(plan: SweepPlan, folder: str | Path, executor: Executor,
              retry_failed: bool = False, progress: bool = True,
              prepared: list[PreparedCase] | None = None) -> SweepOutcome:
    """Solve every run of ``plan`` not finished in ``folder`` with ``executor`` and write
    the run folders and the summary.

    Parameters
    ----------
    plan : SweepPlan
        The sweep (exubrush.sweep.plan.read_sweep).
    folder : path
        The sweep folder; an unfinished run of the same sweep there is resumed.
    executor : Executor
        Runs all the runs' bristle groups as one queue (a Dask cluster, a process pool).
    retry_failed : bool
        Solve failed runs again (their finished groups are kept); else they stay failed.
    progress : bool
        Show one progress bar for the sweep on standard error.
    prepared : list of PreparedCase, optional
        The runs already prepared (prepare_runs), else prepared here.
    """
    folder = Path(folder)
    prepared = prepared if prepared is not None else prepare_runs(plan)
    claim_folder(folder, plan, prepared)
    states = [RunState(run, case, folder / run.name) for run, case in zip(plan.runs, prepared,
                                                                          strict=True)]
    tasks, skipped = [], 0
    for number, state in enumerate(states):
        recorded = recorded_status(state.folder)
        if recorded == "completed" or (recorded == "failed" and not retry_failed):
            state.status, skipped = recorded, skipped + 1
            continue
        state.store = RunDirectory(state.folder, state.prepared, overwrite=False,
                                   afresh=f"delete {state.folder} to solve that run anew")
        stored = state.store.stored_groups()
        state.solutions = [stored.get(i) for i in range(len(state.prepared.groups))]
        state.returned = len(stored)
        tasks += [SolveTask(state.prepared, i, selection, run=number)
                  for i, selection in state.prepared.solved_groups if i not in stored]
        if state.returned == len(state.prepared.solved_groups):
            _finish(state, executor)
    total = sum(s.prepared.motion.end_time * len(s.prepared.solved_groups) for s in states
                if s.store is not None)
    done = sum(s.prepared.motion.end_time * s.returned for s in states if s.store is not None)
    bar = SimulatedTimeBar(total, 1, f"sweep {plan.name}", progress,
                           unit="s simulated (all groups)")
    bar.advance(done)
    bar.note(_runs_note(states))
    start = time.perf_counter()

    def solved(task: SolveTask, solution) -> None:
        if solution.interrupted:  # stopped on request: its run stays unfinished, to resume
            return
        state = states[task.run]
        state.solutions[task.index] = solution
        state.returned += 1
        if solution.completed:
            state.store.keep(task.index, solution)
        if state.returned == len(state.prepared.solved_groups):
            _finish(state, executor)
            bar.note(_runs_note(states))

    interrupted = executor.run(tasks, solved, bar.advance) if tasks else False
    bar.close()
    for state in states:
        if state.status == "pending":
            state.status = "interrupted"
    written = write_summary(plan, states, folder)
    counts = {status: sum(s.status == status for s in states)
              for status in ("completed", "failed", "interrupted")}
    return SweepOutcome(counts, skipped, interrupted and counts["interrupted"] > 0,
                        time.perf_counter() - start, tuple(written))


def _runs_note(states: list[RunState]) -> str:
    finished = sum(s.status in ("completed", "failed") for s in states)
    return f"runs {finished}/{len(states)}"


def _finish(state: RunState, executor: Executor) -> None:
    """Assemble and write a run whose every group came back."""
    # runs of a sweep overlap: a run's own wall time is its solves' time, summed
    compute = sum(s.wall_time for s in state.solutions if s is not None)
    facts = RunFacts(interrupted=False, wall_time=compute,
                     workers=executor.workers, resumed=state.store.resumed)
    results = assemble_results(state.prepared, state.solutions, facts)
    results.save(state.folder)
    state.status = results.metadata["status"]
    if state.status == "completed":
        state.store.close()


def _value_columns(plan: SweepPlan) -> list[str]:
    return [f"{s.key} [{s.unit}]" if s.unit else s.key for s in plan.swept]


def _case_value(case, key: str, unit: str):
    """The value of dotted ``key`` in ``case``, in ``unit`` (the sweep file's): a number or
    a text as it is, a vector (e.g. motion.pivot) as the text ``[x, y, z]`` of its
    components in ``unit``, so that every cell of summary.csv is one value."""
    value = case
    for part in key.split("."):
        value = getattr(value, part)
    if isinstance(value, tuple | list):
        _, meta = describe_key(Case, key)
        return json.dumps([convert(v, meta["unit"], unit) if unit else v for v in value])
    if not unit or isinstance(value, str):
        return value
    _, meta = describe_key(Case, key)
    return convert(value, meta["unit"], unit)


def write_summary(plan: SweepPlan, states: list[RunState], folder: Path) -> list[str]:
    """summary.csv (+ .parquet), sensitivity.csv and the summary plots; returns the names."""
    columns = _value_columns(plan)
    values = {column: [_case_value(state.run.case, swept.key, swept.unit) for state in states]
              for swept, column in zip(plan.swept, columns, strict=True)}
    header = ["run", "status", *columns, "compute_time [s]", "simulated_time [s]",
              *(f"{name} [{unit}]" for name, unit in METRICS)]
    rows = []
    for number, state in enumerate(states):
        state.metrics = dict.fromkeys((m for m, _ in METRICS), math.nan)
        simulated = compute = math.nan
        if state.status in ("completed", "failed"):
            try:  # from the files, as written (9 digits), also for runs of this command:
                results = read_results(state.folder)  # a resumed sweep's table is the same
                state.metrics = run_metrics(results)
                simulated = float(results.metadata.get("simulated_time_s", math.nan))
                compute = float(results.metadata.get("solver_wall_time_s_sum", math.nan))
            except ResultsError:
                pass  # a failed run that stored no time series: its row stays empty
        rows.append([state.run.name, state.status, *(v[number] for v in values.values()),
                     compute, simulated, *state.metrics.values()])
    write_csv(folder / "summary.csv", header, rows)
    written = ["summary.csv"]
    if write_parquet(folder / "summary.parquet", header, rows):
        written.append("summary.parquet")
    completed = [n for n, state in enumerate(states) if state.status == "completed"]
    numeric = {swept.key: np.array([values[column][n] for n in completed], dtype=float)
               for swept, column in zip(plan.swept, columns, strict=True)
               if all(isinstance(values[column][n], int | float) for n in completed)}
    if completed and numeric:
        measured = {name: np.array([states[n].metrics[name] for n in completed])
                    for name, _ in METRICS}
        table = sensitivities(numeric, measured)
        write_csv(folder / "sensitivity.csv", ["metric", *numeric],
                    [[metric, *by_parameter.values()] for metric, by_parameter in table.items()])
        written.append("sensitivity.csv")
    written += plot_summary(plan.name, values, [s.status for s in states],
                            [s.metrics for s in states], folder)
    return written
