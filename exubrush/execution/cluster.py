"""Solve tasks on a Dask cluster: a local one started here, or one at a scheduler address.

Each task is the same bristle-group solve the process pool runs
(:func:`exubrush.run.solve.solve_group`); its :class:`~exubrush.run.solution.GroupSolution`
comes back to this process, which writes every file, so workers need exubrush installed and
nothing else (no shared disk). Tasks of every run of a sweep go into one queue here; the
scheduler holds only :data:`IN_FLIGHT` tasks per worker thread at a time, each with its
prepared case (tens of kB), so whichever worker is free takes the next one. (A prepared
case shared as one Dask dependency made the scheduler put every task of a run on the worker
holding it: one core of two did the work.)

Faults and stops:

- a worker that dies mid-task is replaced (its nanny restarts it) and the scheduler runs the
  task again elsewhere; a task that kills ``distributed.scheduler.allowed-failures`` + 1
  workers comes back as a failed group whose message says so;
- Ctrl-C or SIGTERM here sets a cluster-wide event: running solves see it at their next
  check (at most :data:`CHECK_INTERVAL` s later) and return what they have, tasks that start
  after it return at once with nothing, and no further task is handed out. The workers of
  a local cluster ignore SIGINT and SIGTERM themselves (they are started with both
  ignored), so a Ctrl-C in the terminal stops the run through this process and not by
  killing the workers.
"""

from __future__ import annotations

import collections
import contextlib
import logging
import os
import signal
import tempfile
import time
import uuid
from collections.abc import Iterator

from exubrush.execution import Executor
from exubrush.execution.signals import StopRequest, signals_redirected
from exubrush.run.solution import GroupSolution

POLL = 0.2  # s between two looks at the futures and the progress queue
CHECK_INTERVAL = 0.5  # s of wall time between a worker's looks at the stop event
REPORT_INTERVAL = 1.0  # s of wall time between a worker's progress reports
CONNECT_TIMEOUT = 10.0  # s to reach a scheduler before giving up
LOCAL_WORKERS_PER_CORE = 4  # most processes of a local cluster per core
IN_FLIGHT = 3  # tasks per worker thread handed to the scheduler at a time (one runs, two wait)
# A worker solves in a thread beside its event loop; what wakes that loop takes the GIL from
# the solve, which calls Python every step. These make a local worker's solves 7-10 % faster
# (docs/decisions/0006); workers of another cluster take them
# from their environment (docs/sweeps.md).
QUIET_WORKERS = {
    "distributed.admin.tick.interval": "1s",  # the event loop's watchdog, 20 ms by default
    "distributed.admin.tick.limit": "30s",  # ... and its warning of a busy loop
    "distributed.worker.profile.enabled": False,  # the statistical profiler, every 10 ms
    "distributed.admin.system-monitor.interval": "5s",  # CPU and memory sampling, 0.5 s
}
SCHEMES = ("tcp", "tls", "inproc", "ws", "wss", "ucx")  # Dask's communication protocols


class ClusterError(RuntimeError):
    """The cluster cannot be reached or used."""


