"""Measured-data reading, alignment and flat-zone/reversal metrics (exubrush.output.experiment)."""

import math

import numpy as np
import pytest

from exubrush.output.experiment import (
    Alignment,
    ForceSeries,
    align,
    compare,
    read_measured_csv,
    strokes,
)


def write_csv(path, text):
    path.write_text(text)
    return path


def test_measured_csv_converts_units(tmp_path):
    path = write_csv(tmp_path / "m.csv", "# measured on rig 2\ntime [ms],slider_position [m],"
                     "normal_force [mN],tangential_force [N]\n0,0,100,0.5\n10,0.001,200,0.25\n")
    series = read_measured_csv(path)
    np.testing.assert_allclose(series.time, [0.0, 0.01])
    np.testing.assert_allclose(series.slider_position, [0.0, 1.0])
    np.testing.assert_allclose(series.normal_force, [0.1, 0.2])
    np.testing.assert_allclose(series.tangential_force, [0.5, 0.25])


@pytest.mark.parametrize("text, message", [
    ("time [s],slider_position [mm],normal_force [N]\n0,0,1\n1,1,1\n",
     "has no column 'tangential_force [unit]'"),
    ("time [s],slider_position [mm],normal_force,tangential_force [N]\n0,0,1,0\n1,1,1,0\n",
     "column 'normal_force' has no unit; write 'normal_force [N]'"),
    ("time [s],slider_position [mm],normal_force [mm],tangential_force [N]\n0,0,1,0\n1,1,1,0\n",
     "cannot be converted to 'N'"),
    ("time [s],slider_position [mm],normal_force [N],tangential_force [N]\n0,0,1,0\n0,1,1,0\n",
     "times must increase strictly, but sample 2 is at 0 s after 0 s"),
    ("time [s],slider_position [mm],normal_force [N],tangential_force [N]\n0,0,1,0\n1,1,x,0\n",
     "line 3, column 'normal_force': 'x' is not a number"),
])
def test_measured_csv_errors_say_what_is_wrong(tmp_path, text, message):
    with pytest.raises(ValueError, match="measured CSV") as err:
        read_measured_csv(write_csv(tmp_path / "m.csv", text))
    assert message in str(err.value)


def test_strokes_of_a_sine_have_the_exact_flat_zone(sine_run):
    run = sine_run(dt=0.001)
    velocity = np.gradient(run.slider_position, run.time)
    found = strokes(run.time, velocity, 0.8)
    # x = A sin(ωτ): strokes turn at ωτ = π/2 + kπ; |v| >= 0.8 peak while |cos ωτ| >= 0.8
    # whole strokes only: not the quarter stroke from rest nor the one cut off at the end
    assert [s.direction for s in found] == [-1, 1, -1]
    flat = 2.0 * math.acos(0.8) / (math.pi / 6.0)  # ω of the synthetic slide (conftest)
    middle = found[1]
    # tolerance: the flat edges are found on a 1 ms sample grid (plus one sample of the
    # finite-difference velocity)
    assert middle.flat_end - middle.flat_start == pytest.approx(flat, abs=2e-3)
    assert 0.5 * (middle.flat_start + middle.flat_end) == pytest.approx(1.2 + 12.0, abs=2e-3)


def test_strokes_refuse_a_fraction_outside_zero_one():
    with pytest.raises(ValueError, match=r"must lie in \(0, 1\)"):
        strokes(np.arange(3.0), np.ones(3), 1.0)


def test_position_alignment_recovers_a_time_shift(sine_run):
    simulated = sine_run(dt=0.01)
    shift = 0.37  # s: the measurement's clock started 0.37 s after the simulation's
    measured = ForceSeries(simulated.time[100:] - shift, simulated.slider_position[100:],
                           simulated.normal_force[100:], simulated.tangential_force[100:])
    aligned = align(simulated, measured, Alignment(by_position=True, search_window=2.0))
    # tolerance: linear interpolation of a 10 ms sampled sine biases the least-squares fit
    # by far less than a sample
    assert aligned.time_offset == pytest.approx(shift, abs=1e-3)


def test_differences_of_a_scaled_measurement_are_exact(sine_run):
    simulated = sine_run()
    measured = sine_run(scale=1.25)  # every measured force 25 % higher
    aligned = align(simulated, measured, Alignment())
    velocity = np.gradient(simulated.slider_position, simulated.time)
    result = compare(aligned, strokes(simulated.time, velocity, 0.8))
    assert len(result["strokes"]) == 3  # whole strokes between reversals at 3, 9, 15, 21 s
    assert len(result["reversals"]) == 2
    for row in result["strokes"]:
        assert row["relative_difference"]["normal_force"] == pytest.approx(1 / 1.25 - 1)
        assert row["relative_difference"]["tangential_force"] == pytest.approx(1 / 1.25 - 1)
        assert row["relative_difference"]["friction_coefficient"] == pytest.approx(0.0, abs=1e-12)
    for row in result["reversals"]:
        # the bump peaks at v = 0, inside every reversal zone: F_n peak = 1.5 x scale
        assert row["simulated"]["normal_force"] == pytest.approx(1.5, rel=1e-6)
        assert row["ratio"]["normal_force"] == pytest.approx(1 / 1.25)
    assert result["largest_flat_difference"]["normal_force"] == pytest.approx(1 / 1.25 - 1)


def test_sign_flip_and_partial_coverage(sine_run):
    simulated = sine_run()
    measured = sine_run()
    flipped = ForceSeries(measured.time[:1300], measured.slider_position[:1300],
                          measured.normal_force[:1300], -measured.tangential_force[:1300])
    aligned = align(simulated, flipped, Alignment(signs=(("tangential_force", -1.0),)))
    np.testing.assert_allclose(aligned.measured.tangential_force,
                               simulated.tangential_force[:1300])
    velocity = np.gradient(simulated.slider_position, simulated.time)
    result = compare(aligned, strokes(simulated.time, velocity, 0.8))
    # 13 s of data: only stroke 0 (slide time 3 to 9 s) has its flat zone inside
    assert [row["index"] for row in result["strokes"]] == [0]


def test_no_overlap_is_refused(sine_run):
    simulated = sine_run()
    measured = ForceSeries(simulated.time + 100.0, simulated.slider_position,
                           simulated.normal_force, simulated.tangential_force)
    with pytest.raises(ValueError, match="does not overlap the simulation"):
        align(simulated, measured, Alignment())


def test_reversal_zones_of_a_sine_are_centred_on_the_reversals(sine_run):
    from exubrush.output.experiment import reversal_zones

    run = sine_run(dt=0.001)
    velocity = np.gradient(run.slider_position, run.time)
    zones = reversal_zones(run.time, velocity, 0.8)
    # reversals at slide time 3, 9, 15, 21 s (t0 = 1.2 s); |v| < 0.8 peak within
    # asin(0.8)/ω of each; the start from rest and the end at full speed are no reversal
    half = math.asin(0.8) / (math.pi / 6.0)
    assert len(zones) == 4
    for (start, end), reversal in zip(zones, [4.2, 10.2, 16.2, 22.2], strict=True):
        # tolerance: zone edges fall on the 1 ms sample grid
        assert start == pytest.approx(reversal - half, abs=2e-3)
        assert end == pytest.approx(reversal + half, abs=2e-3)
