"""A run's results keep the Case they solved, and a saved run builds its Case from run.json
once (issue 49, section 4): every reader of a Results asks for its case (the cleaning
metrics, the plots, the frames, the viewer), and each ask used to build and check the whole
Case again from run.json's text."""

import numpy as np
import pytest

from exubrush.output.results import Results, read_results
from exubrush.parameters.case import Case
from exubrush.parameters.catalogue import BUILT_IN_CASES
from exubrush.parameters.fields import build, to_plain
from exubrush.parameters.io import load_case
from exubrush.simulation import simulate

ONE_BRISTLE = ["head.rows=1", "head.columns=1", "motion.periods=0.05"]


@pytest.fixture
def builds(monkeypatch):
    """How many Cases are built (each build ends in Case.check) from here on."""
    count = [0]
    check = Case.check

    def counted(case):
        count[0] += 1
        check(case)

    monkeypatch.setattr(Case, "check", counted)
    return count


@pytest.mark.slow  # a one-bristle solve, about 1 s
def test_the_results_of_a_run_hold_the_case_it_solved_and_build_none(builds, tmp_path):
    case = load_case("orthogonal", ONE_BRISTLE)
    results = simulate(case, progress=False)
    before = builds[0]
    assert results.case() is case
    results.save(tmp_path)  # the metrics, summary.json and the plots ask for it again
    assert results.case() is case
    assert builds[0] == before  # not one Case built from run.json's text
    again = read_results(tmp_path)
    assert again.case() == case  # what run.json records is the case that was solved


def test_a_saved_run_builds_its_case_from_run_json_once(builds, tmp_path):
    case = load_case("orthogonal", ["head.rows=1", "head.columns=1"])
    time = np.arange(11) * case.output.interval
    zero = np.zeros(len(time))
    shapes = time[::case.output.shape_stride]  # as run.json says: checked when read
    Results(time=time, slider_position=zero, normal_force=zero, tangential_force=zero,
            head_height=zero + 4.0, shape_time=shapes,
            shape_nodes=np.zeros((len(shapes), 1, case.model.shape_nodes + 1, 3)),
            metadata={"parameters": to_plain(case), "status": "completed"}).save(tmp_path)
    before = builds[0]
    results = read_results(tmp_path)  # its checks need the case: built there
    first = results.case()
    assert results.case() is first and results.vibration() == ([], [])
    assert results.surface_mesh() is None and results.tuft_columns() == {}
    assert builds[0] - before == 1


@pytest.mark.parametrize("name", BUILT_IN_CASES)
def test_a_built_in_case_is_the_case_its_run_record_builds_again(name):
    """The results of a run compute their metrics from the Case in memory, a reader of the
    saved run from the one run.json's text builds: for every built-in case the two are the
    same, so summary.json is what a reader of the run computes again."""
    case = load_case(name)
    assert build(Case, to_plain(case)) == case
