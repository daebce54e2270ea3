"""The parts build_scene assembles a group from (exubrush.run.scene), each on its own: the
handle, the drive, a bristle, a tip's contact with the surface, the contact between
bristles and the step hooks."""

import pytest

from exubrush.parameters.io import load_case
from exubrush.run import scene as scenes
from exubrush.run.prepared import prepare

ONE = ["head.rows=1", "head.columns=1"]


def _handle(prepared, count=1):
    """A scene with the handle and the first ``count`` bristles' geometry, nothing added."""
    return scenes.add_handle(prepared, prepared.bristles[:count], drawn=False)


def _hook_names(scene):
    """The step hooks' factories, in the order the scene calls them."""
    return [hook.__qualname__.split(".")[0] for hook in scene.step_hooks]


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
    assert scene.step_hooks == []  # nothing moves yet


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
    (drive,) = scene.step_hooks
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


def test_the_step_hooks_run_in_their_order():
    # two touching filaments of a tuft: the sampling before the step cap, the candidate
    # pairs after it (they read the cap)
    prepared = prepare(load_case("tuft", ["contact.between_bristles=true"]))
    scene = scenes.build_scene(prepared, prepared.groups[0][:2])
    assert _hook_names(scene) == ["add_drive", "lagged_drop_hook", "_contact_sampler",
                                  "step_cap", "contact_refresh"]
