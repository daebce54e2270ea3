"""Poses that drive the head through the surface or into the Tait-Bryan singularity are
refused before solving (issue 48, section 2; exubrush.world.clearance)."""

import math
import re

import numpy as np
import pytest

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.world.clearance import (
    COARSE_SAMPLES,
    REACH_MARGIN,
    ROOT_MARGIN,
    RY_MARGIN,
    largest_acceleration,
    lowest_below,
    outermost,
)
from exubrush.world.motion import HeadMotion
from exubrush.world.pose import AXES, HeadPose, SineTerm, rotation_matrix
from exubrush.world.slide import RestingSlide

SINE = """
name = "posed"
[head]
rows = 1
columns = 1
[surface]
kind = "{surface}"
[motion]
profile = "none"
pivot = ["0 mm", "0 mm", "{pivot_z}"]
[[motion.sine]]
axis = "{axis}"
angle = "{angle}"
frequency = "2 Hz"
ramp_cycles = 0
"""


def _prepare(tmp_path, text, *overrides):
    path = tmp_path / "case.toml"
    path.write_text(text)
    # the slide's time: 0.02 x 12 s = 0.24 s, past the sine's first peak at 0.125 s
    return prepare(load_case(str(path), ["motion.periods=0.02", *overrides]))


def _refusal(tmp_path, text, *overrides):
    with pytest.raises(ParameterError) as refused:
        _prepare(tmp_path, text, *overrides)
    return str(refused.value)


def _depth(message):
    return float(re.search(r"roots (\S+) mm through", message).group(1))


def test_a_narrow_dip_between_the_first_samples_is_found():
    # a V-shaped dip to -0.3 at t = 0.5037, falling at 100 per s: the coarse samples
    # nearest to it (0.5 and 0.515625) are above 0, so only the refinement finds it
    rate, centre = 100.0, 0.5037
    def f(t):
        return min(1.0, rate * abs(t - centre) - 0.3)
    assert min(f(k / (COARSE_SAMPLES - 1)) for k in range(COARSE_SAMPLES)) > 0.0
    when, value = lowest_below(f, 0.0, 1.0, rate, margin=0.01)
    assert value == pytest.approx(-0.3, abs=0.01)  # within the margin of the true least
    assert when == pytest.approx(centre, abs=0.01 / rate)


def test_a_function_that_stays_above_zero_is_passed():
    # its least, 0.002 at t = 0.3, is closer to 0 than the margin: still not refused
    assert lowest_below(lambda t: 0.002 + 50.0 * abs(t - 0.3), 0.0, 1.0, 50.0, 0.01) is None


def test_a_turn_about_a_pivot_below_is_refused_with_its_depth(tmp_path):
    message = _refusal(tmp_path, SINE.format(surface="plane", pivot_z="-30 mm", axis="rx",
                                             angle="60 deg"))
    # the root turns on a 30 mm arm about a pivot 30 - 4.2 mm under the plane: at 60° it
    # stands 30 cos 60° above the pivot, 30 - 15 - 4.2 = 10.8 mm under the plane
    assert _depth(message) == pytest.approx(10.8, abs=ROOT_MARGIN)
    # the sine's peak: slide start (1 s approach + 0.2 s hold) + a quarter of 0.5 s
    assert float(re.search(r"at t = (\S+) s", message).group(1)) == pytest.approx(1.325,
                                                                                   abs=1e-3)


def test_a_pose_table_lowering_the_head_is_refused_with_its_depth(tmp_path):
    (tmp_path / "down.csv").write_text("time [s],z [mm]\n0,0\n0.1,-8\n0.2,-8\n")
    text = ('name = "down"\n[head]\nrows = 1\ncolumns = 1\n[motion]\nprofile = "none"\n'
            'pose_csv = "down.csv"\n')
    # the roots stand d = 4.2 mm above the plane; 8 mm lower they are 3.8 mm under it
    assert _depth(_refusal(tmp_path, text)) == pytest.approx(3.8, abs=ROOT_MARGIN)


def test_a_head_lowered_onto_a_sphere_is_refused(tmp_path):
    (tmp_path / "down.csv").write_text("time [s],z [mm]\n0,0\n0.2,-6\n")
    text = ('name = "down"\n[head]\nrows = 1\ncolumns = 1\n[surface]\nkind = "sphere"\n'
            '[motion]\nprofile = "none"\npose_csv = "down.csv"\n')
    message = _refusal(tmp_path, text)
    # the root over the sphere's top: 6 - 4.2 mm into it
    assert "through the sphere" in message
    assert _depth(message) == pytest.approx(1.8, abs=ROOT_MARGIN)


def test_a_turn_that_keeps_the_roots_above_is_run(tmp_path):
    # the same turn about a pivot at the roots: the root stays on the pivot, 4.2 mm up
    prepared = _prepare(tmp_path, SINE.format(surface="plane", pivot_z="0 mm", axis="rx",
                                              angle="60 deg"))
    assert prepared.motion.pose is not None


