"""Pose terms in a case (``[[motion.sine]]``, ``motion.pose_csv``, ``motion.pivot``): read
and checked as parameters, turned into the head's motion, bounded by the step budget."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exubrush.parameters.case import Case, Motion
from exubrush.parameters.fields import ParameterError, build
from exubrush.parameters.io import load_case
from exubrush.run.budget import term_segments, term_steps, term_windows
from exubrush.run.prepared import prepare
from exubrush.run.step_policy import term_step_cap
from exubrush.world.kinematics import handle_angles, handle_coordinates, handle_kinematics
from exubrush.world.motion import HeadMotion, with_pose
from exubrush.world.pose import SineTerm
from exubrush.world.slide import RestingSlide

SONIC = {"axis": "y", "amplitude": "0.3 mm", "frequency": "260 Hz"}


def _case_file(tmp_path, motion_lines, name="posed"):
    path = tmp_path / f"{name}.toml"
    path.write_text("[head]\nrows = 1\ncolumns = 1\n[motion]\n" + motion_lines)
    return str(path)


def test_a_sine_entry_reads_its_units():
    motion = build(Motion, {"sine": [SONIC, {"axis": "rz", "angle": "20 deg",
                                             "frequency": "7600 1/min"}]})
    y, rz = motion.sine
    assert (y.size, y.frequency) == (0.3, 260.0)
    assert rz.size == pytest.approx(math.radians(20.0), rel=1e-15)  # a unit conversion
    assert rz.frequency == pytest.approx(7600.0 / 60.0, rel=1e-15)
    assert motion.posed and not build(Motion, {}).posed


@pytest.mark.parametrize("entry, message", [
    ({"axis": "rz", "amplitude": "1 mm"}, "axis 'rz' takes angle, not amplitude"),
    ({"axis": "x", "angle": "5 deg"}, "axis 'x' takes amplitude, not angle"),
    ({"axis": "x"}, "axis 'x' needs a amplitude above 0"),
    ({**SONIC, "frequency": "0 Hz"}, "frequency"),
    ({**SONIC, "frequency": "260 mm"}, "frequency"),
    ({**SONIC, "amplitude": "-1 mm"}, "amplitude"),
    ({**SONIC, "axis": "w"}, "axis"),
    ({**SONIC, "duration": "5 ms"}, "duration 0.005 s is shorter than the rise and fall"),
    ({**SONIC, "colour": "red"}, "colour: unknown key"),
])
def test_a_bad_sine_entry_is_refused_by_name(entry, message):
    with pytest.raises(ParameterError, match="motion.sine") as caught:
        build(Motion, {"sine": [entry]}, "motion.")
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_the_pivot_is_a_point():
    with pytest.raises(ParameterError, match="pivot needs 3 coordinates"):
        build(Motion, {"pivot": ["1 mm", "2 mm"]})


def test_no_pose_terms_leave_the_motion_as_it_was():
    case = load_case("orthogonal")
    head = HeadMotion(3.0, 1.0, 0.2, RestingSlide(1.0))
    assert with_pose(head, case.motion) is head


def test_a_resting_slide_holds_the_head_and_lasts_its_periods(tmp_path):
    prepared = prepare(load_case(_case_file(
        tmp_path, 'profile = "none"\nperiod = "0.1 s"\nperiods = 2\n')))
    motion = prepared.motion
    assert motion.end_time == pytest.approx(motion.slide_start + 0.2, rel=1e-15)
    assert motion.sliding(motion.slide_start + 0.05) == (0.0, 0.0, 0.0)


def test_a_turn_about_the_pivot_carries_the_handle_on_its_circle(tmp_path):
    # rz about a pivot 3 mm along x from the head's centre: the handle's node (the head
    # frame's origin) stays 3 mm from the pivot's axis, at the angle the term gives
    prepared = prepare(load_case(_case_file(tmp_path, (
        'profile = "none"\nperiod = "0.02 s"\nperiods = 1\npivot = ["3 mm", "0 mm", "0 mm"]\n'
        '[[motion.sine]]\naxis = "rz"\nangle = "30 deg"\nfrequency = "125 Hz"\n'
        'ramp_cycles = 0\n')), ["solver.step_size='0.2 ms'"]))
    motion, axis = prepared.motion, prepared.slide_axis
    for t in np.linspace(motion.slide_start, motion.end_time, 41):
        coordinates = handle_coordinates(motion, axis, t)
        descent = motion.descent(t)[0]
        angle = math.radians(30.0) * math.sin(2 * math.pi * 125.0 * (t - motion.slide_start))
        assert coordinates[5] == pytest.approx(angle, abs=1e-15)
        assert coordinates[2] == pytest.approx(-descent, abs=1e-12)  # in the plane
        arm = coordinates[:2] - [3.0, 0.0]
        # rounding only: sines and cosines of a 3 mm arm
        assert np.hypot(*arm) == pytest.approx(3.0, abs=1e-12)
        turned = [math.cos(math.pi + angle), math.sin(math.pi + angle)]
        np.testing.assert_allclose(arm / 3.0, turned, rtol=0, atol=1e-12)


def test_the_handles_velocity_and_acceleration_are_those_of_its_position(tmp_path):
    prepared = prepare(load_case(_case_file(tmp_path, (
        'amplitude = "2 mm"\nperiod = "0.05 s"\nperiods = 1\npivot = ["1 mm", "-2 mm", "4 mm"]\n'
        '[[motion.sine]]\naxis = "rx"\nangle = "10 deg"\nfrequency = "60 Hz"\n'
        '[[motion.sine]]\naxis = "y"\namplitude = "0.5 mm"\nfrequency = "90 Hz"\n'
        'start = "0.01 s"\n')), ["solver.step_size='0.2 ms'"]))
    motion, axis = prepared.motion, prepared.slide_axis
    h = 1e-6  # s: central differences, truncation ~ h² x (2π 90 Hz)³ x 0.5 mm, rounding ~ 1e-16 / h
    for t in motion.slide_start + np.array([0.004, 0.013, 0.027, 0.041]):
        before, now, after = (handle_kinematics(motion, axis, t + d)[0] for d in (-h, 0, h))
        _, velocity, acceleration = handle_kinematics(motion, axis, t)
        np.testing.assert_allclose((after - before) / (2 * h), velocity, rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose((after - 2 * now + before) / h**2, acceleration,
                                   rtol=1e-3, atol=5.0)  # mm/s² of ~1e5: rounding / h²


def test_a_vibration_is_stepped_finely_while_it_acts_and_counted_in_the_budget(tmp_path):
    case = load_case(_case_file(tmp_path, '[[motion.sine]]\naxis = "y"\namplitude = "0.3 mm"\n'
                                          'frequency = "260 Hz"\nduration = "0.5 s"\n'))
    prepared = prepare(case)  # the 2 ms step stays: the vibration caps it while it acts
    plain = math.ceil(prepared.motion.end_time / case.solver.step_size)
    per_cycle = case.solver.steps_per_cycle
    fine = 1 / (260 * per_cycle)
    # from 6 steps of 2 ms before the term to its end, per_cycle steps a cycle instead of
    # 2 ms ones
    assert prepared.work.steps - plain == math.ceil((0.5 + 0.012) / fine) - math.floor(
        (0.5 + 0.012) / 2e-3)
    with pytest.raises(ParameterError) as caught:
        prepare(case.replace(solver=case.solver.replace(minimum_step_size=1e-3)))
    assert (f"motion.sine[0] (260 Hz) needs steps of at most {fine * 1e3:.4g} ms ({per_cycle} "
            "per cycle), below solver.minimum_step_size 1 ms") in str(caught.value)


def test_a_pose_csv_is_read_relative_to_the_case_file_and_checked(tmp_path):
    (tmp_path / "pose.csv").write_text("time [ms],rz [deg]\n0,0\n10,5\n20,0\n")
    prepared = prepare(load_case(_case_file(tmp_path, 'pose_csv = "pose.csv"\n'),
                                 ["solver.step_size='0.2 ms'"]))
    assert dict(prepared.inputs)["motion.pose_csv"] == prepared.motion.pose.table.digest
    (tmp_path / "bad.csv").write_text("time [s],colour [mm]\n0,0\n1,1\n")
    with pytest.raises(ParameterError, match="motion.pose_csv: pose CSV .*bad.csv.* has none"):
        prepare(load_case(_case_file(tmp_path, 'pose_csv = "bad.csv"\n')))


def test_a_posed_run_stopped_before_its_first_sample_has_no_angles(tmp_path):
    # an interrupted run with no sample yet assembles empty results, not a traceback
    prepared = prepare(load_case(_case_file(tmp_path, (
        '[[motion.sine]]\naxis = "rz"\nangle = "5 deg"\nfrequency = "50 Hz"\n'))))
    angles, rates, turning = handle_angles(prepared.motion, np.zeros(0))
    assert angles.shape == rates.shape == turning.shape == (0, 3)


def test_a_posed_run_interrupted_before_any_sample_saves_its_record_only(tmp_path):
    from exubrush.output.assemble import RunFacts, assemble_results

    prepared = prepare(load_case(_case_file(tmp_path, (
        '[[motion.sine]]\naxis = "rz"\nangle = "5 deg"\nfrequency = "50 Hz"\n'))))
    results = assemble_results(prepared, [None] * len(prepared.groups),
                               RunFacts(interrupted=True, wall_time=1.0, workers=1))
    assert results.metadata["status"] == "interrupted" and results.wrench is None
    results.save(tmp_path / "out")
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["run.json"]


@pytest.mark.parametrize("frequency, hertz", [
    ("7600 rpm", 7600.0 / 60.0),  # an oscillating brush's strokes per minute
    ("7600 1/min", 7600.0 / 60.0),
    ("100 rad/s", 100.0 / (2.0 * math.pi)),  # an angular frequency ω: f = ω / 2π
])
def test_a_frequency_per_minute_or_angular_is_read_as_its_cycles(frequency, hertz):
    motion = build(Motion, {"sine": [{**SONIC, "frequency": frequency}]})
    assert motion.sine[0].frequency == pytest.approx(hertz, rel=4e-16)  # one conversion


@pytest.mark.parametrize("key, value", [("phase", "90"), ("phase", 90), ("angle", "0.5"),
                                        ("angle", 0.5), ("phase", "1 1"), ("phase", "50 %"),
                                        ("angle", "2*0.1")])
def test_an_angle_without_an_angle_unit_is_refused_in_every_form(key, value):
    entry = {"axis": "rz", "angle": "5 deg", "frequency": "50 Hz", key: value}
    with pytest.raises(ParameterError, match=f"motion.sine\\[0\\].{key}: .*has no unit") as err:
        build(Motion, {"sine": [entry]}, "motion.")
    assert "\n" not in str(err.value)


def test_a_pose_table_that_starts_after_the_run_is_refused_as_a_late_sine_is(tmp_path):
    (tmp_path / "pose.csv").write_text("time [ms],x [mm]\n0,0\n10,0.5\n20,0\n")
    lines = ('profile = "none"\nperiod = "0.1 s"\nperiods = 1\npose_csv = "pose.csv"\n'
             'pose_csv_start = "{}"\n')
    case = _case_file(tmp_path, lines.format("0.1 s"))
    with pytest.raises(ParameterError) as caught:
        prepare(load_case(case, ["solver.step_size='0.1 ms'"]))
    assert str(caught.value) == ("motion.pose_csv starts 100 ms after the slide, at or after "
                                 "the run's end (1.3 s): it would never act; start it earlier "
                                 "or run longer")
    late_sine = _case_file(tmp_path, 'profile = "none"\nperiod = "0.1 s"\nperiods = 1\n'
                           '[[motion.sine]]\naxis = "x"\namplitude = "1 mm"\n'
                           'frequency = "50 Hz"\nstart = "0.1 s"\n', name="late")
    with pytest.raises(ParameterError, match="motion.sine.0. starts 100 ms after the slide, "
                                             "at or after the run's end .1.3 s.: it would"):
        prepare(load_case(late_sine, ["solver.step_size='0.1 ms'"]))
    # just before the end it acts, and is taken
    prepare(load_case(_case_file(tmp_path, lines.format("99 ms"), name="in_time"),
                      ["solver.step_size='0.1 ms'"]))


def _many_sines(tmp_path, count: int) -> str:
    """A case file of one bristle with ``count`` small, slow sine terms (1-7 Hz)."""
    terms = "".join(f'[[motion.sine]]\naxis = "{"xyz"[i % 3]}"\namplitude = "1e-6 mm"\n'
                    f'frequency = "{1 + i % 7} Hz"\n' for i in range(count))
    return _case_file(tmp_path, "periods = 0.02\n" + terms, name=f"sines{count}")


def test_many_sine_terms_are_refused_by_their_evaluations_before_any(tmp_path, monkeypatch):
    # 20,000 terms over 877 steps (the steps of the 2,000-term run, measured: 880)
    def never(*args):
        raise AssertionError("a term was evaluated before the work was bounded")

    monkeypatch.setattr(SineTerm, "evaluate", never)
    case = load_case(_many_sines(tmp_path, 20_000))
    with pytest.raises(ParameterError) as caught:
        prepare(case)
    assert str(caught.value) == (
        "the run's 20,000 pose terms would be evaluated 17,540,000 times per system (at each "
        "of at least 877 steps), more than limits.term_evaluations = 10,000,000; a pose table "
        "(motion.pose_csv) holds any motion as one term, or --set "
        "limits.term_evaluations=17540000")
    # 877 steps: 1.44 s at 2 ms (720) and, while the 4-7 Hz terms act, their cycle over 160
    # (7 Hz: 0.89 ms) from 6 steps ahead of the slide's start to the end
    fine, ahead = 1 / (7 * 160), 6 * 2e-3
    span = 0.24 + ahead
    assert 720 + math.ceil(span / fine) - math.floor(span / 2e-3) == 877
    raised = case.replace(limits=case.limits.replace(term_evaluations=17_540_000.0))
    monkeypatch.undo()  # within the limit the pose's clearance check evaluates the terms
    assert prepare(raised).work.term_evaluations == 17_540_000


def test_overlapping_terms_are_stepped_at_the_finest_of_them():
    # three windows (from, to, step) as term_windows gives them, overlapping: the step
    # cap and the estimate take the finest step where they overlap, each instant once
    motion = build(Motion, {"sine": [
        {"axis": "x", "amplitude": "1 mm", "frequency": "10 Hz", "duration": "0.3 s",
         "ramp_cycles": 0},
        {"axis": "y", "amplitude": "1 mm", "frequency": "40 Hz", "start": "0.1 s",
         "duration": "0.1 s"},
        {"axis": "z", "amplitude": "1 mm", "frequency": "20 Hz", "start": "0.15 s"},
    ]})
    case = Case().replace(motion=motion)
    ahead = 6 * 2e-3  # the look-ahead: step_recovery_steps + 2 steps of 2 ms
    segments = term_segments(case, 1.0, 2.0)
    expected = [(1.0 - ahead, 1.1 - ahead, 1 / 1600), (1.1 - ahead, 1.2, 1 / 6400),
                (1.2, 2.0, 1 / 3200)]
    assert [s[2] for s in segments] == [e[2] for e in expected]
    np.testing.assert_allclose([s[:2] for s in segments], [e[:2] for e in expected],
                               rtol=0, atol=1e-15)  # sums of a few seconds
    # steps added: 0.1 s at 1600/s, 0.112 s at 6400/s and 0.8 s at 3200/s instead of 2 ms
    # steps (160 - 50 + 717 - 56 + 2560 - 400); each window apiece would add 3,333. Each
    # segment's ceil and floor may move by one with the rounding of its ends
    assert abs(term_steps(case, 2.0, 1.0) - 2931) <= 3
    finer = term_step_cap(case, HeadMotion(1.0, 1.0, 0.0, RestingSlide(1.0)))
    for t, cap in ((0.5, None), (1.05, 1 / 1600), (1.15, 1 / 6400), (1.2, 1 / 6400),
                   (1.5, 1 / 3200), (2.5, None)):
        assert finer(t) == cap, t


@settings(max_examples=60, deadline=None)
@given(terms=st.lists(st.tuples(st.sampled_from([3.0, 10.0, 40.0, 130.0]),
                                st.integers(0, 500).map(lambda ms: ms / 1000),
                                st.sampled_from([0.0, 0.05, 0.3])),
                      min_size=1, max_size=8))
def test_the_merged_windows_give_each_instant_the_finest_step_of_its_terms(terms):
    motion = build(Motion, {"sine": [
        {"axis": "x", "amplitude": "1 mm", "frequency": f"{f!r} Hz", "start": f"{s!r} s",
         "duration": f"{d!r} s", "ramp_cycles": 0} for f, s, d in terms]})
    case = Case().replace(motion=motion)
    windows = term_windows(case, 1.0, 1.6)
    segments = term_segments(case, 1.0, 1.6)
    for t in np.linspace(0.9, 1.7, 401):
        caps = [cap for start, end, cap in windows if start <= t <= end]
        inside = [cap for start, end, cap in segments if start <= t <= end]
        assert min(inside, default=None) == min(caps, default=None)
