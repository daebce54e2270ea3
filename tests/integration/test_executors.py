"""The local executors' stop contract: after Ctrl-C or SIGTERM, solves in progress return
what they have, tasks not started return nothing, and the run ends (exubrush.execution)."""

import os
import signal
import time

import pytest

from exubrush.execution import SolveTask
from exubrush.execution.local import ProcessExecutor, SerialExecutor
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare


@pytest.fixture(scope="module")
def tasks():
    # twelve one-bristle groups of about a second each: more than two workers finish
    # before a stop reaches them
    prepared = prepare(load_case("orthogonal", ["model.segments=2", "motion.periods=1",
                                                "head.rows=1", "head.columns=12"]))
    return [SolveTask(prepared, index, selection)
            for index, selection in enumerate(prepared.groups)]


@pytest.mark.parametrize("executor", [SerialExecutor(), ProcessExecutor(2)],
                         ids=["serial", "process pool"])
def test_a_sigterm_after_the_first_solve_stops_the_run(tasks, executor):
    solved = []

    def keep(task, solution):
        solved.append(solution)
        if len(solved) == 1:  # the signal a terminal or a scheduler sends
            os.kill(os.getpid(), signal.SIGTERM)

    start = time.monotonic()
    interrupted = executor.run(tasks, keep, lambda seconds: None)
    assert interrupted
    # the solves running when the stop came may still report (cut short), the queued
    # ones do not: the serial executor stops at once, the pool within its two workers
    # and the few tasks already handed to them
    assert 1 <= len(solved) < len(tasks)
    assert solved[0].completed
    # a solve takes about a second here; twelve would take several: the run did not go on
    assert time.monotonic() - start < 60
    # and the handlers are back as they were (pytest's: SIGTERM not caught)
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
