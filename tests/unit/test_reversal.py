"""The reversal metrics (exubrush.output.reversal) on the synthetic slide of
tests/conftest.py (x = 15 mm sin(ω τ), ω = π/6 rad/s; F_n = 1 + 0.5 exp(-(v / 2 mm/s)²),
F_t = 0.7 tanh(v)), whose flat levels, peaks and peak widths are known in closed form."""

import dataclasses
import math

import numpy as np
import pytest

from exubrush.output.reversal import reversal_metrics, width_above

OMEGA = math.pi / 6.0  # rad/s, the synthetic slide's
SPEED = 15.0 * OMEGA  # mm/s, its peak slide speed


def test_flat_levels_peaks_ratio_and_width_of_the_synthetic_slide(sine_run):
    metrics = reversal_metrics(sine_run(dt=0.001))
    # in the flat zone (|v| >= 0.8 of the peak speed) the bump is below exp(-(0.8 x 7.85 /
    # 2)²) = 5e-5 of its height and tanh(v) within 1e-5 of 1: the levels are 1 and 0.7
    assert set(metrics["flat"]) == {1, -1}
    for direction in (1, -1):
        assert metrics["flat"][direction]["normal_force"] == pytest.approx(1.0, abs=1e-4)
        assert metrics["flat"][direction]["tangential_force"] == pytest.approx(0.7, abs=1e-4)
    # four reversals in two periods, each with the full bump (v = 0 is sampled to within
    # 1 ms: 1 - exp(-(7.85 x 5.2e-4 / 2)²) below 1e-5)
    assert metrics["peaks"] == pytest.approx([1.5] * 4, abs=1e-4)
    assert metrics["ratio"] == pytest.approx(1.5, abs=2e-4)
    # above 1 + half the excess where the bump exceeds 1/2: |v| < 2 sqrt(ln 2) mm/s, i.e.
    # |cos ωτ| < that / SPEED around a reversal; the flat level's 5e-5 and the linear
    # crossings on a 1 ms grid move the width by far less than 1 ms
    half_width = math.asin(2.0 * math.sqrt(math.log(2.0)) / SPEED) / OMEGA
    assert metrics["duration"] == pytest.approx(2.0 * half_width, abs=1e-3)


def test_the_first_reversal_is_left_out_of_the_ratio(sine_run):
    run = sine_run(dt=0.001)
    first = run.time < 1.2 + 6.0  # the first reversal is at 1.2 + 3 s, the second at + 9 s
    normal = np.where(first, 3.0 * run.normal_force - 2.0, run.normal_force)  # bump x 3
    metrics = reversal_metrics(dataclasses.replace(run, normal_force=normal))
    assert metrics["peaks"][0] == pytest.approx(2.5, abs=1e-4)
    assert metrics["ratio"] == pytest.approx(1.5, abs=2e-4)


def test_width_above_interpolates_the_crossings():
    time = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    values = np.array([0.0, 2.0, 4.0, 2.0, 0.0])
    # above 1: from t = 0.5 to t = 3.5 on the straight lines between the samples
    assert width_above(time, values, 2, 1.0) == pytest.approx(3.0, rel=1e-12)
    # above -1 everywhere: the series' ends bound it
    assert width_above(time, values, 2, -1.0) == pytest.approx(4.0, rel=1e-12)


def test_a_run_without_a_later_reversal_is_refused(sine_run):
    with pytest.raises(ValueError, match="reversal after the first"):
        reversal_metrics(sine_run(t_end=6.0, dt=0.01))


def test_a_head_that_does_not_touch_is_refused(sine_run):
    run = sine_run(scale=0.0)
    with pytest.raises(ValueError, match="does not touch"):
        reversal_metrics(run)


def test_a_reversal_without_a_peak_has_no_duration(sine_run):
    run = sine_run(dt=0.01)
    metrics = reversal_metrics(dataclasses.replace(run, normal_force=np.ones_like(run.time)))
    assert metrics["ratio"] == pytest.approx(1.0, rel=1e-12)  # flat everywhere: peak = mean
    assert math.isnan(metrics["duration"])


def test_the_friction_band_benchmark_uses_the_package_definition(benchmark_script):
    # one definition for the benchmark, the sweep summary and the study
    assert benchmark_script("friction_band").reversal_metrics is reversal_metrics
