"""Prescribed head motion: values and consistency of derivatives."""

import math

import numpy as np
import pytest

from exubrush.world.motion import HeadMotion
from exubrush.world.slide import SineSlide, TabulatedSlide, read_slide_csv, smooth_step


def _finite_difference(f, t, h=1e-5):
    return (f(t + h) - f(t - h)) / (2 * h)


def test_paper_motions_reach_7_85_mm_per_s():
    orthogonal, parallel = SineSlide(15.0, 12.0, 1), SineSlide(30.0, 24.0, 1)
    assert orthogonal.evaluate(0.0)[1] == pytest.approx(15 * math.pi / 6, rel=1e-14)
    assert parallel.evaluate(0.0)[1] == pytest.approx(30 * math.pi / 12, rel=1e-14)
    assert orthogonal.evaluate(0.0)[1] == pytest.approx(7.85, abs=5e-3)  # printed digits


@pytest.mark.parametrize("tau", [0.1, 0.37, 0.5, 0.9])
def test_smooth_step_derivatives(tau):
    s, ds, dds = smooth_step(tau)
    # central differences, h = 1e-5: error O(h²) ~ 1e-9 relative
    assert ds == pytest.approx(_finite_difference(lambda x: smooth_step(x)[0], tau), rel=1e-6)
    assert dds == pytest.approx(_finite_difference(lambda x: smooth_step(x)[1], tau), rel=1e-6,
                                abs=1e-8)
    assert smooth_step(0) == (0, 0, 0) and smooth_step(1) == (1, 0, 0)


def test_head_motion_phases():
    motion = HeadMotion(1.5, 1.0, 0.2, SineSlide(15.0, 12.0, 2.0))
    assert motion.slide_start == pytest.approx(1.2)
    assert motion.end_time == pytest.approx(25.2)
    assert motion.descent(1.0)[0] == pytest.approx(1.5)
    assert motion.sliding(1.2) == (0.0, 0.0, 0.0)
    assert motion.sliding(1.2 + 3.0)[0] == pytest.approx(15.0, rel=1e-12)


def test_tabulated_slide_reproduces_a_sine():
    t = np.linspace(0, 12, 1201)
    table = TabulatedSlide(t, 15 * np.sin(np.pi * t / 6))
    # monotone cubic on 0.01 s samples: at an extremum of the data (t = 3 s) its slope is
    # set to zero and the error is second order, at most h² max|f''| / 8 =
    # 1e-4 s² · 15 mm (π/6 /s)² / 8 = 5.1e-5 mm
    assert table.evaluate(3.005)[0] == pytest.approx(15 * np.sin(np.pi * 3.005 / 6), abs=5.2e-5)
    assert table.evaluate(0.5)[1] == pytest.approx(15 * np.pi / 6 * np.cos(np.pi / 12), rel=1e-4)


def test_slide_csv_with_units(tmp_path):
    path = tmp_path / "slide.csv"
    path.write_text("time [ms],slider_position [m]\n0,0\n500,0.001\n1000,0.004\n")
    table = read_slide_csv(path)
    assert table.duration == pytest.approx(1.0)
    assert table.evaluate(1.0)[0] == pytest.approx(4.0)


def test_records_at_step_ends_land_on_the_output_grid():
    from exubrush.run.solve import on_output_grid

    # records at the first step end at or after each 0.01 s, as Exudyn writes them
    times = np.array([0.0, 0.0104, 0.02, 0.0301, 0.0407])
    values = np.column_stack([3.0 * times + 1.0, -times])  # linear: interpolation is exact
    grid, resampled = on_output_grid(times, values, 0.01)
    np.testing.assert_allclose(grid, [0.0, 0.01, 0.02, 0.03, 0.04], atol=1e-15)
    np.testing.assert_allclose(resampled, np.column_stack([3.0 * grid + 1.0, -grid]),
                               atol=1e-12)
    nodes = np.zeros((5, 2, 3, 3))  # any trailing shape is kept
    assert on_output_grid(times, nodes, 0.01)[1].shape == (5, 2, 3, 3)


def test_peak_slide_speed_of_a_sine_and_of_its_samples():
    sine = SineSlide(15.0, 12.0, 1.0)
    assert sine.peak_speed == pytest.approx(15 * math.pi / 6, rel=1e-14)
    # a ramp at 4 mm/s between rests: where it leaves the rest, the cubic from slope 0 at
    # t = 1 s to 4 at t = 2 s over the secant 4 mm is -4s³ + 8s², speed -12s² + 16s,
    # largest at s = 2/3: 16/3 mm/s
    times = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
    ramp = TabulatedSlide(times, np.array([0.0, 0.0, 4.0, 8.0, 12.0, 12.0]))
    assert ramp.evaluate(2.0)[1] == pytest.approx(4.0, rel=1e-12)
    assert ramp.peak_speed == pytest.approx(16.0 / 3.0, rel=1e-12)
    # a sine sampled every 0.1 s: PCHIP's slope differs from the sine's by O(0.1²)
    dense = np.arange(0.0, 12.0001, 0.1)
    sampled = TabulatedSlide(dense, 15.0 * np.sin(2 * np.pi * dense / 12.0))
    assert sampled.peak_speed == pytest.approx(sine.peak_speed, rel=1e-2)


