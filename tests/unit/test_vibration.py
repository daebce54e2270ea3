"""The tips' amplitude against the head's for sine pose terms (exubrush.output.vibration)."""

import math

import numpy as np
import pytest

from exubrush.output.vibration import sine_amplitudes, vibration_summary
from exubrush.parameters.case import Motion
from exubrush.parameters.fields import build
from exubrush.parameters.io import load_case


def test_a_sine_on_a_drifting_offset_is_measured_exactly():
    t = np.linspace(0.3, 0.5, 201)  # 10 cycles at 50 Hz, 20 samples a cycle
    values = np.column_stack([0.7 * np.sin(2 * np.pi * 50 * t + 0.4) + 3.0 - 2.0 * t,
                              np.full_like(t, 5.0)])
    # the model holds the signal exactly: least squares recovers it to rounding
    np.testing.assert_allclose(sine_amplitudes(t, values, 50.0), [0.7, 0.0], atol=1e-12)


def _case(sine, **motion):
    case = load_case("orthogonal")
    return case.replace(motion=build(Motion, {"sine": [sine], **motion}, "motion."))


def test_tips_that_follow_a_turn_twice_as_far_are_amplified_twice():
    # two tips on a head turning ±10° about z through the pivot (1, 0, 0): the first turns
    # with it, the second swings 20° about the same axis
    case = _case({"axis": "rz", "angle": "10 deg", "frequency": "40 Hz", "ramp_cycles": 1},
                 pivot=["1 mm", "0 mm", "0 mm"])
    slide_start, rise = 0.2, 1 / 40
    t = np.arange(0.0, 0.5, 1e-3)
    phase = 2 * np.pi * 40 * (t - slide_start)
    angle = np.where(t >= slide_start + rise, np.radians(10.0) * np.sin(phase), 0.0)
    tips = np.zeros((len(t), 2, 3))
    for k, gain in enumerate((1.0, 2.0)):
        tips[:, k, 0] = 1.0 + 3.0 * np.cos(gain * angle)
        tips[:, k, 1] = 3.0 * np.sin(gain * angle)
    pivot = np.tile([1.0, 0.0, 0.0], (len(t), 1))
    (entry,), (amplitude,) = vibration_summary(case, slide_start, t, tips, pivot)
    assert entry["unit"] == "rad" and entry["window_s"][0] == pytest.approx(slide_start + rise)
    np.testing.assert_allclose(amplitude, np.radians([10.0, 20.0]), rtol=1e-9)
    assert entry["amplification_median"] == pytest.approx(1.5, rel=1e-9)


def test_a_shake_is_measured_along_its_axis():
    case = _case({"axis": "y", "amplitude": "0.3 mm", "frequency": "100 Hz"})
    t = np.arange(0.0, 0.3, 2.5e-4)
    tips = np.zeros((len(t), 1, 3))
    tips[:, 0, 1] = 0.45 * np.sin(2 * np.pi * 100 * (t - 0.1)) * (t > 0.12) + 5.0 * t
    tips[:, 0, 0] = 0.2 * np.sin(2 * np.pi * 100 * t)  # across the term's axis: not counted
    (entry,), _ = vibration_summary(case, 0.1, t, tips, np.zeros((len(t), 3)))
    assert entry["amplification_median"] == pytest.approx(1.5, rel=1e-9)


@pytest.mark.parametrize("interval, duration, reason", [
    (4e-3, 1.0, "samples fewer than 4 times a cycle"),
    (1e-4, 0.012, "fewer than 2 whole cycles"),
])
def test_a_term_that_cannot_be_measured_says_why(interval, duration, reason):
    case = _case({"axis": "x", "amplitude": "0.1 mm", "frequency": "100 Hz"})
    t = np.arange(0.0, duration, interval)
    (entry,), (amplitude,) = vibration_summary(case, 0.0, t, np.zeros((len(t), 1, 3)),
                                               np.zeros((len(t), 3)))
    assert reason in entry["skipped"] and amplitude is None
    assert math.isfinite(entry["frequency_Hz"])
