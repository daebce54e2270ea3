"""Larger steps in the middle of a stroke (solver.sliding_step_factor,
exubrush.run.step_policy)."""

from types import SimpleNamespace

import exudyn as exu
import numpy as np
import pytest

from exubrush.parameters.case import Surface
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.run.scene import build_scene
from exubrush.run.solve import group_settings
from exubrush.run.step_hooks import STEP_SIZE
from exubrush.run.step_policy import STRIBECK_MARGIN, tips_on_flat_tops
from exubrush.simulation import simulate
from exubrush.world.surfaces import orientation, to_surface_frame

ONE_BRISTLE = ["head.rows=1", "head.columns=1", "motion.periods=0.25"]


def _run(factor, *overrides):
    results = simulate(load_case("orthogonal", [*ONE_BRISTLE, *overrides,
                                                f"solver.sliding_step_factor={factor}"]),
                       progress=False, workers=1)
    assert results.metadata["status"] == "completed", results.metadata["message"]
    return results


def test_the_middle_of_a_stroke_takes_fewer_steps_at_the_same_forces():
    held, grown = _run(1), _run(5)
    # the slide starts at its peak speed, so the larger steps also cover the snap of the
    # state the approach left (within the first 0.4 s of slide; there a sample can differ
    # by 2 % of the range, the snap moving by a fraction of a step); compared: the steady
    # sliding after it, as long as the steps may be larger (speed >= 1/2 peak)
    assert len(grown.time) == len(held.time)
    speed = np.abs(np.gradient(held.slider_position, held.time))
    start = held.time[np.argmax(speed > 0.0)]
    steady = (held.time >= start + 0.5) & (speed >= 0.5 * speed.max())
    assert steady.sum() > 100  # 1.5 s at 10 ms
    for name in ("normal_force", "tangential_force"):
        a, b = getattr(held, name)[steady], getattr(grown, name)[steady]
        # within 0.1 % (the default head's later strokes: within 0.06 %, benchmark)
        assert np.abs(b - a).max() <= 1e-3 * np.abs(a).max()
    assert grown.metadata["solver_statistics"]["steps"] < \
        0.75 * held.metadata["solver_statistics"]["steps"]


@pytest.mark.parametrize(("overrides", "capped"), [
    ([], True),
    (["solver.sliding_step_factor=1"], False),
    # a tooth row: only while the tips are over flat tops (next test)
    (["surface.kind='tooth-row'"], True),
    # a mesh may have edges anywhere
    (["surface.kind='mesh'", "surface.mesh_file='plane.stl'"], False),
])
def test_the_step_grows_only_where_the_surface_allows(overrides, capped, tmp_path,
                                                       monkeypatch):
    monkeypatch.chdir(tmp_path)
    _write_plane_mesh(tmp_path / "plane.stl")
    prepared = prepare(load_case("orthogonal", [*ONE_BRISTLE, *overrides]))
    scene = build_scene(prepared, (0,))
    held = build_scene(prepare(load_case("orthogonal", [
        *ONE_BRISTLE, *overrides, "solver.sliding_step_factor=1"])), (0,))
    assert len(scene.step_hooks.of(STEP_SIZE)) == capped
    assert len(scene.step_hooks) == len(held.step_hooks) + capped


def _write_plane_mesh(path):
    import trimesh

    box = trimesh.creation.box(extents=[60.0, 60.0, 2.0])
    box.apply_translation([0.0, 0.0, -1.0])  # its top face at z = 0
    box.export(path)


class _Tips:
    """Stands in for the system: the tips' positions [mm] and velocities [mm/s]."""

    def __init__(self, positions, velocities=None):
        self.positions = positions
        self.velocities = velocities or [[0.0, 0.0, 0.0]] * len(positions)

    def GetNodeOutput(self, node, variable):
        if variable == exu.OutputVariableType.Velocity:
            return self.velocities[node]
        return self.positions[node]


def test_on_a_tooth_row_the_step_grows_only_with_every_tip_over_a_flat_top():
    # a placed and turned row; the tips are put at points of the row's own frame (along
    # the row u, across v, height z), turned into the head frame by the row's placement
    row = Surface(kind="tooth-row", tooth_width=7.0, gap_width=1.0, edge_radius=0.5,
                  x=1.5, y=-2.0, yaw=0.7)

    def head(u, v, z):
        return (np.array([row.x, row.y, 0.0]) + orientation(row) @ [u, v, z]).tolist()

    assert np.allclose(to_surface_frame(row, head(2.0, 1.0, 0.3)), [2.0, 1.0, 0.3])
    # the flat part of a top ends 3 mm from the tooth's centre; a radius of 0.2 mm and
    # 0.3 mm of travel (0.1 s at 3 mm/s) leave 2.5 mm either side
    clear = tips_on_flat_tops(row, [(0, 0.2), (1, 0.2)], ahead=0.1, speed=3.0)
    centre = head(0.0, 5.0, 0.3)  # across the row does not matter
    assert clear(_Tips([centre, head(2.4, -3.0, 0.3)]))
    assert clear(_Tips([centre, head(-2.4, 0.0, 0.3)]))  # the other side
    assert clear(_Tips([centre, head(8.0 + 2.4, 0.0, 0.3)]))  # the next tooth
    assert not clear(_Tips([centre, head(2.6, 0.0, 0.3)]))  # 2.6 mm: too close
    assert not clear(_Tips([centre, head(4.0, 0.0, 0.3)]))  # over the gap
    assert not clear(_Tips([centre, head(0.0, 0.0, -0.3)]))  # below the tops
    assert not clear(_Tips([head(-2.6, 0.0, 0.3), centre]))  # the first tip decides too
    # a tip moving along the row at 10 mm/s needs 1 mm of travel: not at 2.4 mm
    along = (orientation(row) @ [10.0, 0.0, 0.0]).tolist()
    assert not clear(_Tips([centre, head(2.4, 0.0, 0.3)], [[0.0, 0.0, 0.0], along]))
    assert clear(_Tips([centre, head(1.5, 0.0, 0.3)], [[0.0, 0.0, 0.0], along]))


