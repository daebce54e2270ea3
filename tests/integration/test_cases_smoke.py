"""Both built-in cases with both models, on a small head and a short slide.

Smoke checks: the run completes, nothing is NaN, the normal force is never negative, the
head presses once it has reached d, and the sliding force opposes the head's motion.
"""

import numpy as np
import pytest

from exubrush.parameters.io import load_case
from exubrush.simulation import simulate

SMALL_HEAD = ["head.rows=1", "head.columns=2", "motion.periods=0.15"]


@pytest.fixture(scope="module", params=[("orthogonal", "dfm"), ("orthogonal", "prb"),
                                        ("parallel", "dfm"), ("parallel", "prb")])
def smoke_run(request):
    case, model = request.param
    return simulate(load_case(case, [*SMALL_HEAD, f"model.kind='{model}'"]), progress=False,
                    workers=1)


def test_run_completes_without_nan(smoke_run):
    assert smoke_run.metadata["completed"], smoke_run.metadata["message"]
    for values in (smoke_run.normal_force, smoke_run.tangential_force, smoke_run.shape_nodes):
        assert np.all(np.isfinite(values))


def test_forces_have_the_right_sign(smoke_run):
    start = smoke_run.metadata["derived"]["slide_start_s"]
    # before contact only round-off of the summed reactions remains (~1e-20 N)
    assert np.all(smoke_run.normal_force >= -1e-12)
    pressed = smoke_run.time >= start
    assert np.all(smoke_run.normal_force[pressed] > 0.0)
    # slide is forward (+axis) all along a 0.15 period; once the tips slip, the head drags
    # the surface forward: positive sliding force, effective μ near μ_d = 0.76
    late = smoke_run.time > smoke_run.time[-1] - 0.3
    assert np.all(smoke_run.tangential_force[late] > 0.0)
    assert np.all(np.abs(smoke_run.friction_coefficient[late] - 0.76) < 0.1)


def test_runs_are_repeatable(smoke_run):
    case = load_case(smoke_run.metadata["case"],
                     [*SMALL_HEAD, f"model.kind='{smoke_run.metadata['model']}'"])
    again = simulate(case, progress=False, workers=1)
    np.testing.assert_array_equal(again.normal_force, smoke_run.normal_force)


def test_builtin_contact_blends_friction_in_for_prb_then_slides_at_mu_d():
    # PRB blends friction in after the approach (motion.approach_friction = auto); with
    # Exudyn's built-in contact a step hook does it (tested on its own in
    # test_contact_connector.py). Without the hook μ would stay 0; steady sliding is at μ_d
    results = simulate(load_case("orthogonal", [*SMALL_HEAD, "model.kind='prb'",
                                                "contact.backend='exudyn-builtin'"]),
                       progress=False, workers=1)
    assert results.metadata["completed"], results.metadata["message"]
    late = results.time > results.time[-1] - 0.3
    # 1e-3: the drive reaction's round-off and the last bit of bending still building up
    np.testing.assert_allclose(results.friction_coefficient[late], 0.76, atol=1e-3)


@pytest.mark.parametrize("script", ["orthogonal", "parallel"])
def test_case_scripts_run_in_smoke_mode(script):
    import importlib.util
    from pathlib import Path

    path = Path(__file__).parents[2] / "cases" / f"{script}.py"
    spec = importlib.util.spec_from_file_location(f"case_{script}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # no work on import
    results = module.run("prb", ["head.rows=1", "head.columns=1", "motion.periods=0.05"],
                         progress=False)
    assert results.metadata["completed"] and results.metadata["case"] == script