@pytest.mark.parametrize("angle, refused", [("75 deg", False), ("85 deg", True),
                                            ("90 deg", True)])
def test_ry_near_the_singularity_is_refused(tmp_path, angle, refused):
    text = SINE.format(surface="plane", pivot_z="0 mm", axis="ry", angle=angle)
    if not refused:
        assert _prepare(tmp_path, text).motion.pose is not None
        return
    message = _refusal(tmp_path, text)
    reached = float(re.search(r"ry reaches (\S+)° at", message).group(1))
    assert reached == pytest.approx(float(angle.split()[0]), abs=math.degrees(RY_MARGIN))
    assert "keep |ry| below 80°" in message


def test_a_bristle_brought_within_reach_by_the_pose_gets_contact(tmp_path):
    # the default bristle reaches l + r = 5 + 0.4 mm below its root: not from d = 6 mm,
    # but the table lowers the head by 1 mm, to 5 mm
    (tmp_path / "down.csv").write_text("time [s],z [mm]\n0,0\n0.2,-1\n")
    text = ('name = "down"\n[head]\nrows = 1\ncolumns = 1\n[motion]\nprofile = "none"\n'
            'interaction_distance = "6 mm"\npose_csv = "down.csv"\n')
    prepared = _prepare(tmp_path, text)
    assert prepared.reaching == (True,)
    # E A δ / l with E = 7.5 MPa, A = 0.6 x 0.9 mm², δ = 5.4 - 5 mm at most 2 REACH_MARGIN
    # more (the closest approach is taken REACH_MARGIN below a sample within REACH_MARGIN
    # of the true one)
    exact = 7.5 * 0.54 * 0.4 / 5.0
    assert exact <= prepared.force_limits[0] <= exact + 7.5 * 0.54 * 2 * REACH_MARGIN / 5.0
    assert not any("cannot reach" in w for w in prepared.warnings)


@pytest.mark.parametrize("seed", range(20))
def test_lowest_below_against_dense_sampling(seed):
    # f = c + Σ a sin(ω t + φ): it changes at most Σ a ω per second. A dense grid of 2e5
    # samples on [0, 1] misses its least by at most rate / 4e5 (< 0.004 here)
    rng = np.random.default_rng(seed)
    a, omega, phi = rng.uniform(0.1, 1.0, 4), rng.uniform(1.0, 300.0, 4), rng.uniform(0, 7, 4)
    c = rng.uniform(-0.5, 1.0) * a.sum() + a.sum() * 0.5
    rate, margin = float(a @ omega), 0.01
    def f(t):
        return c + float(a @ np.sin(omega * t + phi))
    dense = np.linspace(0.0, 1.0, 200_001)
    values = c + np.sin(np.outer(dense, omega) + phi) @ a
    true_least = values.min() - rate / 4e5  # at or below f's least
    found = lowest_below(f, 0.0, 1.0, rate, margin)
    if values.min() < -margin:
        assert found is not None
    if found is not None:
        assert found[1] < 0.0
        assert f(found[0]) == found[1]
        assert found[1] - margin <= values.min() + 1e-12
        assert found[1] >= true_least - 1e-12
    else:
        assert values.min() >= -margin


def test_the_lowest_root_is_a_hull_vertex():
    rng = np.random.default_rng(1)
    points = np.column_stack([rng.uniform(-10, 10, (300, 2)), np.zeros(300)])
    for angles in rng.uniform(-1.5, 1.5, (50, 3)):
        turned = points @ rotation_matrix(angles).T
        hull = outermost(points) @ rotation_matrix(angles).T
        assert hull[:, 2].min() == turned[:, 2].min()
    assert len(outermost(points)) < len(points)


@pytest.mark.parametrize("seed", range(10))
def test_the_acceleration_bound_holds_along_random_poses(seed):
    # sine terms on random axes, amplitudes, frequencies, phases and ramps: no sampled
    # acceleration of the head's points beats the bound, and no term's beats its own
    rng = np.random.default_rng(seed)
    terms = []
    for axis in rng.choice(AXES, 3):
        size = rng.uniform(0.1, 2.0) if axis in "xyz" else rng.uniform(0.05, 0.5)
        frequency = rng.uniform(1.0, 50.0)
        terms.append(SineTerm(axis, size, frequency, rng.uniform(0, 7), rng.uniform(0, 0.2),
                              ramp=rng.choice([0.0, rng.uniform(0.5, 2.0) / frequency])))
    pose = HeadPose(terms, rng.uniform(-5, 5, 3))
    motion = HeadMotion(1.0, 0.1, 0.0, RestingSlide(1.0), pose)
    points = rng.uniform(-6, 6, (5, 3))
    bound = largest_acceleration(motion, points)
    everywhere = np.vstack([np.zeros((1, 3)), points])
    for t in np.linspace(0.0, motion.end_time, 3001):
        sampled = np.linalg.norm(pose.point_motion(everywhere, t)[2], axis=1).max()
        assert sampled <= bound
        for term in terms:
            assert np.all(np.abs(term.evaluate(t)[2]) <= term.peak_acceleration + 1e-9)