def _large_step(case) -> float:
    """The larger step of the middle of a stroke [s]: sliding_step_factor times step_size,
    at most the output interval."""
    return min(case.solver.sliding_step_factor * case.solver.step_size, case.output.interval)


def _cap_in_a_stroke(surface_x: float) -> float:
    """The step cap the tooth row's scene sets in the middle of a stroke, with its one tip
    at rest where the reference state has it (over a top with the row at x = 0)."""
    prepared = prepare(load_case("orthogonal", [
        *ONE_BRISTLE, "surface.kind='tooth-row'", f"surface.x='{surface_x} mm'"]))
    scene = build_scene(prepared, (0,))
    iteration = SimpleNamespace(maxStepSize=0.0)
    scene.mbs.sys["dynamicSolver"] = SimpleNamespace(it=iteration)
    scene.step_hooks.of(STEP_SIZE)[-1](scene.mbs, scene.motion.slide_start + 0.1)
    return iteration.maxStepSize


def test_the_tooth_row_scene_caps_the_step_by_where_its_tips_are():
    case = load_case("orthogonal", ONE_BRISTLE)
    large = _large_step(case)
    assert _cap_in_a_stroke(0.0) == large  # the tip over a top's middle
    assert _cap_in_a_stroke(-4.0) == case.solver.step_size  # the tip over a gap


def test_a_slide_slower_than_the_stribeck_margin_keeps_the_step():
    # peak speed 2π·3 mm / 12 s = 1.57 mm/s: below 1.5 v_d = 2.25 mm/s everywhere, so the
    # tips' slip is never clear of the Stribeck band and the step stays step_size
    steps = [_run(factor, "motion.amplitude='3 mm'").metadata["solver_statistics"]["steps"]
             for factor in (1, 5)]
    assert steps[0] == steps[1]


def test_no_large_step_runs_into_a_slow_stretch_of_a_fast_short_stroke():
    # a sine of 5 mm and 0.5 s (63 mm/s peak, like brushing by hand): its slow stretches
    # around the reversals last 0.097 T = 48 ms, under the look-ahead of 60 ms, so a rule
    # that only looks at both ends of the look-ahead lets large steps through them
    case = load_case("orthogonal", [*ONE_BRISTLE, "motion.period=0.5 s",
                                    "motion.amplitude=5 mm", "motion.periods=2"])
    prepared = prepare(case)
    scene = build_scene(prepared, (0,))
    settings = group_settings(prepared, scene, (0,))
    attempts = []
    start_of_step = exu.ConfigurationType.StartOfStep

    def recorded(mbs, t):
        attempts.append((mbs.systemData.GetTime(start_of_step), t))
        return scene.run_step_hooks(mbs, t)

    scene.mbs.SetPreStepUserFunction(recorded)
    scene.mbs.SolveDynamic(settings)
    steps = np.array([a for a, b in zip(attempts, attempts[1:], strict=False)
                      if b[0] != a[0]])  # accepted: the next attempt starts where it ended
    large = steps[:, 1] - steps[:, 0] > 1.01 * case.solver.step_size
    assert large.sum() > 20  # the rule is at work in the middle of the strokes
    # the speed threshold: a fraction of the peak, 2π A / T
    peak = 2 * np.pi * case.motion.amplitude / case.motion.period
    threshold = max(case.solver.sliding_speed_fraction * peak,
                    STRIBECK_MARGIN * case.contact.dynamic_velocity)
    omega = 2 * np.pi / case.motion.period
    for begin, end in steps[large]:
        taus = np.linspace(begin, end, 20) - scene.motion.slide_start
        assert taus[0] > 0.0
        assert np.abs(peak * np.cos(omega * taus)).min() >= threshold


def test_the_cap_drops_the_look_ahead_before_the_speed_falls():
    case = load_case("orthogonal", ONE_BRISTLE)
    scene = build_scene(prepare(case), (0,))
    iteration = SimpleNamespace(maxStepSize=0.0)
    scene.mbs.sys["dynamicSolver"] = SimpleNamespace(it=iteration)
    large = _large_step(case)
    # Exudyn applies a lower cap when it next tries to grow the step, every
    # step_recovery_steps good steps: the step in progress and up to step_recovery_steps - 1
    # more may still be large; two steps of margin (docs/model.md)
    lead = (case.solver.step_recovery_steps + 2) * large
    # x = A sin(2π τ/T): the speed falls below the fraction f of its peak at
    # τ = T/(2π) arccos(f), before the first reversal at T/4 (0.3 of the paper's 7.85 mm/s
    # is above the Stribeck margin, so f is the fraction)
    fraction, period = case.solver.sliding_speed_fraction, case.motion.period
    assert fraction * 2 * np.pi * case.motion.amplitude / period > \
        STRIBECK_MARGIN * case.contact.dynamic_velocity
    slows = scene.motion.slide_start + period / (2 * np.pi) * np.arccos(fraction)
    margin = 1.5 * case.solver.step_size  # the speed is sampled every step_size
    scene.step_hooks.of(STEP_SIZE)[-1](scene.mbs, slows - lead - margin)
    assert iteration.maxStepSize == large
    scene.step_hooks.of(STEP_SIZE)[-1](scene.mbs, slows - lead + margin)
    assert iteration.maxStepSize == case.solver.step_size
