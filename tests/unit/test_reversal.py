"""The reversal metrics (exubrush.output.reversal) on the synthetic slide of
tests/conftest.py (x = 15 mm sin(ω τ), ω = π/6 rad/s; F_n = 1 + 0.5 exp(-(v / 2 mm/s)²),
F_t = 0.7 tanh(v)), whose flat levels, peaks and peak widths are known in closed form."""

import dataclasses
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from exubrush.output.reversal import (
    SeedRun,
    configuration_table,
    markdown_table,
    reversal_metrics,
    width_above,
)
from exubrush.parameters.io import load_case

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


def _run(configuration, seed, ratio, forward, backward=None, duration=0.5, wall=10.0):
    backward = forward if backward is None else backward
    flat = {1: {"normal_force": forward, "tangential_force": 0.7 * forward},
            -1: {"normal_force": backward, "tangential_force": 0.7 * backward}}
    return SeedRun(configuration, seed, {"flat": flat, "ratio": ratio, "duration": duration},
                   wall)


def test_the_study_table_compares_each_seed_with_the_reference_seed():
    runs = [_run("ideal", 1, 4.0, 1.0), _run("ideal", 2, 6.0, 2.0),
            _run("tilt", 1, 2.0, 1.1, 0.95), _run("tilt", 2, 3.3, 2.0),
            _run("tilt", 3, 9.0, 5.0, duration=math.nan)]  # no reference seed 3
    ideal, tilt = configuration_table(runs, "ideal", flat_band=0.16)
    assert ideal["configuration"] == "ideal" and ideal["seeds"] == [1, 2]
    assert ideal["ratio_change"]["mean"] == 0.0 and not ideal["on_target"]
    assert tilt["seeds"] == [1, 2, 3]
    # the spread over all three seeds, NaN durations left out
    assert tilt["ratio"] == pytest.approx({"mean": 14.3 / 3, "min": 2.0, "max": 9.0})
    assert tilt["duration"] == pytest.approx({"mean": 0.5, "min": 0.5, "max": 0.5})
    # changes only over the shared seeds 1 and 2: R 2/4 - 1 and 3.3/6 - 1
    assert tilt["ratio_change"] == pytest.approx({"mean": -0.475, "min": -0.5, "max": -0.45})
    # flat F_n per direction: +10 % and -5 % (seed 1), 0 and 0 (seed 2)
    assert tilt["flat_normal_change"] == pytest.approx({"mean": 0.0125, "min": -0.05,
                                                        "max": 0.1})
    assert tilt["within_band"]  # 10 % within 16 %
    assert tilt["on_target"]  # R / R_ideal 0.525 within 0.5 x (1 ± 0.2)
    assert not configuration_table(runs, "ideal", flat_band=0.08)[1]["within_band"]


def test_the_study_table_refuses_a_missing_reference_and_a_repeated_seed():
    with pytest.raises(ValueError, match="no completed run"):
        configuration_table([], "ideal", flat_band=0.16)
    with pytest.raises(ValueError, match="no run of the reference configuration 'ideal'"):
        configuration_table([_run("tilt", 1, 2.0, 1.0)], "ideal", flat_band=0.16)
    with pytest.raises(ValueError, match="seed 1 twice"):
        configuration_table([_run("ideal", 1, 2.0, 1.0)] * 2, "ideal", flat_band=0.16)


def test_the_markdown_table_has_a_row_per_configuration_in_mN():
    runs = [_run("ideal", 1, 4.0, 0.5), _run("tilt", 1, 2.0, 0.55, duration=math.nan)]
    lines = markdown_table(configuration_table(runs, "ideal", flat_band=0.16)).splitlines()
    assert len(lines) == 4 and all(line.count("|") == 14 for line in lines)
    assert lines[3].startswith("| tilt | 1 | 550.0 (550.0 to 550.0) |")
    assert "| 2.00 (2.00 to 2.00) | -50.0 (-50.0 to -50.0) | – | +10.0" in lines[3]


def test_the_study_names_a_configuration_by_what_it_sets_away_from_the_ideal_head():
    spec = importlib.util.spec_from_file_location(
        "study", Path(__file__).parents[2] / "validation" / "reversal_peaks" / "study.py")
    study = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(study)
    assert study.configuration_label(load_case("orthogonal")) == "ideal"
    case = load_case("parallel", ["head.tilt_spread_x='3 deg'", "head.length_spread=0.05",
                                  "head.root_jitter='0.2 mm'", "contact.between_bristles=true"])
    assert study.configuration_label(case) == (
        "tilt spread x 3 deg, length spread 5 %, root jitter 0.2 mm, contact between blades")
