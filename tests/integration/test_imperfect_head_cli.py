"""An imperfect head's keys out of range, refused at the command line: one line on standard
error, exit 2, nothing solved (docs/model.md, "Imperfections of a real head")."""

import pytest


@pytest.mark.parametrize("settings, message, case", [
    (["head.tilt_spread_x='-0.5 deg'"], "head.tilt_spread_x: -0.5 deg must be >= 0 deg",
     "orthogonal"),
    (["head.tilt_spread_y='10 deg'"], "head.tilt_spread_y: 10 deg must be < 10 deg", "orthogonal"),
    (["head.length_spread=-0.01"], "head.length_spread: -0.01 must be >= 0", "orthogonal"),
    (["head.length_spread='50 %'"], "head.length_spread: 50 % must be < 0.5", "orthogonal"),
    (["head.root_jitter='-0.1 mm'"], "head.root_jitter: -0.1 mm must be >= 0 mm", "orthogonal"),
    (["head.misalign_x='10 deg'"], "head.misalign_x: 10 deg must be < 10 deg", "orthogonal"),
    (["head.misalign_y='-11 deg'"], "head.misalign_y: -11 deg must be >= -10 deg", "orthogonal"),
    # the default grid: 1.8 mm pitch less the 1.082 mm diagonal of a 0.6 x 0.9 mm blade,
    # closed by up to 2√2 x the jitter: at most 0.25396 mm, shown rounded down
    (["head.root_jitter='0.254 mm'"], "head: root_jitter 0.254 mm could push neighbouring "
     "roots of the grid into each other (their sections' circles 0.7183 mm apart close by "
     "up to 2√2 x root_jitter): keep it at most 0.2539 mm", "orthogonal"),
    # list.toml's entries 1.2 mm apart: 1.2 - 1.082 = 0.1183 mm, / 2√2 = 0.041838 mm
    (["head.root_jitter='0.05 mm'"], "head: root_jitter 0.05 mm could push the roots of "
     "bristles[0] and bristles[1] into each other (their sections' circles 0.1183 mm apart "
     "close by up to 2√2 x root_jitter): keep it at most 0.04183 mm", "list.toml"),
    (["head.root_jitter='0.01 mm'"], "head: root_jitter is for grid and list layouts",
     "tuft"),
    # the root at x = 9.9 mm sinks 9.9 sin 9.9° = 1.702 mm, 0.702 mm below the plane at 1 mm
    (["head.misalign_y='9.9 deg'", "motion.interaction_distance='1 mm'"],
     "head.misalign_x, head.misalign_y: the misaligned head's lowest root comes 0.7021 mm "
     "below the plane", "orthogonal"),
    # the tooth row's tops are level with the plane: the same root would be inside a tooth
    (["head.misalign_y='9.9 deg'", "motion.interaction_distance='1 mm'"],
     "head.misalign_x, head.misalign_y: the misaligned head's lowest root comes 0.7021 mm "
     "below the tooth tops", "interdental"),
])
def test_an_imperfection_out_of_range_is_refused_in_one_line(tmp_path, cli_here, settings,
                                                             message, case):
    (tmp_path / "list.toml").write_text(
        '[head]\nlayout = "list"\n[[head.bristles]]\nx = "0 mm"\ny = "0 mm"\n'
        '[[head.bristles]]\nx = "1.2 mm"\ny = "0 mm"\n')
    args = ["run", case, "--periods", "0.01", "--out", "run"]
    for setting in settings:
        args += ["--set", setting]
    done = cli_here(*args, cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert message in done.stderr, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert not (tmp_path / "run").exists()


@pytest.mark.slow  # two real runs of one bristle
def test_run_json_holds_the_drawn_values_of_an_imperfect_head_only(tmp_path, cli_here):
    import json

    tiny = ["run", "orthogonal", "--quiet", "--segments", "2", "--periods", "0.02", "--set",
            "head.rows=1", "--set", "head.columns=2"]
    assert cli_here(*tiny, "--out", "ideal", cwd=tmp_path).returncode == 0
    done = cli_here(*tiny, "--set", "head.length_spread='4 %'", "--out", "imperfect",
                    cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    ideal = json.loads((tmp_path / "ideal" / "run.json").read_text())["derived"]
    record = json.loads((tmp_path / "imperfect" / "run.json").read_text())["derived"][
        "imperfections"]
    assert "imperfections" not in ideal
    assert len(record["length_mm"]) == 2
    assert all(4.8 <= length <= 5.2 for length in record["length_mm"])  # 5 mm ± 4 %
    assert record["length_mm"][0] != record["length_mm"][1]
