"""Each tip's contact force, as recorded for the cleaning metrics, adds up to the head's
normal force; a run writes the tip data, the cleaning summary and its plot."""

import json

import numpy as np
import pytest

from exubrush.parameters.io import load_case
from exubrush.results import read_results
from exubrush.simulation import simulate

SMALL = ["head.rows=1", "head.columns=2", "motion.periods=0.25"]


@pytest.mark.parametrize("backend", ["paper-symbolic", "exudyn-builtin"])
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
