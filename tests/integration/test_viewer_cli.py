"""``exubrush run --viewer`` and ``exubrush view``: the whole head in Exudyn's SolutionViewer.

No window opens here (no display); what is checked is what the viewer would show: the
solution file, loaded into the head built with graphics, puts every node where the run
saw it.
"""

import exudyn as exu
import numpy as np
import pytest
from exudyn.utilities import LoadSolutionFile, SetSolutionState

from exubrush.output.results import read_results
from exubrush.output.viewer import viewer_scene
from exubrush.run.solution_files import SOLUTION_FILE, head_coordinates


@pytest.mark.slow
@pytest.mark.parametrize("model", ["dfm", "prb"])
def test_the_solution_file_replays_the_run(two_model_runs, cli, model):
    directory = two_model_runs / model
    done = cli("view", str(directory))
    assert done.returncode == 0, done.stderr
    assert "no display here" in done.stderr
    results = read_results(directory)
    solution = LoadSolutionFile(str(directory / SOLUTION_FILE), verbose=False)
    assert solution["nRows"] == len(results.shape_time)
    scene = viewer_scene(results)
    nodes = [n for sensors in scene.node_sensors
             for n in (scene.mbs.GetSensor(s)["nodeNumber"] for s in sensors)]
    objects = [scene.mbs.GetObject(i) for i in range(scene.mbs.systemData.NumberOfObjects())]
    drawn = sum(bool(item.get("VgraphicsData")) for item in objects)
    assert drawn == len(nodes) + 2  # every bristle body, the handle and the surface
    for row in range(solution["nRows"]):
        SetSolutionState(scene.mbs, solution, row, exu.ConfigurationType.Visualization)
        shown = np.array([scene.mbs.GetNodeOutput(n, exu.OutputVariableType.Position,
                                                  exu.ConfigurationType.Visualization)
                          for n in nodes])
        saved = results.shape_nodes[row, :, 1:].reshape(-1, 3)
        # 1e-9 mm: the file holds 12 significant digits of coordinates of order 1-10 mm
        np.testing.assert_allclose(shown, saved, atol=1e-9)


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_view_asks_for_a_run_that_kept_its_coordinates(tmp_path, cli):
    done = cli("run", "orthogonal", "--segments", "2", "--periods", "0.02", "--quiet",
               "--set", "head.rows=1", "--set", "head.columns=1", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    done = cli("view", str(tmp_path))
    assert done.returncode == 2
    assert "kept no node coordinates: run the case again with --viewer" in done.stderr
    assert "Traceback" not in done.stderr


def test_groups_join_into_the_head_once_with_its_handle():
    time = np.array([[0.0], [0.1]])
    first = np.hstack([time, np.ones((2, 6)), np.full((2, 3), 2.0)])
    second = np.hstack([time, np.ones((2, 6)), np.full((2, 3), 3.0)])
    joined = head_coordinates([first, second], np.array([0, 1]))
    np.testing.assert_array_equal(joined[0], [0.0, *[1.0] * 6, *[2.0] * 3, *[3.0] * 3])
    late = second.copy()
    late[1, 0] = 0.2
    with pytest.raises(ValueError, match="not at the same times"):
        head_coordinates([first, late], np.array([0, 1]))


def test_groups_that_interleave_join_in_the_head_order():
    # groups (0, 2) and (1,): joined positions hold bristles 0, 2, 1
    time = np.array([[0.0]])
    first = np.hstack([time, np.ones((1, 6)), [[10.0, 11.0, 30.0, 31.0]]])
    second = np.hstack([time, np.ones((1, 6)), [[20.0, 21.0]]])
    order = np.argsort(np.concatenate([(0, 2), (1,)]))
    joined = head_coordinates([first, second], order)
    np.testing.assert_array_equal(joined[0, 7:], [10.0, 11.0, 20.0, 21.0, 30.0, 31.0])


@pytest.mark.parametrize("rows", [0, 1, 3])
def test_a_solution_file_of_any_length_reads_back(tmp_path, rows):
    from exubrush.run.solution_files import read_coordinate_file, write_solution_file

    written = np.arange(8.0 * rows).reshape(rows, 8)
    write_solution_file(tmp_path / "solution.txt", written, "test")
    read = read_coordinate_file(tmp_path / "solution.txt")
    assert read.shape[0] == rows
    np.testing.assert_array_equal(read.reshape(written.shape), written)


@pytest.mark.parametrize("model", [
    ["model.kind='dfm'"], ["model.kind='dfm'", "model.rotation='rotation-vector'"],
    ["model.kind='prb'"], ["model.kind='prb'", "model.rotation='euler-parameters'"],
    ["model.kind='prb'", "model.prb_link='rigid'"], ["model.kind='prb'", "model.prb_pivot='joint'"],
])
def test_the_coordinates_a_saved_run_is_checked_for_are_those_of_its_head(model):
    """Model.bristle_coordinates, which read_results and a resume check the kept node
    coordinates against without building the head, counts what Exudyn's system holds."""
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare
    from exubrush.run.scene import build_scene
    from exubrush.run.solution_files import HANDLE_COORDINATES

    prepared = prepare(load_case("orthogonal", ["head.rows=1", "head.columns=3",
                                                "model.segments=3", *model]))
    scene = build_scene(prepared)
    per_bristle = prepared.case.model.bristle_coordinates
    assert scene.mbs.systemData.ODE2Size() == HANDLE_COORDINATES + 3 * per_bristle
