"""A sweep's metrics and sensitivities against series and functions whose answer is known."""

import math

import numpy as np
import pytest

from exubrush.output.results import Results
from exubrush.sweep.summary import run_metrics, sensitivities

PERIOD, AMPLITUDE, REST = 2.0, 3.0, 1.0  # s, mm, s


def synthetic_results():
    """Rest, then two sine periods: F_n = 1 N with a 2 N bump at each reversal, F_t =
    +0.3 N moving forward and -0.2 N moving back; one tip swings to (3, 0, 4) mm from its
    root (straight length 5 mm) while the head slides."""
    t = np.linspace(0.0, REST + 2 * PERIOD, 20001)
    phase = np.clip(t - REST, 0.0, None) * 2 * np.pi / PERIOD
    position = AMPLITUDE * np.sin(phase)
    velocity = np.where(t > REST, np.cos(phase), 0.0)
    reversals = REST + PERIOD * np.array([0.25, 0.75, 1.25, 1.75])
    bumps = sum(np.exp(-0.5 * ((t - r) / (0.01 * PERIOD)) ** 2) for r in reversals)
    normal = 1.0 + 2.0 * bumps
    tangential = np.where(velocity > 0, 0.3, np.where(velocity < 0, -0.2, 0.0))
    shape_time = t[::100]
    swing = np.clip(shape_time - REST, 0.0, 1.0)[:, None]  # 0 -> 1 over a second
    root = np.column_stack([AMPLITUDE * np.sin(np.clip(shape_time - REST, 0, None)),
                            np.zeros_like(shape_time), np.zeros_like(shape_time)])
    tip = root + (1 - swing) * np.array([0.0, 0.0, 5.0]) + swing * np.array([3.0, 0.0, 4.0])
    nodes = np.stack([root, (root + tip) / 2, tip], axis=1)[:, None, :, :]
    return Results(time=t, slider_position=position, normal_force=normal,
                   tangential_force=tangential, head_height=np.zeros_like(t),
                   shape_time=shape_time, shape_nodes=nodes)


def test_run_metrics_of_a_known_series():
    metrics = run_metrics(synthetic_results())
    # flat zones (speed >= 80 % of the peak) lie > 0.1 period from every reversal, where the
    # bumps (width 0.01 period) are below 1e-20
    for direction, tangential in (("forward", 0.3), ("backward", 0.2)):
        assert metrics[f"flat_normal_force_{direction}"] == pytest.approx(1.0, rel=1e-12)
        assert metrics[f"flat_tangential_force_{direction}"] == pytest.approx(tangential,
                                                                              rel=1e-12)
        assert metrics[f"friction_coefficient_{direction}"] == pytest.approx(tangential,
                                                                             rel=1e-12)
    # the bump peaks at a sample (reversal times are on the grid): 1 + 2
    assert metrics["reversal_peak_normal_force"] == pytest.approx(3.0, rel=1e-9)
    assert metrics["largest_tip_deflection"] == pytest.approx(math.sqrt(10.0), rel=1e-12)


def test_run_metrics_carry_the_reversal_ratio_its_duration_and_the_flat_mean():
    metrics = run_metrics(synthetic_results())
    # three whole strokes at F_n = 1 N; every later reversal peaks at 1 + 2 N: R = 3
    assert metrics["flat_normal_force"] == pytest.approx(1.0, rel=1e-12)
    assert metrics["reversal_ratio"] == pytest.approx(3.0, rel=1e-9)
    # above 1 + half the excess (2 N) where 2 exp(-t²/2σ²) > 1: the Gaussian's full width
    # at half maximum 2 sqrt(2 ln 2) σ, σ = 0.01 period; linear crossings on a 0.2 ms grid
    # move it by far less than 1e-5 s
    fwhm = 2.0 * math.sqrt(2.0 * math.log(2.0)) * 0.01 * PERIOD
    assert metrics["reversal_peak_duration"] == pytest.approx(fwhm, abs=1e-5)


def test_metrics_of_a_run_without_whole_strokes_are_undefined_not_zero():
    results = synthetic_results()
    short = results.time <= REST + 0.2 * PERIOD  # rest and the first quarter stroke only
    cut = Results(time=results.time[short], slider_position=results.slider_position[short],
                  normal_force=results.normal_force[short],
                  tangential_force=results.tangential_force[short],
                  head_height=results.head_height[short],
                  shape_time=np.zeros(0), shape_nodes=np.zeros((0, 0, 0, 3)))
    metrics = run_metrics(cut)
    assert all(math.isnan(value) for value in metrics.values())


def test_sensitivities_of_a_linear_function_are_exact():
    p1, p2 = np.meshgrid([1.0, 2.0, 3.0], [10.0, 20.0, 40.0], indexing="ij")
    p1, p2 = p1.ravel(), p2.ravel()
    metric = 2.0 + 0.5 * p1 - 0.1 * p2
    seeds = np.arange(p1.size, dtype=float)
    table = sensitivities({"a": p1, "b": p2, "head.seed": seeds}, {"m": metric})["m"]
    at_mean = 2.0 + 0.5 * p1.mean() - 0.1 * p2.mean()
    assert table["a"] == pytest.approx(0.5 * p1.mean() / at_mean, rel=1e-12)
    assert table["b"] == pytest.approx(-0.1 * p2.mean() / at_mean, rel=1e-12)
    assert math.isnan(table["head.seed"])  # repeats, not a trend


def test_sensitivities_the_runs_cannot_determine_are_nan():
    constant = sensitivities({"a": np.ones(4)}, {"m": np.arange(4.0)})["m"]
    assert math.isnan(constant["a"])
    too_few = sensitivities({"a": np.array([1.0, 2.0]), "b": np.array([3.0, 5.0])},
                            {"m": np.array([1.0, 2.0])})["m"]
    assert math.isnan(too_few["a"]) and math.isnan(too_few["b"])
    undefined = sensitivities({"a": np.array([1.0, 2.0, 3.0])},
                              {"m": np.array([1.0, np.nan, np.nan])})["m"]
    assert math.isnan(undefined["a"])
