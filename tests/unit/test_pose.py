"""The head's six-degree-of-freedom pose: Exudyn's Rxyz rotation and its G matrix, sine and
table terms, their sum and the motion of points fixed to the head."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exubrush.world.pose import (
    AXES,
    HeadPose,
    SineTerm,
    TableTerm,
    angular_acceleration,
    angular_velocity,
    read_pose_csv,
    rotation_matrix,
)

angles = st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3).map(np.array)
rates = st.lists(st.floats(-3.0, 3.0), min_size=3, max_size=3).map(np.array)


def _skew_vector(matrix):
    """The vector w of a skew matrix w̃ (its antisymmetric part, to be safe)."""
    m = 0.5 * (matrix - matrix.T)
    return np.array([m[2, 1], m[0, 2], m[1, 0]])


def test_rotation_and_g_are_exudyns_rotxyz():
    from exudyn.rigidBodyUtilities import RotXYZ2G, RotXYZ2RotationMatrix

    rng = np.random.default_rng(1)
    for theta, theta_dot in zip(rng.uniform(-4, 4, (20, 3)), rng.uniform(-3, 3, (20, 3)),
                                strict=True):
        # the same products of sines and cosines: equal to round-off (a few ulp of 1)
        np.testing.assert_allclose(rotation_matrix(theta), RotXYZ2RotationMatrix(theta),
                                   rtol=0, atol=1e-15)
        np.testing.assert_allclose(angular_velocity(theta, theta_dot),
                                   RotXYZ2G(theta) @ theta_dot, rtol=0, atol=1e-14)


@settings(max_examples=60, deadline=None)
@given(theta=angles, theta_dot=rates, theta_ddot=rates)
def test_angular_velocity_and_acceleration_are_those_of_the_rotation_matrix(
        theta, theta_dot, theta_ddot):
    h = 1e-5

    def at(t):  # the angles along a parabola through θ with rate θ̇ and acceleration θ̈
        return theta + theta_dot * t + 0.5 * theta_ddot * t * t

    a_dot = (rotation_matrix(at(h)) - rotation_matrix(at(-h))) / (2 * h)
    omega_fd = _skew_vector(a_dot @ rotation_matrix(theta).T)
    velocity_at = [angular_velocity(at(t), theta_dot + theta_ddot * t) for t in (h, -h)]
    alpha_fd = (velocity_at[0] - velocity_at[1]) / (2 * h)
    # central differences: truncation h²/6 max|third derivative| <= 1e-10/6 (|θ̇| + |θ̈|)³
    # ≈ 2e-8 with rates and accelerations up to 3 per component (|θ̇|, |θ̈| <= 5.2);
    # round-off eps/h ~ 2e-11
    np.testing.assert_allclose(angular_velocity(theta, theta_dot), omega_fd, rtol=0, atol=1e-7)
    np.testing.assert_allclose(angular_acceleration(theta, theta_dot, theta_ddot), alpha_fd,
                               rtol=0, atol=1e-7)


def test_a_rotation_about_the_pivot_keeps_every_point_on_its_circle():
    pivot = np.array([1.0, -2.0, 3.0])
    term = SineTerm("rz", 0.6, 1.5, phase=0.3)
    head = HeadPose([term], pivot)
    points0 = np.random.default_rng(2).uniform(-10, 10, (8, 3))
    arm0 = points0 - pivot
    for t in (0.0, 0.11, 0.4, 0.93):
        rz = term.evaluate(t)[0][5]
        x = head.point_motion(points0, t)[0]
        arm = x - pivot
        # rotations and a complex angle: round-off of a few ulp of the 10 mm lengths
        np.testing.assert_allclose(np.hypot(arm[:, 0], arm[:, 1]),
                                   np.hypot(arm0[:, 0], arm0[:, 1]), rtol=0, atol=1e-12)
        np.testing.assert_allclose(arm[:, 2], arm0[:, 2], rtol=0, atol=1e-12)
        turned = np.angle((arm[:, 0] + 1j * arm[:, 1]) / (arm0[:, 0] + 1j * arm0[:, 1]))
        np.testing.assert_allclose(turned, rz, rtol=0, atol=1e-12)


def test_point_velocities_and_accelerations_are_those_of_their_positions():
    terms = [SineTerm(axis, amplitude, frequency, phase=0.4 * k, start=0.05 * k, ramp=0.1)
             for k, (axis, amplitude, frequency) in enumerate(
                 [("x", 2.0, 1.0), ("y", 1.0, 1.7), ("z", 0.5, 2.3),
                  ("rx", 0.3, 1.1), ("ry", 0.4, 0.7), ("rz", 0.5, 1.9)])]
    head = HeadPose(terms, pivot=[0.5, 1.0, -4.0])
    points0 = np.random.default_rng(3).uniform(-10, 10, (6, 3))
    h = 3e-5
    for t in (0.37, 0.81, 1.6):  # past every ramp: smooth sines only
        x, v, a = head.point_motion(points0, t)
        before, after = head.point_motion(points0, t - h)[0], head.point_motion(points0, t + h)[0]
        # truncation: velocity h²/6 |x'''|, acceleration h²/12 |x''''|. The head turns at
        # |ω| <= Σ a 2π f = 9.8 rad/s on arms below 15 mm: |x'''| ~ 9.8³ 15 ≈ 1.4e4 mm/s³,
        # |x''''| ~ 9.8⁴ 15 + (the translations' a ω⁴ ≈ 4e4) ≈ 2e5 mm/s⁴, so 2e-6 mm/s and
        # 1.5e-5 mm/s²; round-off of the second difference 4 eps 12 mm / h² ≈ 1.2e-5 mm/s²
        np.testing.assert_allclose(v, (after - before) / (2 * h), rtol=0, atol=1e-5)
        np.testing.assert_allclose(a, (after - 2 * x + before) / h**2, rtol=0, atol=1e-4)


def _fd_rate(term, t, k, h):
    return [(term.evaluate(t + h)[m][k] - term.evaluate(t - h)[m][k]) / (2 * h) for m in (0, 1)]


def test_a_ramped_sine_is_smooth_at_its_four_corners_and_zero_outside():
    term = SineTerm("y", 2.0, 3.0, phase=0.7, start=0.5, end=2.5, ramp=0.3)
    k = AXES.index("y")
    delta, h = 1e-9, 1e-5
    # sizes on this term (a = 2 mm, ω = 18.85 rad/s, e' <= 15/8 / ramp = 6.25 /s,
    # e'' <= 5.77 / ramp² = 64 /s², e''' <= 60 / ramp³ = 2.2e3 /s³): rate below 50 mm/s,
    # acceleration below 1e3 mm/s², jerk below a ω³ + 3 e' a ω² + 3 e'' a ω + e''' a ≈ 4e4
    for corner in (0.5, 0.8, 2.2, 2.5):
        below, above = term.evaluate(corner - delta), term.evaluate(corner + delta)
        # continuous: across 2δ each changes by at most 2δ times the next one's size,
        # 2δ 4e4 = 8e-5 at most
        for m in range(3):
            assert above[m][k] == pytest.approx(below[m][k], abs=1e-4)
    # the corners, and a quarter and three quarters into each ramp (s'' is 0 at its middle)
    for t in (0.5, 0.575, 0.725, 0.8, 2.2, 2.275, 2.425, 2.5):
        # rate and acceleration are derivatives: the central difference of the value errs
        # by h²/6 |jerk| < 7e-7 mm/s; that of the rate by h²/6 |f''''| < 1e-3 where smooth,
        # and at a corner, where the jerk jumps by up to e''' a = 4.4e3 mm/s³, by
        # h · jump / 4 = 1.1e-2 mm/s²
        rate_fd, acceleration_fd = _fd_rate(term, t, k, h)
        value, rate, acceleration = (q[k] for q in term.evaluate(t))
        assert rate == pytest.approx(rate_fd, abs=1e-6)
        assert acceleration == pytest.approx(acceleration_fd, abs=2e-2)
    for t in (0.0, 0.5, 2.5, 3.0):  # outside, and at the ends where the envelope is 0
        for q in term.evaluate(t):
            np.testing.assert_array_equal(q, np.zeros(6))
    # without a ramp the sine starts at its peak rate: the rate jumps at the start
    jump = SineTerm("y", 2.0, 3.0, start=0.5)
    assert jump.evaluate(0.5)[1][k] == pytest.approx(2.0 * 2 * math.pi * 3.0, rel=1e-15)
    assert jump.evaluate(0.5 - delta)[1][k] == 0.0


def test_the_peak_rate_bounds_the_rate():
    t = np.linspace(0.0, 2.0, 4001)
    plain, ramped = SineTerm("rx", 0.3, 2.0), SineTerm("rx", 0.3, 2.0, end=1.5, ramp=0.2)
    k = AXES.index("rx")
    plain_rates = np.abs([plain.evaluate(s)[1][k] for s in t])
    ramped_rates = np.abs([ramped.evaluate(s)[1][k] for s in t])
    # sampled every 0.5 ms: the peak 0.3 · 4π is missed by at most ω² a δ² / 2 ~ 1e-5
    assert plain_rates.max() == pytest.approx(plain.peak_rate[k], abs=1e-5)
    assert ramped_rates.max() <= ramped.peak_rate[k]
    assert np.count_nonzero(plain.peak_rate) == 1


@pytest.mark.parametrize("bad, field", [
    ({"axis": "w"}, "axis"),
    ({"amplitude": -1.0}, "amplitude"),
    ({"amplitude": math.nan}, "amplitude"),
    ({"frequency": 0.0}, "frequency"),
    ({"frequency": -2.0}, "frequency"),
    ({"frequency": math.inf}, "frequency"),
    ({"phase": math.nan}, "phase"),
    ({"start": math.inf}, "start"),
    ({"end": math.nan}, "end"),
    ({"end": -math.inf}, "end"),
    ({"end": 0.0}, "end"),
    ({"ramp": -0.1}, "ramp"),
    ({"ramp": math.inf}, "ramp"),
    ({"end": 1.0, "ramp": 0.6}, "ramp"),
])
def test_a_sine_term_refuses_each_bad_field_by_name(bad, field):
    fields = {"axis": "x", "amplitude": 1.0, "frequency": 1.0, **bad}
    with pytest.raises(ValueError, match=rf"^SineTerm\.{field} ") as caught:
        SineTerm(**fields)
    assert "\n" not in str(caught.value)


def test_a_table_term_reproduces_its_samples_from_its_start_and_holds_after_its_end():
    times = np.array([1.0, 2.0, 3.0, 4.0])
    x, rz = np.array([1.0, 3.0, 2.0, 5.0]), np.array([0.0, 0.1, 0.3, 0.2])
    term = TableTerm(times, {"x": x, "rz": rz}, start=2.0)
    assert term.end_time == 5.0
    for time, xi, rzi in zip(times, x, rz, strict=True):
        pose = term.evaluate(2.0 + time - 1.0)[0]
        # an interpolant at its knots: round-off only
        assert pose[0] == pytest.approx(xi - 1.0, abs=1e-14)
        assert pose[5] == pytest.approx(rzi, abs=1e-15)
    for q in term.evaluate(1.9):  # before its start: at rest at its origin
        np.testing.assert_array_equal(q, np.zeros(6))
    pose, rate, acceleration = term.evaluate(7.0)
    np.testing.assert_allclose(pose, [4.0, 0, 0, 0, 0, 0.2], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(rate, np.zeros(6))
    np.testing.assert_array_equal(acceleration, np.zeros(6))
    assert term.peak_rate[1:5].tolist() == [0.0] * 4 and term.peak_rate[0] > 0


def test_a_table_term_never_leaves_the_range_of_a_step():
    times = np.arange(6.0)
    term = TableTerm(times, {"z": np.array([0.0, 0.0, 0.0, 10.0, 10.0, 10.0])})
    z = np.array([term.evaluate(t)[0][2] for t in np.linspace(-1.0, 7.0, 1601)])
    assert z.min() >= 0.0 and z.max() <= 10.0
    assert np.all(np.diff(z) >= 0.0)


def test_a_pose_csv_converts_units(tmp_path):
    path = tmp_path / "pose.csv"
    path.write_text("# measured\ntime [ms],x [m],rz [rad],ry [deg],force [N]\n"
                    "0,0,0,0,1\n500,0.001,0.5,90,2\n1000,0.002,1.0,180,3\n")
    term = read_pose_csv(path, start=0.25)
    assert term.end_time == pytest.approx(1.25, rel=1e-15)
    pose = term.evaluate(1.25)[0]
    # ms, m and deg converted by one factor each: a few ulp
    np.testing.assert_allclose(pose, [2.0, 0.0, 0.0, 0.0, math.pi, 1.0], rtol=1e-15, atol=0)


@pytest.mark.parametrize("text, message", [
    ("time [s],force [N]\n0,1\n1,2\n",
     "none of the pose columns 'x [mm]', 'y [mm]', 'z [mm]', 'rx [deg]', 'ry [deg]', "
     "'rz [deg]'"),
    ("time [s],x\n0,1\n1,2\n", "column 'x' has no unit"),
    ("time [s],y [mm]\n0,1\n1,nan\n", "finite numbers only"),
    ("time [s],y [mm]\n0,1\ninf,2\n", "finite numbers only"),
    ("time [s],y [mm]\n0,1\n1,two\n", "'two' is not a number"),
    ("time [s],ry [N]\n0,1\n1,2\n", "column 'ry'"),
    ("time [s],y [mm]\n0,1\n0,2\n", "times must increase strictly"),
    ("time [s],rz [1]\n0,0\n1,0.5\n", "column 'rz [1]' has no unit of 'rad'"),
    ("time [s],rz [%]\n0,0\n1,0.5\n", "column 'rz [%]' has no unit of 'rad'"),
    ("time [s],rx []\n0,0\n1,0.5\n", "column 'rx' has no unit"),
    ("time [s],x [mm],y [mm],x [cm]\n0,0,0,0\n1,1,1,0.1\n",
     "has 2 columns for 'x' ('x [mm]', 'x [cm]'); keep one"),
    ("time [s],time [ms],x [mm]\n0,0,0\n1,1000,1\n", "has 2 columns for 'time'"),
    ("time [s],x [mm],Y [mm]\n0,0,0\n1,1,1\n",
     "column 'Y' is not 'y' (labels are case sensitive); write 'y [mm]'"),
    # a decimal comma: the row's cells after it would shift (x read as 1 mm, not 1.5)
    ("time [s],x [mm]\n0,0\n1,1,5\n", "line 3 has 3 cells for 2 columns (a decimal comma?"),
    # no such table at all (a file of other text): told by its missing column, not by the
    # cells of a line
    ("root:x:0:0\nbin,x,1,1\nsync,x,2,2\n", "has no column 'time [unit]'"),
    # a brush head moves within 10 m and at 100 m/s at most (slide.TABLE_REACH, TABLE_RATE)
    ("time [s],x [mm]\n0,0\n1,1e300\n2,0\n",
     "'x' is 1e+300 mm from its first row at sample 2 (t = 1 s), beyond the 10000 mm"),
    ("time [s],z [mm]\n0,-1e308\n1,1e308\n", "'z' is inf mm from its first row at sample 2"),
    ("time [s],ry [deg]\n0,0\n1,1e300\n", "'ry' is 1.75e+298 rad from its first row"),
    # 1 mm in a nanosecond (the monotone cubic's end slope is 4/3 of it here)
    ("time [s],y [mm]\n0,0\n1e-9,1\n1,1\n", "e+09 mm/s, faster than the 100000 mm/s"),
    ("time [s],rz [deg]\n0,0\n1e-9,10\n1,10\n", "e+08 rad/s, faster than the 100000 rad/s"),
])
def test_a_bad_pose_csv_is_refused_naming_the_file(tmp_path, text, message):
    path = tmp_path / "pose.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=f"pose CSV '{path}'") as caught:
        read_pose_csv(path)
    assert message in str(caught.value)


def test_terms_add():
    first, second = SineTerm("x", 1.0, 2.0), SineTerm("x", 0.5, 3.0, phase=1.0, start=0.1)
    head = HeadPose([first, second], pivot=[0.0, 0.0, 0.0])
    for t in (0.05, 0.3, 1.2):
        for total, a, b in zip(head.evaluate(t), first.evaluate(t), second.evaluate(t),
                               strict=True):
            np.testing.assert_array_equal(total, a + b)
    np.testing.assert_array_equal(head.peak_rate, first.peak_rate + second.peak_rate)
    assert head.end_time == math.inf


def test_a_head_without_terms_rests():
    head = HeadPose([], pivot=[1.0, 2.0, 3.0])
    points0 = np.array([[0.0, 0.0, 0.0], [4.0, -1.0, 2.5]])
    x, v, a = head.point_motion(points0, 0.7)
    np.testing.assert_array_equal(x, points0)
    np.testing.assert_array_equal(v, np.zeros((2, 3)))
    np.testing.assert_array_equal(a, np.zeros((2, 3)))
    assert head.end_time == 0.0
    np.testing.assert_array_equal(head.peak_rate, np.zeros(6))


def test_a_pose_csv_with_a_byte_order_mark_is_read(tmp_path):
    # spreadsheet programs start a UTF-8 CSV with the mark U+FEFF, which is no text
    path = tmp_path / "pose.csv"
    path.write_bytes("\ufefftime [s],x [mm]\n0,0\n1,2\n".encode())
    assert read_pose_csv(path).evaluate(1.0)[0][0] == 2.0


def test_a_pose_table_at_its_bounds_is_taken():
    # 10 m from the first row, and 100 m/s (two rows: a straight line): the bounds
    # themselves are motions
    far = TableTerm(np.array([0.0, 2.0]), {"x": np.array([0.0, 1e4])})
    assert far.evaluate(2.0)[0][0] == 1e4
    fast = TableTerm(np.array([0.0, 0.0625]), {"y": np.array([0.0, 6250.0])})
    assert fast.peak_rate[1] == 1e5  # exact: 6250 / 0.0625, both binary fractions
