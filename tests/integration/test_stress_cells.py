"""A reduced set of the stability stress matrix (validation/stress_matrix.py): each cell
must finish with forces below the physical bound or stop with a clear message."""

from dataclasses import replace

import pytest

from validation import stress_matrix  # the repository root is on the test path (pyproject)

pytestmark = pytest.mark.slow  # each cell is an exubrush process of a few seconds

CELLS = {c.name: c for c in stress_matrix.cells(full=True)}
REDUCED = ["orthogonal dfm: step 10 ms", "orthogonal dfm: no damping",
           "orthogonal dfm: contact k x100", "parallel prb: mu 1.5"]


@pytest.mark.parametrize("name", REDUCED)
def test_stress_cell_ends_sanely(name, tmp_path):
    # a tenth of a period after the approach: the first stick, slip and sliding
    cell = replace(CELLS[name], periods=0.1)
    row = stress_matrix.run_cell(cell, tmp_path, limit=600.0)
    assert row["verdict"] == "pass", row


def test_prb_default_head_passes_a_whole_reversal(tmp_path):
    # regression: with the sparse solver a PRB link swinging round its cone at the second
    # reversal (t = 10.6 s) made the Jacobian singular and the run stopped
    cell = replace(CELLS["orthogonal prb: default"], periods=1.0)
    row = stress_matrix.run_cell(cell, tmp_path, limit=600.0)
    assert row["outcome"] == "completed", row


def test_a_diverging_cell_is_judged_by_its_message(tmp_path):
    cell = stress_matrix.Cell("forced failure", (
        "solver.step_size='0.01 s'", "solver.minimum_step_size='0.01 s'",
        "contact.stiffness='1e5 N/mm^1.3'"), periods=0.1)
    row = stress_matrix.run_cell(cell, tmp_path, limit=600.0)
    assert row["outcome"] == "failed" and row["verdict"] == "pass", row
    assert "stopped at t = " in row["why"]


def test_a_cell_the_command_line_refuses_passes_as_refused(tmp_path):
    # the command line's refusal (exit 2, one line) is what the matrix accepts without a
    # run.json: a step that cannot resolve the motion is refused before anything is written
    cell = stress_matrix.Cell("refused step", ("solver.step_size='20 s'",), periods=0.1)
    row = stress_matrix.run_cell(cell, tmp_path, limit=600.0)
    assert (row["outcome"], row["verdict"], row["exit"]) == ("refused", "pass", 2), row
    assert "does not resolve the motion" in row["why"]
