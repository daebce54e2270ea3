"""A sweep that varies a vector parameter (motion.pivot), solved in this process: its runs
are named by the components, and its summary holds each value in one cell."""

import csv
import json

from exubrush.execution.local import SerialExecutor
from exubrush.sweep.plan import read_sweep
from exubrush.sweep.runner import run_sweep

SWEEP = """
[sweep]
name = "pivots"
base = "orthogonal"
set = ["head.rows=1", "head.columns=1", "model.segments=2", "motion.periods=0.02"]
[grid]
"motion.pivot" = [["0 mm", "0 mm", "0 mm"], ["0 mm", "0.5 mm", "-1 cm"]]
"""


def test_a_swept_vector_is_one_cell_of_the_summary_in_the_sweep_files_unit(tmp_path):
    path = tmp_path / "pivots.toml"
    path.write_text(SWEEP)
    plan = read_sweep(path)
    assert [run.name for run in plan.runs] == ["000-pivot=0_0_0", "001-pivot=0_0.5_-1"]
    outcome = run_sweep(plan, tmp_path / "out", SerialExecutor(), progress=False)
    assert outcome.counts["completed"] == 2
    assert "summary.csv" in outcome.written
    with open(tmp_path / "out" / "summary.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    # the pivot in mm, the sweep's display unit: -1 cm is -10 mm
    assert [json.loads(row["motion.pivot [mm]"]) for row in rows] == [[0, 0, 0],
                                                                      [0, 0.5, -10]]
    assert [row["status"] for row in rows] == ["completed", "completed"]
