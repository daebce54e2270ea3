"""Ctrl-C and SIGTERM, handled where a run can stop cleanly."""

from __future__ import annotations

import contextlib
import signal
import threading


class StopRequest:
    """A signal handler that only raises a flag; the code that stops reads it with
    :meth:`is_set` and tells others (a worker event) itself.

    A handler runs in the main thread between two bytecodes: inside another handler (a
    second Ctrl-C, or the two SIGTERMs a process group gets) or while the main thread holds
    a lock. ``threading.Event.set`` and ``multiprocessing.Event.set`` take a non-reentrant
    lock, so a handler calling them can wait forever on its own thread; setting an
    attribute cannot.
    """

    def __init__(self):
        self.requested = False

    def __call__(self, *_) -> None:
        self.requested = True

    def is_set(self) -> bool:
        return self.requested


@contextlib.contextmanager
def signals_redirected(handler):
    """Handle Ctrl-C and SIGTERM with ``handler`` inside the block (restored after it).

    Used to let a solve in this process stop at its next check instead of raising inside
    Exudyn (an exception there surfaces as a solver failure or a traceback), and to finish
    writing results. Outside the main thread signals cannot be handled: no change.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {number: signal.signal(number, handler)
                for number in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for number, old in previous.items():
            signal.signal(number, old)
