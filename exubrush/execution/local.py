"""Executors on this machine: in this process, or a pool of worker processes.

Exudyn's threads do not mix with Python user functions, so parallel work uses processes
("spawn": a fresh interpreter per worker, as on every platform). Ctrl-C, or a SIGTERM sent
to the whole process group, reaches every worker; the parent decides: workers ignore
SIGINT and SIGTERM, and an event asks the running solves to stop at their next check and
return what they have; tasks not started return at once. A worker whose parent died
(kill -9) exits at once instead of computing on as an orphan.
"""

from __future__ import annotations

import multiprocessing
import os
import queue
import signal
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool

from exubrush.execution import Executor
from exubrush.execution.signals import StopRequest, signals_redirected
from exubrush.run.solve import solve_group

POLL = 0.2  # s between two looks at the pool and the progress queue


class SerialExecutor(Executor):
    """Solves the tasks one after another in this process; Ctrl-C and SIGTERM stop the
    running solve at its next check."""

    workers = 1

    def run(self, tasks, solved, advance) -> bool:
        stop = StopRequest()
        monitor = _Monitor(stop, advance)
        with signals_redirected(stop):
            for task in tasks:
                if stop.is_set():
                    break
                solved(task, solve_group(task.prepared, task.selection, monitor))
        return stop.is_set()


class ProcessExecutor(Executor):
    """Solves the tasks in ``processes`` worker processes."""

    def __init__(self, processes: int):
        self.processes = processes

    @property
    def workers(self) -> int:
        return self.processes

    def run(self, tasks, solved, advance) -> bool:
        context = multiprocessing.get_context("spawn")
        updates, stop = context.Queue(), context.Event()
        requested = StopRequest()
        with (signals_redirected(requested),
              ProcessPoolExecutor(min(self.processes, len(tasks)), mp_context=context,
                                  initializer=_init_worker,
                                  initargs=(updates, os.getpid(), stop)) as pool):
            futures = {pool.submit(_solve_in_worker, task.prepared, task.selection): task
                       for task in tasks}
            pending = set(futures)
            while pending:
                done, pending = wait(pending, timeout=POLL, return_when=FIRST_COMPLETED)
                for future in done:
                    try:
                        result = future.result()
                    except BrokenProcessPool:
                        if requested.is_set():  # a worker the same SIGTERM reached before
                            continue  # it could ignore it (still starting): a clean stop
                        raise
                    if result is not None:
                        solved(futures[future], result)
                _drain(updates, advance)
                if requested.is_set() and not stop.is_set():
                    # running solves return what they have at their next check, the others
                    # None at once. Not Future.cancel: a worker dying after a cancel (the
                    # SIGTERM reaching one still starting) makes Python 3.11's pool manager
                    # thread raise InvalidStateError and the pool hang for ever
                    stop.set()
        # after the pool has shut down: a worker's last report may reach the queue after
        # its result, and is flushed only when the worker exits
        _drain(updates, advance)
        return requested.is_set()


def local_executor(workers: int | None, tasks: int) -> Executor:
    """A process pool of ``workers`` (default: every core) processes, or the serial
    executor where one process is enough."""
    workers = workers or os.cpu_count() or 1
    if workers <= 1 or tasks <= 1:
        return SerialExecutor()
    return ProcessExecutor(workers)


class _Monitor:
    """A solve's monitor: progress to ``advance``, stop when ``stop`` is set, and exit at
    once if the process that started this one is gone."""

    def __init__(self, stop, advance, parent: int | None = None):
        self.stop, self.advance_to, self.parent = stop, advance, parent

    def advance(self, simulated: float) -> None:
        self.advance_to(simulated)

    def stop_requested(self) -> bool:
        if self.parent is not None and os.getppid() != self.parent:
            os._exit(1)  # orphaned: nobody will read the result
        return self.stop.is_set()


_WORKER: dict = {"monitor": None}


def _init_worker(updates, parent: int, stop) -> None:
    """Pool initializer: progress goes to ``updates``, ``stop`` asks for a clean stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    _WORKER["monitor"] = _Monitor(stop, updates.put, parent)


def _solve_in_worker(prepared, selection):
    """Solve one group, or return None at once if the run was stopped before it began."""
    monitor = _WORKER["monitor"]
    if monitor.stop_requested():
        return None
    return solve_group(prepared, selection, monitor)


def _drain(updates, advance) -> None:
    """Pass the workers' progress reports on."""
    while True:
        try:
            advance(updates.get_nowait())
        except queue.Empty:
            return
