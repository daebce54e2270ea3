"""Running solve tasks: the executor interface and the local executors.

An executor takes a list of :class:`SolveTask` (bristle groups, of one run or of the many runs
of a sweep), runs :func:`exubrush.run.solve.solve_group` for each wherever it likes, and hands every
:class:`~exubrush.run.solve.GroupSolution` back to the caller, in the caller's process, as it
finishes. It reports progress in simulated seconds and stops cleanly on Ctrl-C or SIGTERM:
solves in progress return what they have, tasks not started return nothing. The physics
never sees which executor runs it; a distributed engine plugs in as one more
:class:`Executor`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from exubrush.run.prepared import PreparedCase
from exubrush.run.solution import GroupSolution


@dataclass(frozen=True, eq=False)
class SolveTask:
    """One bristle group to solve: the prepared run it belongs to, the group's index in that
    run, the bristles in it, and the run's index among the runs solved together (0 for a
    single run, the run's number in a sweep)."""

    prepared: PreparedCase
    index: int
    selection: tuple[int, ...]
    run: int = 0


class Executor(ABC):
    """Runs solve tasks with progress and clean stops (see the package docstring)."""

    @abstractmethod
    def run(self, tasks: Sequence[SolveTask],
            solved: Callable[[SolveTask, GroupSolution], None],
            advance: Callable[[float], None]) -> bool:
        """Solve ``tasks``; call ``solved(task, solution)`` here as each one finishes and
        ``advance(seconds)`` with the simulated time solved since the last call (summed
        over tasks).

        Returns
        -------
        bool
            True if the run was interrupted (Ctrl-C or SIGTERM) before every task finished.
        """

    @property
    @abstractmethod
    def workers(self) -> int:
        """How many tasks can run at once."""
