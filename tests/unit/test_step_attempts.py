"""The step-attempt counter of validation/benchmarks/step_attempts.py: which attempts
failed and what each cost, from the solver's counters read before every attempt."""

import importlib.util
from pathlib import Path

import numpy as np

SCRIPT = Path(__file__).parents[2] / "validation" / "benchmarks" / "step_attempts.py"


def _script(monkeypatch):
    monkeypatch.syspath_prepend(str(SCRIPT.parent))  # its sibling one_bristle.py
    spec = importlib.util.spec_from_file_location("step_attempts", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_retry_marks_the_attempt_before_it_failed_and_costs_add_up(monkeypatch):
    # (end time, start time, Jacobians so far, Newton iterations so far) before each
    # attempt: the second attempt (0.1 -> 0.2 s) failed, its retry went 0.1 -> 0.15 s
    rows = [(0.1, 0.0, 0, 0), (0.2, 0.1, 2, 3), (0.15, 0.1, 10, 15), (0.2, 0.15, 11, 17)]
    ends, failed, jacobians, iterations = _script(monkeypatch).attempt_costs(rows, 12, 18)
    np.testing.assert_array_equal(ends, [0.1, 0.2, 0.15, 0.2])
    np.testing.assert_array_equal(failed, [False, True, False, False])
    np.testing.assert_array_equal(jacobians, [2, 8, 1, 1])
    np.testing.assert_array_equal(iterations, [3, 12, 2, 1])
    assert jacobians.sum() == 12 and iterations.sum() == 18  # every count in one attempt