def test_peak_slide_acceleration_of_a_sine_and_of_a_ramp():
    assert SineSlide(15.0, 12.0, 1.0).peak_acceleration == pytest.approx(
        15 * (2 * math.pi / 12) ** 2, rel=1e-14)
    # the ramp above: the cubic -4s³ + 8s² leaving the rest at t = 1 s has the acceleration
    # -24s + 16: 16 mm/s² as it leaves, the largest (the other stretches mirror it)
    times = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
    ramp = TabulatedSlide(times, np.array([0.0, 0.0, 4.0, 8.0, 12.0, 12.0]))
    assert ramp.peak_acceleration == pytest.approx(16.0, rel=1e-12)


def test_the_head_slides_faster_than_a_speed_only_in_the_middle_of_a_stroke():
    motion = HeadMotion(1.5, 1.0, 0.2, SineSlide(15.0, 12.0, 2.0))
    start, half = motion.slide_start, 0.5 * motion.slide.peak_speed
    fast = motion.sliding_faster_throughout(half, 0.0, 0.002)  # at a point (its samples)
    assert not fast(0.5)  # approaching
    assert not fast(start)  # at rest before the slide
    assert fast(start + 0.01)  # a sine starts at its peak speed
    assert not fast(start + 3.0)  # the reversal
    # |cos| >= 1/2 within T/6 = 2 s of a speed peak
    assert fast(start + 6.0 + 1.99)
    assert not fast(start + 6.0 + 2.01)


@pytest.mark.parametrize("slide", [
    SineSlide(15.0, 12.0, 2.0),
    # the same sine sampled every 10 ms (PCHIP's speed within 0.011 mm/s of the sine's)
    TabulatedSlide(np.arange(0.0, 24.0001, 0.01),
                   15.0 * np.sin(2 * np.pi * np.arange(0.0, 24.0001, 0.01) / 12.0)),
])
def test_the_head_slides_fast_throughout_a_window_only_without_a_slow_stretch_in_it(slide):
    motion = HeadMotion(1.5, 1.0, 0.2, slide)
    start, half = motion.slide_start, 0.5 * motion.slide.peak_speed
    # |cos(2π τ/12)| >= 1/2 for τ in [0, 2], [4, 8], [10, 14], ...
    fast = motion.sliding_faster_throughout(half, 2.3, 0.002)
    assert not fast(start + 0.1)  # [0.1, 2.4]: slow from τ = 2
    assert fast(start + 4.1)  # [4.1, 6.4]
    assert not fast(start + 5.8)  # [5.8, 8.1]: slow at its end
    # both ends fast, the reversal at τ = 3 between them: slow
    assert abs(motion.sliding(start + 1.9)[1]) >= half
    assert abs(motion.sliding(start + 4.2)[1]) >= half
    assert not fast(start + 1.9)
    assert not fast(start - 0.5)  # before the slide
    assert not fast(start)


def test_the_samples_that_bracket_a_window_decide():
    # 0.6 of the peak speed: slow for τ in (1.7715, 4.2285) s; samples every 0.5 s
    motion = HeadMotion(1.5, 1.0, 0.2, SineSlide(15.0, 12.0, 2.0))
    start, speed = motion.slide_start, 0.6 * motion.slide.peak_speed
    assert not motion.sliding_faster_throughout(speed, 1.2, 0.5)(start + 0.6)  # 2.0 after
    assert not motion.sliding_faster_throughout(speed, 0.5, 0.5)(start + 4.2)  # 4.0 before
    assert motion.sliding_faster_throughout(speed, 0.5, 0.5)(start + 4.6)  # 4.5 .. 5.5
    # far past the slide's end (2 periods, 24 s): the last sample answers, at τ = 24.5 s
    # (sampled to a sample past the end): |cos(2π 24.5/12)| = 0.97 >= 0.6
    assert motion.sliding_faster_throughout(speed, 0.5, 0.5)(start + 100.0)


def test_a_window_longer_than_the_slide_samples_the_slide_only():
    # solver.step_recovery_steps = 2**31 - 1 made a window of 2e7 s: sampling it at 2 ms
    # asked for 80 GiB. The run ends with the slide, so the samples do too.
    motion = HeadMotion(1.5, 1.0, 0.2, SineSlide(15.0, 12.0, 2.0))
    start, half = motion.slide_start, 0.5 * motion.slide.peak_speed
    fast = motion.sliding_faster_throughout(half, 2e7, 0.002)
    assert not fast(start + 0.1)  # the reversal at τ = 3 s lies in the window
