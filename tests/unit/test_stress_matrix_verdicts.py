"""How the stability stress matrix (validation/stress_matrix.py) judges a cell that wrote no
run.json: only a refusal as the command line promises it (exit status 2, one line on
standard error) passes; a kill, an out-of-memory kill or an exit 1 fails."""

import json
import signal
import subprocess

import pytest

from validation import stress_matrix  # the repository root is on the test path (pyproject)

REFUSAL = "exubrush: error: solver.step_size 20 s does not resolve the motion\n"


def _verdict(tmp_path, status, stderr):
    return stress_matrix.judge({"cell": "c", "wall_s": 1.0}, status, stderr, tmp_path)


def test_a_refusal_passes_with_exit_2_and_one_line(tmp_path):
    row = _verdict(tmp_path, 2, REFUSAL)
    assert (row["outcome"], row["verdict"]) == ("refused", "pass")
    assert row["why"] == REFUSAL.strip()


@pytest.mark.parametrize("status, stderr", [
    (-signal.SIGKILL, ""),  # killed: nothing on standard error
    (-signal.SIGKILL, REFUSAL),  # killed after it printed a line
    (-signal.SIGSEGV, ""),
    (137, ""),  # a shell's report of a SIGKILL (128 + 9)
    (1, "exubrush: error: results not written: out: No space left on device\n"),
    (1, ""),
    (0, ""),  # said it completed, wrote nothing
    (2, ""),  # exit 2 without saying why
    (2, "exubrush: warning: one\nexubrush: error: two\n"),  # more than one line
])
def test_anything_else_without_run_json_fails(tmp_path, status, stderr):
    row = _verdict(tmp_path, status, stderr)
    assert row["verdict"] == "FAIL", row


def test_a_traceback_fails_even_with_exit_2(tmp_path):
    row = _verdict(tmp_path, 2, "Traceback (most recent call last):\nValueError: x\n")
    assert (row["outcome"], row["verdict"]) == ("crash", "FAIL")


def test_a_killed_cell_fails_though_it_left_a_run_json(tmp_path):
    (tmp_path / "run.json").write_text(json.dumps({"status": "completed"}))
    row = _verdict(tmp_path, -signal.SIGKILL, "")
    assert (row["outcome"], row["verdict"]) == ("killed", "FAIL")


def test_run_cell_judges_the_process_it_ran(tmp_path, monkeypatch):
    def killed(command, **kwargs):  # the out-of-memory killer's SIGKILL
        return subprocess.CompletedProcess(command, -signal.SIGKILL, "", "")

    monkeypatch.setattr(stress_matrix.subprocess, "run", killed)
    row = stress_matrix.run_cell(stress_matrix.Cell("default", ()), tmp_path, limit=10.0)
    assert (row["outcome"], row["verdict"], row["exit"]) == ("killed", "FAIL", -9)


def _run_json(tmp_path, peak, within, message):
    (tmp_path / "run.json").write_text(json.dumps({
        "status": "failed", "simulated_time_s": 0.03, "solver_statistics": {},
        "message": message,
        "sanity": {"peak_normal_force_N": peak, "normal_force_bound_N": 1.0,
                   "within_bound": within, "groups_stopped_beyond_bound": [0]}}))


def test_a_clear_stop_at_the_bound_passes(tmp_path):
    # run.json's sanity says within_bound false for a group stopped at its bound (issue 48):
    # its kept samples are within it, and the stop says when
    _run_json(tmp_path, 0.5, False, "group 0 stopped at t = 0.03 s, its last sample within "
              "the bound: normal force 3 N at t = 0.04 s exceeds the physical bound 1 N")
    assert _verdict(tmp_path, 1, "exubrush: failed: ...\n")["verdict"] == "pass"


def test_kept_samples_beyond_the_bound_fail(tmp_path):
    _run_json(tmp_path, 1.5, False, "group 0 stopped at t = 0.03 s, its last sample within "
              "the bound: ...")
    assert _verdict(tmp_path, 1, "exubrush: failed: ...\n")["verdict"] == "FAIL"
