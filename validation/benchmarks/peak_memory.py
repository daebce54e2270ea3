"""Peak resident memory of the processes that solve, read from Linux's /proc.

``getrusage``'s ``ru_maxrss`` cannot be used for worker processes started with "spawn": a
spawned worker is forked from its parent before it executes a fresh interpreter, and Linux
carries the forked image's high-water mark (the parent's whole resident set at that moment)
into the new process's ``ru_maxrss``. ``VmHWM`` in /proc/PID/status is the high-water mark
of the process's current image only. :class:`PeakMemory` samples it for this process and
for every child that is a multiprocessing worker (its command line runs ``spawn_main``)
while they run, and keeps the largest value per process. Other children are left out: a
child caught between its fork and its exec (``git`` asked for the commit, say) still shows
its parent's high-water mark.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

SAMPLE_INTERVAL = 0.05  # s between two looks at the children


def high_water_mark_mb(pid: int) -> float | None:
    """VmHWM of process ``pid`` [MB], or None if it is gone or unreadable."""
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def worker_children(pid: int) -> list[int]:
    """Process ids of the multiprocessing workers among the children of ``pid``."""
    found = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            found.extend(int(child) for child in (task / "children").read_text().split())
        except (OSError, ValueError):
            continue
    return [child for child in found if _is_worker(child)]


def _is_worker(pid: int) -> bool:
    try:
        return b"spawn_main" in Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return False


class PeakMemory:
    """``with PeakMemory() as peak: ...``; then ``peak.children_mb`` (the largest VmHWM of
    any worker child seen, None if there was none) and ``peak.self_mb``."""

    def __init__(self):
        self.peaks: dict[int, float] = {}
        self.children_mb: float | None = None
        self.self_mb: float | None = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._sample, daemon=True)

    def _sample(self) -> None:
        while not self._stop.wait(SAMPLE_INTERVAL):
            for pid in worker_children(os.getpid()):
                value = high_water_mark_mb(pid)
                if value is not None:
                    self.peaks[pid] = max(value, self.peaks.get(pid, 0.0))

    def __enter__(self) -> PeakMemory:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join()
        self.children_mb = max(self.peaks.values()) if self.peaks else None
        self.self_mb = high_water_mark_mb(os.getpid())