class DaskExecutor(Executor):
    """Runs solve tasks on the cluster of a ``distributed.Client``."""

    def __init__(self, client, local: bool = False):
        self.client, self.local = client, local

    @property
    def workers(self) -> int:
        return max(1, sum(self.client.nthreads().values()))

    def describe(self) -> str:
        """Where the tasks run, for the user: the cluster and its dashboard."""
        where = (f"a local Dask cluster of {self.workers} worker processes" if self.local
                 else f"the Dask cluster at {self.client.scheduler.address} "
                      f"({self.workers} worker threads)")
        link = self.client.dashboard_link
        return f"{where}; dashboard {link}" if link else where

    def run(self, tasks, solved, advance) -> bool:
        from distributed import Event, Queue, wait

        name = f"exubrush-{uuid.uuid4().hex[:12]}"
        stop_event = Event(f"{name}-stop", client=self.client)
        reports = Queue(f"{name}-progress", client=self.client)
        stop = StopRequest()
        waiting = collections.deque(enumerate(tasks))
        running: dict = {}  # future -> (task number, task)

        def submit_more() -> None:
            """Keep IN_FLIGHT tasks per worker thread at the scheduler, no more."""
            if not waiting or stop.is_set():
                return
            window = IN_FLIGHT * self.workers  # asks the scheduler: workers come and go
            while waiting and len(running) < window:
                number, task = waiting.popleft()
                future = self.client.submit(_solve_on_worker, task.prepared, task.selection,
                                            name, number, key=f"exubrush-group-{name}-{number}",
                                            pure=False)
                running[future] = (number, task)

        progress = _Progress(tasks, advance)
        last_look = time.monotonic()
        with signals_redirected(stop), self.client.as_current():
            submit_more()
            while running:
                try:  # back as soon as one finishes
                    batch = wait(list(running), timeout=POLL, return_when="FIRST_COMPLETED").done
                except TimeoutError:
                    batch = ()
                if time.monotonic() - last_look >= POLL:  # the queue is at the scheduler
                    progress.take(reports)
                    last_look = time.monotonic()
                for future in batch:
                    number, task = running.pop(future)
                    solution = _outcome(future, task)
                    future.release()
                    progress.finished(number)
                    if solution is not None:
                        solved(task, solution)
                if stop.is_set() and not stop_event.is_set():
                    # running solves return what they have, the others return None at once
                    stop_event.set()
                submit_more()
        return stop.is_set()


def _outcome(future, task) -> GroupSolution | None:
    """The solution a finished future holds; a failed group if workers kept dying under
    it; None if it never started (stopped first)."""
    from distributed import KilledWorker

    try:
        return future.result()
    except KilledWorker as err:
        return GroupSolution.not_solved(
            f"every worker that ran group {task.index} died ({err}); a worker may be out of "
            "memory: give the workers more memory or run fewer per machine")


class _Progress:
    """Simulated seconds per task: the workers' reports while a task runs, the rest of the
    task's end time when it finishes (a task's solve always accounts for its whole end
    time), late reports of finished tasks ignored, and no task counted past its end time
    (a task run again after its worker died reports twice)."""

    def __init__(self, tasks, advance):
        self.end = [task.prepared.motion.end_time for task in tasks]
        self.reported = [0.0] * len(tasks)
        self.done = [False] * len(tasks)
        self.advance = advance

    def _add(self, number: int, seconds: float) -> None:
        step = min(seconds, self.end[number] - self.reported[number])
        if step > 0.0 and not self.done[number]:
            self.reported[number] += step
            self.advance(step)

    def take(self, reports) -> None:
        """Pass on the reports (task number, seconds) in the queue."""
        with contextlib.suppress(TimeoutError):
            for number, seconds in reports.get(batch=True, timeout=0) or ():
                self._add(number, seconds)

    def finished(self, number: int) -> None:
        self._add(number, self.end[number])
        self.done[number] = True


class _WorkerMonitor:
    """A solve's monitor on a worker: progress and stop checks go through the cluster, at
    most every :data:`REPORT_INTERVAL` and :data:`CHECK_INTERVAL` seconds of wall time,
    shared by the tasks of one run of the executor on this worker (so short tasks do not
    pay a round trip to the scheduler each)."""

    def __init__(self, name: str):
        from distributed import Event, Queue, get_client

        client = get_client()  # the worker's own client
        self.stop_event = Event(f"{name}-stop", client=client)
        self.reports = Queue(f"{name}-progress", client=client)
        self.unreported, self.last_report, self.last_check = 0.0, time.monotonic(), 0.0
        self.stopping, self.task = False, 0

    def advance(self, simulated: float) -> None:
        self.unreported += simulated
        if time.monotonic() - self.last_report >= REPORT_INTERVAL:
            self.reports.put((self.task, self.unreported))
            self.unreported, self.last_report = 0.0, time.monotonic()

    def start(self, task: int) -> None:
        """A new task begins: what the last one did not report, its end reports."""
        self.task, self.unreported = task, 0.0

    def stop_requested(self) -> bool:
        if not self.stopping and time.monotonic() - self.last_check >= CHECK_INTERVAL:
            self.stopping, self.last_check = self.stop_event.is_set(), time.monotonic()
        return self.stopping


