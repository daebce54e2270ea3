"""validation/benchmarks/newton_attempts.py and setting_forces.py: the attempts' classes, the
replay of a give-up rule on recorded residuals, and the comparison of a setting's forces."""

import numpy as np
import pytest

# four attempts: accepted in 2 and in 5 iterations, failed after 12, accepted in 11
FAILED = np.array([False, False, True, False])
JACOBIANS = np.array([1, 2, 9, 7])
ITERATIONS = np.array([2, 5, 12, 11])


def test_attempts_are_classed_by_iterations_and_the_failed_apart(benchmark_script):
    table = benchmark_script("newton_attempts").by_iterations(FAILED, JACOBIANS, ITERATIONS)
    assert [(count, spent) for _, count, spent in table] == [(1, 1), (1, 2), (1, 7), (1, 9)]
    assert table[-1][0] == "failed"


@pytest.mark.parametrize(("iteration", "ratio", "saved", "stopped"), [
    # the failed attempt's residuals: 1, 0.5, 0.4, ... (above 0.1 to the end): stopped at
    # iteration 3 it saves iterations 4 to 6 (3); the converging one falls to 0.05 at its
    # third and is never stopped by 0.1, but is by 0.01
    (3, 0.1, 3, 0),
    (3, 0.01, 3, 1),
    (5, 0.1, 1, 0),
    (7, 0.1, 0, 0),  # beyond the failed attempt's six iterations: nothing to give up
])
def test_a_give_up_rule_replayed_on_residual_histories(benchmark_script, iteration, ratio,
                                                        saved, stopped):
    histories = [[1.0, 0.5, 0.4, 0.4, 0.3, 0.3],  # failed after six iterations
                 [1.0, 0.2, 0.05, 0.02]]  # accepted (its last residual is not in the list)
    failed = np.array([True, False])
    replay = benchmark_script("newton_attempts").replay
    assert replay(histories, failed, iteration, ratio) == (saved, stopped)


def _run(normal, tangential, peaks, solve):
    return {"normal": normal, "tangential": tangential, "peaks": peaks, "solve": solve,
            "jacobians": 1}


def test_a_settings_forces_are_compared_per_seed_and_summed(benchmark_script):
    compare = benchmark_script("setting_forces").compare
    before = {1: _run(0.060, 0.024, [0.20, 0.21], 30.0), 2: _run(0.058, 0.023, [0.20], 30.0)}
    # seed 1 unchanged; seed 2 jumps to another arrangement (+3.4 % F_n)
    after = {1: _run(0.060, 0.024, [0.20, 0.21], 25.0), 2: _run(0.060, 0.023, [0.202], 25.0)}
    result = compare(before, after)
    assert result["seeds"][1] == {"normal": 0.0, "tangential": 0.0, "peak": 0.0}
    assert result["seeds"][2]["normal"] == pytest.approx(0.060 / 0.058 - 1.0)
    assert result["normal"] == pytest.approx(0.120 / 0.118 - 1.0)  # sums over the seeds
    assert result["tangential"] == pytest.approx(0.0)
    assert result["peak"] == pytest.approx(0.01)
    assert result["speed_up"] == pytest.approx(60.0 / 50.0)
