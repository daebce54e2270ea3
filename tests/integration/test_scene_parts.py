"""The parts build_scene assembles a group from (exubrush.run.scene), each on its own: the
handle, the drive, a bristle, a tip's contact with the surface, the contact between
bristles and the step hooks."""

import pytest

from exubrush.parameters.io import load_case
from exubrush.run import scene as scenes
from exubrush.run.prepared import prepare
from exubrush.run.step_hooks import (
    AFTER_CUT,
    CANDIDATES,
    DRIVE,
    FRICTION,
    JACOBIAN,
    PHASES,
    SAMPLING,
    StepHooks,
)

ONE = ["head.rows=1", "head.columns=1"]


def _handle(prepared, count=1):
    """A scene with the handle and the first ``count`` bristles' geometry, nothing added."""
    return scenes.add_handle(prepared, prepared.bristles[:count], drawn=False)


def _factories(hooks):
    """The names of the functions that made ``hooks``."""
    return [hook.__qualname__.split(".")[0] for hook in hooks]


@pytest.mark.parametrize("posed", [False, True])
def test_the_handle_is_a_block_of_acrylic_lighter_where_the_head_is_posed(posed, tmp_path):
    path = tmp_path / "posed.toml"
    path.write_text('name = "posed"\n[head]\nrows = 1\ncolumns = 1\n' + (
        '[[motion.sine]]\naxis = "x"\namplitude = "0.2 mm"\nfrequency = "100 Hz"\n'
        if posed else ""))
    prepared = prepare(load_case(str(path)))
    assert (prepared.motion.pose is not None) is posed
    scene, handle = _handle(prepared)
    block = 1.2e-9 * 20.0 * 8.0 * 3.0  # t: 1.2 g/cm³ over 20 x 8 x 3 mm
    assert scene.handle_mass == pytest.approx(block * (1e-6 if posed else 1.0), rel=1e-12)
    assert scene.mbs.GetNode(handle.node)["nodeType"] == "RigidBodyRxyz"
    assert int(scene.mbs.GetObject(handle.body)["nodeNumber"]) == int(handle.node)
    assert len(scene.step_hooks) == 0  # nothing moves yet


def test_the_drive_sets_the_slide_and_the_descent_before_a_step():
    prepared = prepare(load_case("orthogonal", ONE))
    scene, handle = _handle(prepared)
    scenes.add_drive(scene, handle.node)
    mbs = scene.mbs
    sensors = scene.drive_sensors
    named = [sensors.x, sensors.y, sensors.z, sensors.rx, sensors.ry, sensors.rz]
    assert [*sensors.force, *sensors.moment] == named
    constraints = [mbs.GetSensor(s)["objectNumber"] for s in named]
    # one per coordinate of the handle, in its order
    markers = [mbs.GetMarker(mbs.GetObject(c)["markerNumbers"][1]) for c in constraints]
    assert {int(m["nodeNumber"]) for m in markers} == {int(handle.node)}
    assert [m["coordinate"] for m in markers] == list(range(6))
    (drive,) = scene.step_hooks.of(DRIVE)
    assert len(scene.step_hooks) == 1
    t = scene.motion.slide_start + 0.3
    drive(mbs, t)
    slide, descent = scene.motion.sliding(t)[0], scene.motion.descent(t)[0]
    expected = [*(slide * scene.slide_axis[:3] - [0.0, 0.0, descent]), 0.0, 0.0, 0.0]
    offsets = [mbs.GetObjectParameter(c, "offset") for c in constraints]
    assert offsets == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize("model", ["dfm", "prb"])
def test_a_bristle_gets_a_position_sensor_on_each_node_from_root_to_tip(model):
    prepared = prepare(load_case("orthogonal", [*ONE, f"model.kind='{model}'"]))
    scene, handle = _handle(prepared)
    items = scenes.add_bristle(scene, prepared, scene.bristles[0], handle.body, drawn=False)
    (sensors,) = scene.node_sensors
    assert [int(scene.mbs.GetSensor(s)["nodeNumber"]) for s in sensors] == \
        [int(n) for n in items.nodes]
    assert len(items.nodes) == (6 if model == "dfm" else 1)  # a node per body, the last the tip


