"""The command line: a small run writes its files; user mistakes give one line, exit 2."""

import csv
import json
import tomllib

import pytest

from exubrush.util.references import FLORES, FRICTION, HOWELL, PAPER, TIMOSHENKO_GERE

REQUIRED_COLUMNS = ["time [s]", "slider_position [mm]", "travelled_distance [mm]",
                    "normal_force [N]", "tangential_force [N]", "friction_coefficient [-]"]


def test_small_run_writes_complete_results(cli, tmp_path):
    out = tmp_path / "run"
    done = cli("run", "parallel", "--model", "prb", "--periods", "0.05", "--quiet",
                     "--set", "head.rows=1", "--set", "head.columns=1", "--out", str(out))
    assert done.returncode == 0, done.stderr
    assert f"results in {out}" in done.stdout
    with open(out / "forces.csv") as handle:
        rows = list(csv.reader(handle))
    assert rows[0][:6] == REQUIRED_COLUMNS
    assert len(rows) > 100
    meta = json.loads((out / "run.json").read_text())
    assert meta["completed"] and meta["model"] == "prb"
    assert {"exubrush", "exudyn", "python"} <= set(meta["versions"])
    assert meta["parameters"]["motion"]["direction"] == "parallel"
    assert meta["solver_statistics"]["steps"] > 0 and meta["wall_time_s"] > 0
    # a PRB run with the buckling link on a surface: the paper, its contact laws, Howell,
    # Timoshenko & Gere
    assert meta["references"] == [r.record() for r in
                                  (PAPER, FLORES, FRICTION, HOWELL, TIMOSHENKO_GERE)]
    assert meta["references"][0]["doi"] == PAPER.doi
    assert (out / "forces.png").stat().st_size > 10_000


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_progress_bar_reaches_the_end(cli, tmp_path):
    done = cli("run", "orthogonal", "--segments", "2", "--periods", "0.05",
                     "--set", "head.rows=1", "--set", "head.columns=2", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    last = done.stderr.replace("\r", "\n").strip().splitlines()[-1]
    assert "100%" in last and "1.80/1.80 s simulated" in last, last
    assert "TqdmWarning" not in done.stderr  # reports summing past the total by round-off


@pytest.mark.slow
def test_case_prints_toml_that_runs_back(cli, tmp_path):
    short = ["--set", "head.rows=1", "--set", "head.columns=2", "--set", "model.segments=2",
             "--set", "motion.periods=0.05"]
    done = cli("case", "orthogonal", *short)
    assert done.returncode == 0, done.stderr
    data = tomllib.loads(done.stdout)
    assert data["head"]["material"]["youngs_modulus"] == "7.5 MPa"
    assert data["solver"]["modified_newton"] is True  # a real boolean, not "yes"
    printed = tmp_path / "printed.toml"
    printed.write_text(done.stdout)
    from_file = cli("run", str(printed), "--quiet", "--out", str(tmp_path / "file"))
    built_in = cli("run", "orthogonal", *short, "--quiet", "--out", str(tmp_path / "built-in"))
    assert from_file.returncode == 0 and built_in.returncode == 0, from_file.stderr
    # the printed case is the built-in one: the same forces, byte for byte
    assert ((tmp_path / "file" / "forces.csv").read_bytes()
            == (tmp_path / "built-in" / "forces.csv").read_bytes())


@pytest.mark.parametrize("args, message", [
    (["run", "diagonal"], "unknown case 'diagonal'"),
    (["run", "orthogonal", "--set", "head.bristle.length='-2 mm'"], "must be > 0 mm"),
    (["run", "orthogonal", "--set", "head.material.youngs_modulus=7.5"], "has no unit"),
    (["run", "orthogonal", "--set", "head.nope=1"], "unknown parameter"),
    (["run", "orthogonal", "--model", "fem"], "'fem' is not one of"),
    (["run", "orthogonal", "--set", "motion.interaction_distance='9 mm'"], "no bristle"),
    (["case", "missing.toml"], "case file 'missing.toml' does not exist"),
    (["run", "orthogonal", "--set", "solver.user_functions=builtin"],
     "renamed contact.backend"),
])
def test_user_mistakes_give_one_line_and_exit_2(cli_here, args, message):
    done = cli_here(*args)
    assert done.returncode == 2
    assert message in done.stderr
    assert "Traceback" not in done.stderr
