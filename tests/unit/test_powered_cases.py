"""The built-in cases of heads that turn or follow a path (docs/motion.md, "The
powered-brush cases"): they load, survive `exubrush case` as TOML, and their heads and
motions are what the docs say."""

import math

import numpy as np
import pytest

from exubrush.parameters.fields import to_toml
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare


@pytest.mark.parametrize("name", ["oscillating-rotating", "sonic", "robot"])
def test_the_case_survives_its_toml(name, tmp_path):
    case = load_case(name)
    path = tmp_path / "case.toml"
    path.write_text(to_toml(case))
    assert load_case(str(path)) == case


def test_the_round_head_fits_its_disc_and_turns_about_its_centre():
    prepared = prepare(load_case("oscillating-rotating"))  # refuses overlapping tufts
    roots = np.array([b.root[:2] for b in prepared.bristles])
    assert len(roots) == 19 * 37
    # every filament (0.2 mm) inside the 11 mm disc
    assert np.hypot(*roots.T).max() + 0.1 <= 5.5
    (turn,) = prepared.case.motion.sine
    assert (turn.axis, prepared.case.motion.pivot) == ("rz", (0.0, 0.0, 0.0))
    # oscillations a minute; a built-in case is read through its TOML text (12 digits)
    assert turn.frequency * 60 == pytest.approx(7600.0, rel=1e-11)
    assert math.degrees(turn.angle) == pytest.approx(20.0, rel=1e-11)
    # the steps while it turns: steps_per_cycle a cycle (exubrush.run.step_policy), counted
    # in the budget
    turning = prepared.motion.end_time - prepared.motion.slide_start
    per_cycle = prepared.case.solver.steps_per_cycle
    assert prepared.work.steps >= turning * per_cycle * turn.frequency


def test_the_sonic_head_swings_across_the_handle_on_a_slow_stroke_along_it():
    prepared = prepare(load_case("sonic"))
    motion = prepared.case.motion
    assert len(prepared.bristles) == 40 * 37  # the manual-brush head
    (swing,) = motion.sine
    # across the handle (the head's long axis is x: 10 tufts along it, 4 across)
    assert (swing.axis, swing.amplitude, swing.frequency) == ("y", 1.5, 258.0)
    np.testing.assert_array_equal(prepared.slide_axis, [1.0, 0.0, 0.0])
    # 0.5 s of brushing after the approach and hold
    start, end = prepared.motion.slide_start, prepared.motion.end_time
    assert end - start == pytest.approx(0.5, rel=1e-12)
    # the stroke under the swing, 15 mm x 2 pi / 4 s = 23.6 mm/s at most along x, is a
    # hundredth of the swing's 1.5 mm x 2 pi x 258 Hz = 2,432 mm/s along y
    strokes = [prepared.motion.sliding(t)[1] for t in np.linspace(start, end, 101)]
    peak = 15.0 * 2 * math.pi / 4.0
    assert 0.999 * peak <= max(np.abs(strokes)) <= peak * (1 + 1e-12)  # sampled near t = 0
    swings = [prepared.motion.pose.evaluate(t)[1] for t in np.linspace(start + 0.1, end, 2001)]
    assert np.abs(swings).max(axis=0) == pytest.approx([0, 2 * math.pi * 258 * 1.5, 0, 0, 0, 0],
                                                     rel=1e-3, abs=1e-9)
    # the output resolves the swing (vibration.py needs 4 samples a cycle) and the steps
    # are steps_per_cycle a cycle while it acts, counted in the budget
    assert 1.0 / (swing.frequency * prepared.case.output.interval) >= 15
    per_cycle = prepared.case.solver.steps_per_cycle
    assert prepared.work.steps >= (end - start) * per_cycle * swing.frequency
    # only the tips are kept at every sample: well within the default memory limit
    assert prepared.work.memory < prepared.case.limits.memory / 4


def test_the_robot_follows_its_rectangle_and_stops_at_each_corner():
    prepared = prepare(load_case("robot"))
    pose, start = prepared.motion.pose, prepared.motion.slide_start
    corners = {0.2: (0, 0), 1.2: (0, 10), 2.0: (8, 10), 3.0: (8, 0), 3.8: (0, 0)}
    for t, (x, y) in corners.items():
        position, rate, _ = pose.evaluate(start + t)
        # the table's samples themselves, to the 4 decimals the file holds
        np.testing.assert_allclose(position[:2], [x, y], atol=1e-9)
        np.testing.assert_allclose(rate, 0.0, atol=1e-9)  # at rest at a corner
    _, rate, _ = pose.evaluate(start + 0.7)
    np.testing.assert_allclose(rate[:2], [0.0, 10.0], rtol=1e-9, atol=1e-9)  # mid-leg: 10 mm/s
    assert prepared.motion.end_time == pytest.approx(start + 4.0, rel=1e-12)
