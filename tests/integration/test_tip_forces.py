"""Each tip's contact force, as recorded for the cleaning metrics, adds up to the head's
normal force; a run writes the tip data, the cleaning summary and its plot."""

import json

import numpy as np
import pytest

from exubrush.output.results import read_results
from exubrush.parameters.io import load_case
from exubrush.simulation import simulate

SMALL = ["head.rows=1", "head.columns=2", "motion.periods=0.25"]


@pytest.mark.parametrize("backend", ["paper-symbolic", "exudyn-builtin"])
@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_tip_forces_add_up_to_the_head_normal_force(backend):
    results = simulate(load_case("orthogonal", [*SMALL, f"contact.backend='{backend}'"]),
                       progress=False)
    assert results.metadata["completed"]
    total = results.tip_force[:, :, 2].sum(axis=1)
    pressing = results.normal_force > 0.01
    assert pressing.sum() > 50
    # what differs is the bristles' own inertia and damping force (their mass is 1e-9 t
    # scale): far below 1e-4 N on the plane
    np.testing.assert_allclose(total, results.normal_force, atol=1e-4)
    assert results.tip_force[:, :, 2].min() >= -1e-9  # the plane pushes, never pulls


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_run_on_a_tooth_row_writes_its_cleaning_summary(tmp_path):
    case = load_case("interdental", [*SMALL, "motion.periods=0.3"])
    results = simulate(case, progress=False)
    results.save(tmp_path)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["data_origin"].startswith("exubrush model output")
    strokes = summary["cleaning"]["strokes"]
    assert strokes and "interdental" in strokes[0]
    assert (tmp_path / "cleaning.png").stat().st_size > 10_000
    again = read_results(tmp_path)
    np.testing.assert_array_equal(again.tip_force, results.tip_force)
    # recomputed from the files (times read back from forces.csv's decimal text)
    recomputed = again.cleaning()["strokes"]
    for stroke, stored in zip(recomputed, strokes, strict=True):
        assert stroke["interdental"]["max_depth_mm"] == stored["interdental"]["max_depth_mm"]
        assert stroke["wiped_area_mm2"] == pytest.approx(stored["wiped_area_mm2"], rel=1e-9)


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_tips_file_says_which_part_each_tip_touches(tmp_path):
    results = simulate(load_case("interdental", [*SMALL, "motion.periods=0.3"]),
                       progress=False)
    results.save(tmp_path)
    with np.load(tmp_path / "tips.npz") as tips:
        names = list(tips["part_names"])
        touching, part = tips["in_contact"], tips["part"]
    assert names == ["top", "edge", "wall", "floor"]
    assert np.array_equal(part >= 0, touching)
    # the stored per-part contact times are these flags summed over time
    summary = json.loads((tmp_path / "summary.json").read_text())["cleaning"]
    dt = np.gradient(results.time)
    for k, name in enumerate(names):
        assert summary["contact_time_per_part_tip_s"][name] == pytest.approx(
            float(np.sum(dt[:, None] * (part == k))), rel=1e-12, abs=1e-12)
    assert summary["contact_time_per_part_tip_s"]["top"] > 0.0


@pytest.mark.parametrize("surface", [
    ["surface.kind='cylinder'"], ["surface.kind='sphere'"],
    ["surface.kind='tooth-row'", "surface.yaw='30 deg'"]])
def test_every_surface_has_graphics_for_the_viewer(surface):
    from exubrush.run.prepared import prepare
    from exubrush.run.scene import build_scene

    prepared = prepare(load_case("orthogonal", [*SMALL, *surface]))
    scene = build_scene(prepared, (0,), drawn=True)
    ground = scene.mbs.GetObject(0)
    assert ground["VgraphicsData"]  # the surface is drawn


def test_a_mesh_surface_has_graphics_for_the_viewer(tmp_path):
    import trimesh

    from exubrush.run.prepared import prepare
    from exubrush.run.scene import build_scene

    trimesh.creation.icosphere(subdivisions=2, radius=4.0).export(tmp_path / "crown.stl")
    prepared = prepare(load_case("orthogonal", [
        *SMALL, "surface.kind='mesh'", f"surface.mesh_file='{tmp_path / 'crown.stl'}'"]))
    scene = build_scene(prepared, (0,), drawn=True)
    assert scene.mbs.GetObject(0)["VgraphicsData"]
    assert len(scene.tangent_planes) == 1  # the tip reaches the crown: one moving frame


@pytest.mark.slow  # an Exudyn run of 14 filaments
def test_the_tufts_forces_add_up_to_the_head_force(tmp_path):
    path = tmp_path / "two-tufts.toml"
    path.write_text('[head]\nlayout = "tufts"\n[[head.tufts]]\nname = "left"\nx = "-1 mm"\n'
                    'filaments = 7\ndiameter = "0.7 mm"\n[[head.tufts]]\nname = "right"\n'
                    'x = "1 mm"\nfilaments = 7\ndiameter = "0.7 mm"\n'
                    '[motion]\ninteraction_distance = "8.4 mm"\nperiods = 0.02\n')
    results = simulate(load_case(str(path)), progress=False, workers=1)
    results.save(tmp_path / "run")
    table = np.genfromtxt(tmp_path / "run" / "tufts.csv", delimiter=",", names=True)
    assert table.dtype.names[1:4] == ("leftforce_x_N", "leftforce_y_N", "leftforce_z_N")
    total_z = table["leftforce_z_N"] + table["rightforce_z_N"]
    # the head's force less the filaments' own inertia: slow brushing, well under 1 % of it
    np.testing.assert_allclose(-total_z, results.normal_force, rtol=0,
                               atol=0.01 * results.normal_force.max())
    assert results.normal_force.max() > 0.01  # they pressed: a test of something