_MONITOR: dict = {}  # this worker's monitor: {run name: _WorkerMonitor}, the latest run only


def _solve_on_worker(prepared, selection, name: str, task: int) -> GroupSolution | None:
    """Solve one group, or return None at once if the run was stopped before it began."""
    from exubrush.run.solve import solve_group

    if name not in _MONITOR:
        _MONITOR.clear()
        _MONITOR[name] = _WorkerMonitor(name)
    monitor = _MONITOR[name]
    monitor.start(task)
    if monitor.stop_requested():
        return None
    return solve_group(prepared, selection, monitor)


@contextlib.contextmanager
def dask_executor(scheduler: str = "local", workers: int | None = None,
                  timeout: float = CONNECT_TIMEOUT, label: str = "--scheduler"
                  ) -> Iterator[DaskExecutor]:
    """A Dask executor on a local cluster started here (``scheduler`` "local", ``workers``
    processes, default: every core) or on the cluster whose scheduler is at ``scheduler``
    (``tcp://HOST:PORT``); ClusterError, naming ``label``, if it cannot be reached."""
    if scheduler == "local":
        cores = os.cpu_count() or 1
        workers = workers or cores
        if workers > LOCAL_WORKERS_PER_CORE * cores:
            raise ClusterError(f"{workers} local workers: at most {LOCAL_WORKERS_PER_CORE} per "
                               f"core ({LOCAL_WORKERS_PER_CORE * cores} here); more only slow "
                               "each other's solves: give fewer, or a --scheduler")
        with local_cluster(workers) as client:
            yield DaskExecutor(client, local=True)
        return
    client = connect(scheduler, timeout, label)
    try:
        yield DaskExecutor(client)
    finally:
        client.close()


def connect(address: str, timeout: float = CONNECT_TIMEOUT, label: str = "--scheduler"):
    """A client of the scheduler at ``address`` (``tcp://HOST:PORT``), or ClusterError with
    what to check."""
    from distributed import Client

    scheme, _, location = address.partition("://")
    if scheme not in SCHEMES or not location:
        raise ClusterError(f"{label} {address!r}: not a scheduler address; write it as "
                           "tcp://HOST:PORT (what 'dask scheduler' prints) or 'local'")
    try:
        return Client(address, timeout=timeout, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as err:
        raise ClusterError(f"{label} {address}: no scheduler answered within {timeout:g} s "
                           f"({' '.join(str(err).split())[:120]}); check the address and that "
                           "'dask scheduler' runs there") from None


@contextlib.contextmanager
def local_cluster(workers: int) -> Iterator:
    """A client of a Dask cluster on this machine: ``workers`` processes of one thread each,
    started with SIGINT and SIGTERM ignored (this process handles both), closed on exit
    together with the temporary directory its workers keep their files in."""
    import dask
    from distributed import Client, LocalCluster

    scratch = tempfile.TemporaryDirectory(prefix="exubrush-dask-")  # workers' files, removed
    previous = {s: signal.signal(s, signal.SIG_IGN) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        with dask.config.set(QUIET_WORKERS):
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=":0", silence_logs=logging.ERROR,
                                   local_directory=scratch.name)
    except BaseException:
        scratch.cleanup()
        raise
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
    try:
        with Client(cluster, set_as_default=False) as client:
            yield client
    finally:
        cluster.close()
        scratch.cleanup()
