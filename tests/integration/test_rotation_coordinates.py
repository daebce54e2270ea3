"""Rotation-vector (Lie-group) nodes are another set of coordinates for the same bristle
model: a brushing run must give the same forces as with Euler parameters."""

import numpy as np
import pytest

from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.run.scene import build_scene
from exubrush.simulation import simulate

pytestmark = pytest.mark.slow  # two models, two node types, each a short run

SMALL_RUN = ["head.rows=1", "head.columns=2", "motion.periods=0.5",
             "output.solution_file=true"]


@pytest.mark.parametrize("model", ["dfm", "prb"])
def test_rotation_vector_nodes_give_the_same_forces(model):
    runs = [
        simulate(load_case("orthogonal", [*SMALL_RUN, f"model.kind='{model}'",
                                          f"model.rotation='{rotation}'"]),
                 progress=False, workers=1)
        for rotation in ("euler-parameters", "rotation-vector")
    ]
    assert all(run.metadata["completed"] for run in runs)
    # the option took effect: 3 rotation coordinates per bristle node instead of 4
    widths = [run.shape_coordinates.shape[1] for run in runs]
    nodes = runs[0].shape_nodes.shape[1] * (runs[0].shape_nodes.shape[2] - 1)
    assert widths[0] - widths[1] == nodes
    reference, other = (np.column_stack([run.normal_force, run.tangential_force])
                        for run in runs)
    assert reference.shape == other.shape
    assert np.max(reference[:, 0]) > 0.01  # the tips did press on the plane [N]
    # same model, other coordinates: only the time discretisation differs (2 ms step cap,
    # Newton rtol 1e-6), so each run is within the step's own error of the converged forces
    # and the two within twice that. The step's error, the largest difference of these runs
    # from the same at 0.5 ms steps (sliding_step_factor 1): 0.8 % (DFM) and 0.65 % (PRB) of
    # the largest force, at the first snap after the approach; twice 0.8 %, rounded up: 2 %.
    # Every sample is compared (a mean lets differences of opposite sign cancel); measured
    # 0.30 % (DFM) and 0.65 % (PRB)
    scale = np.max(np.abs(reference))
    assert np.max(np.abs(other - reference)) < 0.02 * scale


@pytest.mark.parametrize("model, node_type", [("dfm", "RigidBodyEP"),
                                              ("prb", "RigidBodyRotVecLG")])
def test_auto_rotation_gives_each_model_its_faster_node(model, node_type):
    # DFM is faster on Euler parameters, PRB's link on a rotation vector
    # (docs/decisions/0015)
    case = load_case("orthogonal", ["head.rows=1", "head.columns=1", f"model.kind='{model}'"])
    assert case.model.rotation == "auto"
    scene = build_scene(prepare(case), (0,))
    types = {scene.mbs.GetNode(n)["nodeType"] for n in range(scene.mbs.systemData.NumberOfNodes())}
    assert node_type in types
    assert types & {"RigidBodyEP", "RigidBodyRotVecLG"} == {node_type}
