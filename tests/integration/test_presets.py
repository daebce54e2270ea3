"""The solver presets keep the flat-zone accuracy they state (exubrush.presets).

A 1 x 2 head over the approach and one slide period (one whole stroke between the two
reversals), each preset against a converged reference: DFM N = 24, 0.25 ms steps, Newton
rtol 1e-8, as the benchmark harness uses on the full head.
"""

import pytest

from exubrush.experiment import Alignment, ForceSeries, align, compare, strokes
from exubrush.parameters.io import load_case
from exubrush.presets import PRESETS, preset_overrides
from exubrush.simulation import simulate

SMALL_HEAD = ["head.rows=1", "head.columns=2", "motion.periods=1"]
REFERENCE = ["model.segments=24", "solver.step_size='0.25 ms'",
             "solver.relative_tolerance=1e-8"]


@pytest.fixture(scope="module")
def reference():
    results = simulate(load_case("orthogonal", [*SMALL_HEAD, *REFERENCE]), progress=False)
    assert results.metadata["status"] == "completed", results.metadata["message"]
    return ForceSeries.from_results(results)


@pytest.mark.parametrize("name", list(PRESETS))
def test_preset_flat_zone_forces_within_the_stated_error(reference, name):
    results = simulate(load_case("orthogonal", [*SMALL_HEAD, *preset_overrides(name)]),
                       progress=False)
    assert results.metadata["status"] == "completed", results.metadata["message"]
    aligned = align(ForceSeries.from_results(results), reference, Alignment())
    found = strokes(reference.time, reference.slide_velocity, 0.8)
    assert len(found) == 1
    largest = compare(aligned, found)["largest_flat_difference"]
    assert abs(largest["normal_force"]) <= PRESETS[name].flat_error
    assert abs(largest["tangential_force"]) <= PRESETS[name].flat_error


def test_an_unknown_preset_says_which_exist():
    with pytest.raises(ValueError, match="use one of fast, balanced, accurate"):
        preset_overrides("quick")
