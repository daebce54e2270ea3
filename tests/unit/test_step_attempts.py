"""The step-attempt counter of validation/benchmarks/step_attempts.py: which attempts
failed and what each cost, from the solver's counters read before every attempt."""

import numpy as np

# (end time, start time, Jacobians so far, Newton iterations so far) before each attempt:
# 0 -> 0.1 s; 0.1 -> 0.2 s failed, so did its retry 0.1 -> 0.15 s; 0.1 -> 0.125 s; then
# 0.125 -> 0.2 s
ROWS = [(0.1, 0.0, 0, 0), (0.2, 0.1, 2, 3), (0.15, 0.1, 10, 15), (0.125, 0.1, 19, 27),
        (0.2, 0.125, 20, 29)]


def test_retries_mark_the_attempts_before_them_failed_and_each_pays_its_own_counts(
        benchmark_script):
    attempt_costs = benchmark_script("step_attempts").attempt_costs
    starts, failed, jacobians, iterations = attempt_costs(ROWS, 21, 31)
    np.testing.assert_array_equal(starts, [0.0, 0.1, 0.1, 0.1, 0.125])
    np.testing.assert_array_equal(failed, [False, True, True, False, False])
    np.testing.assert_array_equal(jacobians, [2, 8, 9, 1, 1])
    np.testing.assert_array_equal(iterations, [3, 12, 12, 2, 2])


def test_the_last_attempt_of_a_solve_that_stopped_failed(benchmark_script):
    _, failed, _, _ = benchmark_script("step_attempts").attempt_costs(ROWS, 21, 31, finished=False)
    np.testing.assert_array_equal(failed, [False, True, True, False, True])
