"""Compose a brushing simulation: prepare the case, solve its bristle groups, assemble.

With the head's motion prescribed and no bristle-bristle contact, the bristles do not
interact: the head force is the sum of the bristles' forces. By default
(``solver.partition = "per-bristle"``) every bristle is therefore its own small Exudyn
system, solved in parallel processes (Exudyn's threads do not mix with Python user
functions); ``"coupled"`` solves the whole head as one system, which the same forces must
come out of (tests/integration/test_partition.py).

>>> import exubrush
>>> results = exubrush.simulate(exubrush.load_case("orthogonal"))   # doctest: +SKIP
>>> results.save("results/orthogonal")                              # doctest: +SKIP
"""

from __future__ import annotations

import time

from exubrush.execution import Executor, SolveTask
from exubrush.execution.local import local_executor
from exubrush.execution.progress import SimulatedTimeBar
from exubrush.output.assemble import RunFacts, assemble_results
from exubrush.output.results import Results
from exubrush.output.rundir import RunDirectory
from exubrush.parameters.case import Case
from exubrush.run.prepared import PreparedCase, prepare


def simulate(case: Case | PreparedCase, progress: bool = True, workers: int | None = None,
             directory: RunDirectory | None = None,
             executor: Executor | None = None) -> Results:
    """Solve ``case`` and return its results.

    If a solve fails or the run is interrupted, the results hold the head force over the
    time every group reached (nothing if a group never started) and ``metadata["status"]``
    says "failed" or "interrupted" with the reason.

    Parameters
    ----------
    case : Case or PreparedCase
        What to run; a Case is prepared first (exubrush.run.prepared.prepare).
    progress : bool
        Show a progress bar of the simulated time on standard error.
    workers : int, optional
        Processes for the local executor (default: the number of cores).
    directory : RunDirectory, optional
        Where finished groups are stored as they finish, and read back when resuming.
    executor : Executor, optional
        Runs the solve tasks (default: exubrush.execution.local.local_executor).
    """
    prepared = case if isinstance(case, PreparedCase) else prepare(case)
    tasks = [SolveTask(prepared, index, selection)
             for index, selection in prepared.solved_groups]
    solutions = [None] * len(prepared.groups)
    for index, stored in (directory.stored_groups() if directory else {}).items():
        solutions[index] = stored
    todo = [task for task in tasks if solutions[task.index] is None]
    executor = executor or local_executor(workers, len(todo))
    bar = SimulatedTimeBar(prepared.motion.end_time, len(tasks),
                           f"{prepared.case.name} {prepared.case.model.kind}", progress)
    bar.advance(prepared.motion.end_time * (len(tasks) - len(todo)))

    def solved(task: SolveTask, solution) -> None:
        solutions[task.index] = solution
        if directory is not None and solution.completed:
            directory.keep(task.index, solution)

    start = time.perf_counter()
    interrupted = executor.run(todo, solved, bar.advance) if todo else False
    bar.close()
    facts = RunFacts(interrupted=interrupted, wall_time=time.perf_counter() - start,
                     workers=executor.workers, resumed=directory.resumed if directory else 0)
    return assemble_results(prepared, solutions, facts)


def run_case(case: str, model: str = "dfm", overrides=(), progress: bool = True) -> Results:
    """Simulate a built-in case or case file with ``model`` and ``KEY=VALUE`` overrides."""
    from exubrush.parameters.io import load_case

    return simulate(load_case(case, [f"model.kind='{model}'", *overrides]), progress)
