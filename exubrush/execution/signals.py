"""Ctrl-C and SIGTERM, handled where a run can stop cleanly."""

from __future__ import annotations

import contextlib
import signal
import threading


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
