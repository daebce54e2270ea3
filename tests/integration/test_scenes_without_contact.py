"""Scenes where some or all of the filaments never touch the surface (issue 48, section 5):
a tuft that cannot reach beside one that can, and a head that swings in the air."""

import dataclasses
import re

import numpy as np
import pytest

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.simulation import simulate

# two tufts of one 0.5 mm nylon filament, 3 mm apart; the second, 8 mm long, cannot reach
# the plane at d = 9 mm (8 + 0.1 mm tip < 9)
TWO_TUFTS = """
name = "two-tufts"
[head]
layout = "tufts"
[[head.tufts]]
name = "near"
x = "0 mm"
diameter = "0.5 mm"
filaments = 1
width = "0.5 mm"
height = "0.5 mm"
[[head.tufts]]
name = "short"
x = "3 mm"
diameter = "0.5 mm"
filaments = 1
width = "0.5 mm"
height = "0.5 mm"
length = "8 mm"
[motion]
interaction_distance = "9 mm"
"""


@pytest.fixture(scope="module")
def two_tufts(tmp_path_factory):
    path = tmp_path_factory.mktemp("two") / "two.toml"
    path.write_text(TWO_TUFTS)
    return prepare(load_case(str(path), ["motion.periods=0.02"]))


def test_a_tuft_that_cannot_reach_runs_beside_one_that_can(two_tufts):
    assert two_tufts.reaching == (True, False)
    assert any("'short' cannot reach" in w for w in two_tufts.warnings)
    results = simulate(two_tufts, progress=False, workers=1)
    meta = results.metadata
    assert meta["status"] == "completed", meta["message"]
    assert meta["sanity"]["within_bound"]
    assert meta["sanity"]["groups_stopped_beyond_bound"] == []


def test_a_tuft_that_cannot_reach_resumes_as_it_solved(two_tufts, tmp_path):
    """A resumed group is held to the bound its solve checked: the short tuft's is its
    inertia allowance alone (a contact bound of 0 N; its handle pushed 1.7e-17 N at t = 0,
    which the contact bound alone refused on resuming)."""
    from exubrush.output.rundir import RunDirectory

    first = simulate(two_tufts, progress=False, workers=1,
                     directory=RunDirectory(tmp_path / "run", two_tufts))
    assert first.metadata["status"] == "completed", first.metadata["message"]
    sanity = first.metadata["sanity"]
    again = simulate(two_tufts, progress=False, workers=1,
                     directory=RunDirectory(tmp_path / "run", two_tufts))
    assert again.metadata["status"] == "completed", again.metadata["message"]
    assert again.metadata["sanity"] == sanity
    np.testing.assert_array_equal(again.normal_force, first.normal_force)


def test_a_group_stopped_beyond_its_bound_is_reported_honestly(two_tufts):
    # with a hundredth of the inertia allowance (a tenth of the handle's peak m a) the short
    # tuft's handle trips its bound early in the approach, as the bare 0 N bound did before
    # issue 48 (at the first check, 0.05 s)
    bare = dataclasses.replace(two_tufts, peak_acceleration=two_tufts.peak_acceleration / 100)
    meta = simulate(bare, progress=False, workers=1).metadata
    assert meta["status"] == "failed"
    kept, seen = re.search(r"stopped at t = (\S+) s, its last sample within the bound: normal "
                           r"force \S+ N at t = (\S+) s exceeds", meta["message"]).groups()
    # the sample named is the first one dropped: after the last kept, within one record
    # (the output interval) of it
    interval = two_tufts.case.output.interval
    assert float(kept) < float(seen) <= float(kept) + interval + 1e-12
    assert meta["sanity"]["within_bound"] is False
    assert meta["sanity"]["groups_stopped_beyond_bound"] == [1]


def _sonic_filament(*overrides):
    """The sonic case's first tuft, one filament of it, 0.05 s of swing."""
    case = load_case("sonic", ["motion.periods=0.0125", *overrides])
    return case.replace(head=case.head.replace(
        tufts=(case.head.tufts[0].replace(filaments=1),)))


def test_a_sonic_head_lifted_clear_swings_in_the_air():
    # the sonic filament reaches 10.4 + 0.1 mm below its root: at d = 11 mm it never
    # touches (docs/motion.md, "A head in the air")
    prepared = prepare(_sonic_filament("motion.interaction_distance='11 mm'"))
    assert prepared.reaching == (False,)
    assert any("moves in the air" in w for w in prepared.warnings)
    # no approach: the head starts at d and stands still until the swing
    assert prepared.start_height == 11.0
    assert prepared.motion.approach_distance == 0.0
    results = simulate(prepared, progress=False, workers=1)
    meta = results.metadata
    assert meta["status"] == "completed", meta["message"]
    assert meta["sanity"]["within_bound"]
    assert not results.tip_force.any()  # no contact element, no contact force
    # the tip swings across the head (±1.5 mm) and more (the filament near resonance)
    swing = results.time >= meta["derived"]["slide_start_s"]
    tip_across = results.tip_position[swing, 0, 1]
    assert np.ptp(tip_across) > 3.0


@pytest.mark.parametrize("distance", [
    "5.6 mm",  # beyond the reach (5 + 0.4 mm), within the clearance above it (0.3 mm)
    "6 mm",  # beyond both: above the approach's start
])
def test_a_head_in_the_air_without_pose_terms_is_refused(distance):
    with pytest.raises(ParameterError, match="add pose terms"):
        prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1",
                                         f"motion.interaction_distance='{distance}'"]))


TURNED = """
name = "turned"
[head]
rows = 1
columns = 1
[motion]
profile = "none"
pivot = ["0 mm", "0 mm", "-30 mm"]
[[motion.sine]]
axis = "{axis}"
angle = "{angle}"
frequency = "2 Hz"
ramp_cycles = 0
"""


@pytest.mark.parametrize("axis, angle, said", [
    ("rx", "60 deg", "the pose drives the head's roots 10.8 mm through the plane at t = "),
    ("ry", "85 deg", "motion: ry reaches 85° at t = "),
])
def test_an_impossible_pose_is_refused_in_one_line_before_anything_is_written(
        tmp_path, cli_here, axis, angle, said):
    (tmp_path / "turned.toml").write_text(TURNED.format(axis=axis, angle=angle))
    done = cli_here("run", "turned.toml", "--periods", "0.02", "--quiet", "--out", "out",
                    cwd=tmp_path)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and said in lines[0], done.stderr
    assert not (tmp_path / "out").exists()


AIR = """
name = "air"
[head]
rows = 1
columns = 2
[motion]
profile = "none"
period = "0.1 s"
periods = 1
interaction_distance = "9 mm"
[[motion.sine]]
axis = "y"
amplitude = "0.1 mm"
frequency = "50 Hz"
"""


def test_a_head_in_the_air_is_told_once(tmp_path, cli_here):
    # 5 + 0.4 mm of reach below roots 9 mm up: neither bristle touches; the warning that
    # the head moves in the air says it, not a second one counting the bristles
    (tmp_path / "air.toml").write_text(AIR)
    done = cli_here("run", "air.toml", "--quiet", "--out", "out", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    warnings = [line for line in done.stderr.splitlines() if "warning" in line]
    assert len(warnings) == 1 and "moves in the air" in warnings[0], done.stderr
