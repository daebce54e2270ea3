"""Sweep files: how they expand into runs, and how a malformed one is refused.

Nothing here solves: the plan is built from the parameters alone (exubrush.sweep.plan).
"""

import textwrap

import numpy as np
import pytest
from click.testing import CliRunner

from exubrush.cli import main
from exubrush.sweep.example import EXAMPLE
from exubrush.sweep.plan import SweepError, read_sweep, run_name

SMALL = ('[sweep]\nbase = "orthogonal"\nset = ["head.rows=1", "head.columns=2", '
         '"motion.periods=0.2"]\n')


def write(tmp_path, text, name="sweep.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def test_grid_is_every_combination_first_key_slowest(tmp_path):
    plan = read_sweep(write(tmp_path, SMALL + """
        [grid]
        "head.bristle.length" = ["4.5 mm", "5 mm"]
        "motion.interaction_distance" = { from = "4.0 mm", to = "4.4 mm", count = 3 }
        """))
    assert len(plan.runs) == 6
    lengths = [run.case.head.bristle.length for run in plan.runs]
    distances = [run.case.motion.interaction_distance for run in plan.runs]
    assert lengths == [4.5] * 3 + [5.0] * 3
    assert distances == pytest.approx([4.0, 4.2, 4.4] * 2, rel=1e-12)
    assert [s.key for s in plan.swept] == ["head.bristle.length", "motion.interaction_distance"]
    assert [s.unit for s in plan.swept] == ["mm", "mm"]
    # the common overrides reach every run
    assert {run.case.head.columns for run in plan.runs} == {2}


def test_ranges_convert_units_and_space_logarithmically(tmp_path):
    plan = read_sweep(write(tmp_path, SMALL + """
        [grid."head.material.youngs_modulus"]
        from = "5e6 Pa"
        to = "20 MPa"
        count = 3
        scale = "log"
        """))
    moduli = [run.case.head.material.youngs_modulus for run in plan.runs]  # MPa internally
    assert moduli == pytest.approx([5.0, 10.0, 20.0], rel=1e-11)  # geometric: 5 * 2^k


def test_latin_hypercube_has_one_point_per_stratum_and_is_seeded(tmp_path):
    text = SMALL + """
        [sample]
        count = 5
        seed = 4
        [sample.ranges]
        "contact.dynamic_friction" = { from = 0.5, to = 0.75 }
        "motion.interaction_distance" = { from = "4.0 mm", to = "4.5 mm" }
        """
    plan = read_sweep(write(tmp_path, text))
    friction = np.array([run.case.contact.dynamic_friction for run in plan.runs])
    distance = np.array([run.case.motion.interaction_distance for run in plan.runs])
    # Latin hypercube: each of the 5 equal slices of each range holds exactly one point
    assert sorted(np.floor((friction - 0.5) / 0.05).astype(int)) == [0, 1, 2, 3, 4]
    assert sorted(np.floor((distance - 4.0) / 0.1).astype(int)) == [0, 1, 2, 3, 4]
    again = read_sweep(write(tmp_path, text, "again.toml"))
    assert [r.values for r in again.runs] == [r.values for r in plan.runs]


def test_seeds_repeat_every_combination_and_names_are_unique(tmp_path):
    plan = read_sweep(write(tmp_path, SMALL + """
        seeds = [1, 2]
        [grid]
        "model.kind" = ["dfm", "prb"]
        """))
    assert [(r.case.model.kind, r.case.head.seed) for r in plan.runs] == [
        ("dfm", 1), ("dfm", 2), ("prb", 1), ("prb", 2)]
    assert [r.name for r in plan.runs] == ["000-kind=dfm-seed=1", "001-kind=dfm-seed=2",
                                           "002-kind=prb-seed=1", "003-kind=prb-seed=2"]


def test_run_names_stay_one_safe_directory_name():
    name = run_name(7, [("head.bristle.length", "4.50000001 mm"), ("model.kind", "../x y")])
    assert name == "007-length=4.5-kind=.._x_y"
    assert "/" not in name and " " not in name


def test_the_same_file_gives_the_same_identity_and_a_change_another(tmp_path):
    from exubrush.sweep.runner import prepare_runs, sweep_identity

    def identity(text, name):
        plan = read_sweep(write(tmp_path, text, name))
        return sweep_identity(plan, prepare_runs(plan))["fingerprint"]

    text = SMALL + '[grid]\n"head.seed" = [1, 2]\n'
    first = identity(text, "a.toml")
    assert identity(text, "b.toml") == first
    assert identity(text.replace("0.2", "0.3"), "c.toml") != first
    # the limits change no result: a single run resumes after one is raised, so does a sweep
    assert identity(text.replace("]\n[grid]", ', "limits.bristles=500"]\n[grid]'),
                    "d.toml") == first


def test_the_printed_example_is_a_valid_sweep(tmp_path):
    done = CliRunner().invoke(main, ["sweep", "--example"])
    assert done.exit_code == 0 and done.output == EXAMPLE
    plan = read_sweep(write(tmp_path, done.output))
    assert len(plan.runs) == 6 and plan.execution.scheduler == "local"


# (sweep file text, part of the one-line message it must give)
MALFORMED = [
    ("[grids]\n", "unknown section [grids]"),
    ('[sweep]\nbases = "orthogonal"\n',
     "sweep.bases: unknown key; known keys here: base, max_runs, name, seeds, set"),
    ('[sweep]\nbase = "orthogonal"\nmax_runs = 2.5\n', "sweep.max_runs: expected a whole number"),
    (SMALL + 'seeds = [1, "2"]\n', "sweep.seeds[1]: expected a whole number, got '2'"),
    (SMALL + "seeds = [1, 1]\n", "seeds repeats a seed"),
    ('[sweep]\nbase = "orthogonal"\nset = "motion.periods=1"\n', "sweep.set: expected a list"),
    (SMALL + 'name = " "\n[grid]\n"head.seed" = [1]\n', "name must be non-empty text"),
    ("[sweep]\nset = []\n[grid]\n\"head.seed\" = [1]\n", "sweep.base is missing"),
    ('[sweep]\nbase = "no-such-case.toml"\n[grid]\n"head.seed" = [1]\n',
     "no-such-case.toml' does not exist"),
    (SMALL, "nothing varies"),
    (SMALL + '[grid]\n"head.bristle.lenght" = ["4 mm"]\n',
     "grid.head.bristle.lenght: unknown parameter; did you mean head.bristle.length?"),
    (SMALL + '[grid]\n"head.bristle.length" = [4.5, 5]\n', "4.5 has no unit"),
    (SMALL + '[grid]\n"head.bristle.length" = { from = 4, to = 5, count = 2 }\n',
     "grid.head.bristle.length.from: 4 has no unit"),
    (SMALL + '[grid]\n"head.bristle.length" = []\n', "expected a non-empty list"),
    # a number is no angle: pint would read 90 as 90 rad
    (SMALL + '[grid]\n"surface.yaw" = { from = 0, to = 90, count = 2 }\n',
     "grid.surface.yaw.from: 0 has no unit; write it with one, e.g. '0 deg' or '0 rad'"),
    (SMALL + '[grid]\n"surface.yaw" = ["0 deg", "90"]\n', "'90' has no unit"),
    (SMALL + '[grid]\n"head.bristle.length" = ["5 mm", "5 mm"]\n', "a value is listed twice"),
    (SMALL + '[grid]\n"head.bristle.length" = { from = "5 mm", to = "4 mm", count = 2 }\n',
     "from (5 mm) must be below to (4 mm)"),
    (SMALL + '[grid]\n"head.bristle.length" = { from = "4 mm", to = "5 mm" }\n',
     "a range needs count"),
    (SMALL + '[grid]\n"head.bristle.length" = { from = "4 mm", to = "5 mm", count = 1 }\n',
     "count: expected a whole number >= 2"),
    (SMALL + '[grid]\n"head.bristle.length" = { from = "4 s", to = "5 s", count = 2 }\n',
     "'4 s' has unit 's', which cannot be converted to 'mm'"),
    (SMALL + '[grid]\n"head.material.youngs_modulus" = '
             '{ from = "0 MPa", to = "5 MPa", count = 2, scale = "log" }\n',
     "a log range needs from > 0"),
    (SMALL + '[grid]\n"head.bristle.length" = '
             '{ from = "4 mm", to = "5 mm", count = 2, scale = "cubic" }\n',
     "'cubic' is not one of linear, log"),
    (SMALL + '[grid]\n"head.rows" = { from = 1, to = 3, count = 3 }\n',
     "a whole number parameter takes a list of values, not a range"),
    (SMALL + '[grid]\n"motion.pivot" = { from = "0 mm", to = "1 mm", count = 2 }\n',
     "grid.motion.pivot: a vector parameter takes a list of values, not a range"),
    (SMALL + '[grid]\n"motion.pivot" = { from = ["0 mm", "0 mm", "0 mm"], '
             'to = ["1 mm", "1 mm", "1 mm"], count = 2 }\n',
     "grid.motion.pivot: a vector parameter takes a list of values, not a range"),
    (SMALL + '[sample]\ncount = 2\n[sample.ranges]\n"motion.pivot" = { from = "0 mm", '
             'to = "1 mm" }\n', "a vector parameter takes a list of values, not a range"),
    (SMALL + '[sample]\ncount = 0\n[sample.ranges]\n"contact.dynamic_friction" = '
             '{ from = 0.5, to = 0.7 }\n', "sample.count: expected a whole number >= 1"),
    (SMALL + "[sample]\ncount = 3\n", "[sample.ranges] must name at least one parameter"),
    (SMALL + '[sample]\ncount = 3\n[sample.ranges]\n"contact.dynamic_friction" = '
             '{ from = 0.5 }\n', "a range needs to"),
    (SMALL.replace('"motion.periods=0.2"', '"motion.periods=0.2", "head.seed=3"')
     + "seeds = [1, 2]\n", "sweep.set sets head.seed, which the sweep varies"),
    (SMALL + "seeds = []\n", "sweep.seeds must be a non-empty list"),
    (SMALL + 'max_runs = 4\n[grid]\n"head.seed" = [1, 2, 3, 4, 5]\n',
     "expands to 5 runs, more than sweep.max_runs = 4"),
    (SMALL + '[grid]\n"head.material.poisson_ratio" = [0.3, 0.5]\n',
     "run 1 (head.material.poisson_ratio = 0.5): head.material.poisson_ratio: 0.5 must be < 0.5"),
    (SMALL + '[grid]\n"name" = ["a", "b"]\n', "the case name is not a parameter to vary"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\nworkers = -1\n',
     "execution.workers: -1 must be >= 0"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\nworkers = 1000000000000\n',
     "execution.workers: 1000000000000 does not fit a 32-bit integer"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\nworkers = 1.5\n',
     "execution.workers: expected a whole number, got 1.5"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\nplace = "here"\n',
     "execution.place: unknown key; known keys here: scheduler, timeout, workers"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\ntimeout = 10\n',
     "execution.timeout: 10 has no unit"),
    ("[sweep\n", "not valid TOML"),
    # counts far beyond what may run: refused before any value is made
    (SMALL + '[grid]\n"head.bristle.length" = '
             '{ from = "4 mm", to = "5 mm", count = 1000000000000 }\n',
     "count: 1000000000000 values are more than sweep.max_runs = 1000 runs"),
    (SMALL + '[sample]\ncount = 1000000000000\n[sample.ranges]\n"contact.dynamic_friction" = '
             '{ from = 0.5, to = 0.7 }\n',
     "sample.count: 1000000000000 values are more than sweep.max_runs = 1000 runs"),
    (SMALL + "[grid]\n" + "".join(
        f'"{key}" = {{ from = "4 mm", to = "5 mm", count = 1000 }}\n'
        for key in ("head.bristle.length", "head.bristle.width", "head.bristle.height",
                    "head.pitch_along", "head.pitch_across", "motion.amplitude")),
     "expands to 1000000000000000000 runs, more than sweep.max_runs = 1000"),
    (SMALL + '[grid]\n"head.bristle.length" = { from = 1e308, to = 1e308, count = 2 }\n',
     "1e+308 has no unit"),
    (SMALL + '[grid]\n"head.bristle.length" = '
             '{ from = "-1e308 mm", to = "1e308 mm", count = 3 }\n',
     "from (-1e308 mm) to (1e308 mm) spans more than a number can hold"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\ntimeout = "1e308 s"\n',
     "execution.timeout: 1e308 s is outside the magnitudes exubrush computes with"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\ntimeout = "601 s"\n',
     "timeout 601 s is longer than 600 s a wait for a scheduler may take"),
    (SMALL + '[grid]\n"head.seed" = [1]\n[execution]\ntimeout = "0 s"\n',
     "execution.timeout: 0 s must be > 0 s"),
]


@pytest.mark.parametrize(("text", "message"), MALFORMED, ids=[m for _, m in MALFORMED])
def test_malformed_sweep_is_refused_in_one_line_with_exit_2_and_nothing_written(
        tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(SweepError) as caught:
        read_sweep(path)
    assert message in str(caught.value)
    out = tmp_path / "out"
    done = CliRunner().invoke(main, ["sweep", str(path), "--out", str(out), "--quiet"])
    assert done.exit_code == 2, done.output
    lines = done.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("exubrush: error: ")
    assert message in " ".join(str(caught.value).split())
    assert not out.exists()


SCHEDULER_FAULTS = [
    ('scheduler = "foo:8786"', [], "execution.scheduler 'foo:8786': not a scheduler address"),
    ('scheduler = "local"', ["--scheduler", "tcp://"], "--scheduler 'tcp://': not a scheduler"),
    ("workers = 1000000", [], "1000000 local workers: at most 4 per core"),
    # nothing listens on port 9 (discard) here: refused until the timeout
    ('scheduler = "tcp://127.0.0.1:9"\ntimeout = "1 s"', [],
     "execution.scheduler tcp://127.0.0.1:9: no scheduler answered within 1 s"),
]


@pytest.mark.parametrize(("execution", "options", "message"), SCHEDULER_FAULTS,
                         ids=[m[:40] for *_, m in SCHEDULER_FAULTS])
def test_a_scheduler_that_cannot_be_used_is_refused_with_exit_2_and_nothing_written(
        tmp_path, execution, options, message):
    path = write(tmp_path, SMALL + f'[grid]\n"head.seed" = [1]\n[execution]\n{execution}\n')
    out = tmp_path / "out"
    done = CliRunner().invoke(main, ["sweep", str(path), "--out", str(out), "--quiet",
                                     *options])
    assert done.exit_code == 2, done.output
    assert message in done.output
    assert not out.exists()


def test_a_folder_holding_another_sweep_or_foreign_files_is_refused(tmp_path):
    first = write(tmp_path, SMALL + '[grid]\n"head.seed" = [1]\n', "first.toml")
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    done = CliRunner().invoke(main, ["sweep", str(first), "--out", str(out), "--quiet"])
    assert done.exit_code == 2 and "holds files that are not an exubrush sweep" in done.output
    (out / "notes.txt").unlink()
    (out / "sweep.json").write_text('{"fingerprint": "another"}')
    done = CliRunner().invoke(main, ["sweep", str(first), "--out", str(out), "--quiet"])
    assert done.exit_code == 2 and "holds another sweep" in done.output
    assert sorted(p.name for p in out.iterdir()) == ["sweep.json"]


def test_list_valued_settings_are_checked_item_by_item_from_python_too():
    from exubrush.parameters.fields import ParameterError
    from exubrush.sweep.settings import SweepSettings

    assert SweepSettings().replace(seeds=(1, 2)).seeds == (1, 2)
    with pytest.raises(ParameterError, match=r"SweepSettings.seeds\[1\]: -1 must be >= 0"):
        SweepSettings().replace(seeds=(1, -1))
    with pytest.raises(ParameterError, match="SweepSettings.seeds: expected a tuple"):
        SweepSettings().replace(seeds=[1])