@pytest.mark.parametrize(("case", "compiled", "moving"), [
    ("orthogonal", False, False),
    ("interdental", True, False),  # the compiled law: its object's force is recorded
    ("mesh", False, True),  # a tangent plane moved before every step
])
def test_a_tip_contact_records_its_force_and_a_moving_frame(case, compiled, moving,
                                                            tmp_path):
    import trimesh

    trimesh.creation.icosphere(subdivisions=2, radius=4.0).export(tmp_path / "crown.stl")
    mesh = ["surface.kind='mesh'", f"surface.mesh_file='{tmp_path / 'crown.stl'}'"]
    prepared = prepare(load_case("orthogonal" if case == "mesh" else case,
                                 [*ONE, *(mesh if case == "mesh" else [])]))
    scene, handle = _handle(prepared)
    items = scenes.add_bristle(scene, prepared, scene.bristles[0], handle.body, drawn=False)
    surface = scenes.surface_marker(scene.mbs, scene.ground, prepared.case.surface)
    scenes.add_surface_contact(scene, prepared, surface, 0, items, {})
    (contact,) = scene.contacts
    (sensor,) = scene.contact_sensors
    assert (sensor.bristle, sensor.compiled) == (0, compiled)
    recorded = scene.mbs.GetSensor(sensor.force)
    if compiled:  # the object that carries the law, its connector switched off
        assert int(recorded["bodyNumber"]) == int(contact.compiled.item)
        assert not scene.mbs.GetObject(contact.connector)["activeConnector"]
    else:
        assert int(recorded["objectNumber"]) == int(contact.connector)
    assert (sensor.frame is not None) is moving
    assert len(scene.tangent_planes) == moving


@pytest.mark.parametrize("between", [False, True])
def test_bristles_touch_each_other_only_where_the_case_asks(between):
    prepared = prepare(load_case("tuft", [f"contact.between_bristles={str(between).lower()}"]))
    scene, handle = _handle(prepared, 2)
    polylines = []
    for bristle in scene.bristles:
        items = scenes.add_bristle(scene, prepared, bristle, handle.body, drawn=False)
        polylines.append(scenes._polyline(bristle, items.nodes, None))
    scenes.add_contact_between(scene, prepared.case, handle.node, polylines)
    assert (scene.bristle_contact is not None) is between
    assert (scene.bristle_contact in scene.keep_alive) is between


def test_the_hooks_run_phase_by_phase_whatever_order_they_came_in():
    hooks, calls = StepHooks(), []
    for phase in reversed(PHASES):  # registered backwards, two per phase
        for k in range(2):
            hooks.add(phase, lambda mbs, t, name=(phase, k): calls.append((name, t)))
    assert hooks(None, 0.5) is True
    assert calls == [((phase, k), 0.5) for phase in PHASES for k in range(2)]
    with pytest.raises(ValueError, match="'drift' is none of"):
        hooks.add("drift", print)


def test_a_tuft_touching_itself_samples_before_the_step_cap_and_refreshes_after_it():
    # two touching filaments of a tuft, with the line search after cuts
    prepared = prepare(load_case("tuft", ["contact.between_bristles=true",
                                          "solver.line_search='after-cut'"]))
    scene = scenes.build_scene(prepared, prepared.groups[0][:2])
    hooks = scene.step_hooks
    assert _factories(hooks) == ["after_step_cut", "add_drive", "lagged_drop_hook",
                                 "_contact_sampler", "step_cap", "contact_refresh"]
    assert _factories(hooks.of(SAMPLING)) == ["_contact_sampler"]
    assert _factories(hooks.of(CANDIDATES)) == ["contact_refresh"]
    assert _factories(hooks.of(AFTER_CUT)) == ["after_step_cut"]
    assert hooks.of(JACOBIAN) == ()  # touching: renewed at every attempt anyway


def test_a_head_apart_renews_its_jacobian_and_blends_the_builtin_friction_in():
    prepared = prepare(load_case("orthogonal", [*ONE, "contact.backend='exudyn-builtin'",
                                                "solver.linear_solver='EigenSparse'",
                                                "motion.approach_friction='off'"]))
    hooks = scenes.build_scene(prepared, (0,)).step_hooks
    assert _factories(hooks.of(FRICTION)) == ["builtin_friction_blend"]
    assert _factories(hooks.of(JACOBIAN)) == ["fresh_jacobian_after_step_change"]
