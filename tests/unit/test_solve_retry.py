"""A failed solve is solved once more with a full Newton (exubrush.run.solve.solve_group)."""

import dataclasses

import numpy as np

import exubrush.run.solve as solve
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.run.solution import INTERRUPTED, GroupSolution, SolverStatistics


def record(samples: int, completed: bool, message: str = "") -> GroupSolution:
    """A group's record with ``samples`` times and 10 steps of statistics."""
    return dataclasses.replace(
        GroupSolution.not_solved(message), time=np.arange(samples) * 0.01,
        completed=completed, statistics=SolverStatistics(steps=10), wall_time=1.0)


def solves(monkeypatch, outcomes):
    """Patch solve_once to return ``outcomes`` in turn; returns the modified_newton and the
    monitor each call was given."""
    calls = []

    def fake(prepared, selection, monitor=None):
        calls.append((prepared.case.solver.modified_newton, monitor))
        return outcomes[len(calls) - 1]

    monkeypatch.setattr(solve, "solve_once", fake)
    return calls


def test_a_failed_solve_is_solved_again_with_a_full_newton(monkeypatch):
    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1"]))
    calls = solves(monkeypatch, [record(5, False, "SolveDynamic terminated"),
                                 record(9, True)])
    result = solve.solve_group(prepared, (0,))
    assert [modified for modified, _ in calls] == [True, False]
    assert result.completed and result.retried and result.message == ""
    assert result.statistics.steps == 20 and result.wall_time == 2.0  # both solves count
    assert len(result.time) == 9


def test_a_retry_that_fails_sooner_keeps_the_first_record_and_both_reasons(monkeypatch):
    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1"]))
    solves(monkeypatch, [record(7, False, "first reason"), record(3, False, "second reason")])
    result = solve.solve_group(prepared, (0,))
    assert not result.completed and result.retried and len(result.time) == 7
    assert "first reason" in result.message and "second reason" in result.message


def test_no_retry_after_a_stop_request_success_or_a_full_newton(monkeypatch):
    for overrides, outcome in ((["solver.modified_newton=true"], record(4, False, INTERRUPTED)),
                               (["solver.modified_newton=true"], record(4, True)),
                               (["solver.modified_newton=false"], record(4, False, "x"))):
        prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1",
                                                    *overrides]))
        calls = solves(monkeypatch, [outcome])
        result = solve.solve_group(prepared, (0,))
        assert len(calls) == 1 and not result.retried


def test_the_retry_reports_no_progress_but_hears_stop_requests(monkeypatch):
    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1"]))

    class Monitor:
        advanced = 0.0

        def advance(self, simulated):
            self.advanced += simulated

        def stop_requested(self):
            return True

    calls = solves(monkeypatch, [record(5, False, "failed"), record(9, True)])
    monitor = Monitor()
    solve.solve_group(prepared, (0,), monitor)
    retry_monitor = calls[1][1]
    retry_monitor.advance(1.0)
    assert monitor.advanced == 0.0 and retry_monitor.stop_requested()


def test_a_solve_that_needs_no_retry_builds_no_case_for_one(monkeypatch):
    """The full-Newton case is made only for a retry: each made a checked Case, 48 in a
    default orthogonal run whose groups all completed (issue 49)."""
    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1"]))
    made = []
    monkeypatch.setattr(solve, "full_newton", lambda case: made.append(case))
    for outcome in (record(4, True), record(4, False, INTERRUPTED)):
        solves(monkeypatch, [outcome])
        solve.solve_group(prepared, (0,))
    assert made == []
