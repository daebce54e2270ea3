"""A saved run's files cut short, corrupted or replaced by foreign ones: every reader of a
saved run (frames, view, compare, a resumed run, a resumed sweep) ends in one line naming
the file and exit status 2, never a traceback; property tests damage the files at random.

One small run (a 1 x 2 head, two segments, a fiftieth of a period) is solved once for the
module, its checkpoint kept: each test damages a copy.
"""

import json
import shutil

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from exubrush.cli import main

OVERRIDES = ["model.segments=2", "motion.periods=0.02", "output.solution_file=true",
             "head.rows=1", "head.columns=2"]
# the same run on the command line (its checkpoint's fingerprint must match)
RUN = ["run", "orthogonal", "--segments", "2", "--periods", "0.02", "--viewer", "--quiet",
       "--set", "head.rows=1", "--set", "head.columns=2"]
SWEEP = """
[sweep]
name = "one"
base = "orthogonal"
set = ["head.rows=1", "head.columns=2"]
[grid]
"head.seed" = [1]
"""


@pytest.fixture(scope="module")
def solved(tmp_path_factory):
    """``saved``: the run's result directory; ``resumable``: its checkpoint alone (as a run
    stopped after every group finished leaves it)."""
    from exubrush.output.rundir import RunDirectory
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare
    from exubrush.simulation import simulate

    root = tmp_path_factory.mktemp("damaged")
    prepared = prepare(load_case("orthogonal", OVERRIDES))
    store = RunDirectory(root / "resumable", prepared)
    simulate(prepared, progress=False, directory=store, workers=1).save(root / "saved")
    assert sorted(p.name for p in store.checkpoint.glob("group-*.npz"))
    return root


def _copy(solved, tmp_path, which="saved"):
    return shutil.copytree(solved / which, tmp_path / which)


def _truncated(path):
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])


def _foreign_npz(path):  # another exubrush file in its place
    path.write_bytes((path.parent / "tips.npz").read_bytes() if path.name == "shapes.npz"
                     else (path.parent / "shapes.npz").read_bytes())


def _without_coordinates(path):  # a zip entry's name damaged: the array is gone
    with np.load(path) as arrays:
        kept = {name: arrays[name] for name in arrays.files if name != "coordinates"}
    with open(path, "wb") as handle:
        np.savez_compressed(handle, **kept)


DAMAGES = {
    "without coordinates": _without_coordinates,
    "not a zip": lambda path: path.write_text("time,nodes\n0,1\n"),
    "cut short": _truncated,
    "empty": lambda path: path.write_bytes(b""),
    "a JSON list": lambda path: path.write_text("[1, 2, 3]"),
    "not JSON": lambda path: path.write_text('{"status": "completed", "parame'),
    "garbage": lambda path: path.write_bytes(bytes(range(256)) * 4),
    "foreign": _foreign_npz,
}


def _refused(args, named):
    """The command ends with exit 2 and one line naming the file ``named``."""
    done = CliRunner().invoke(main, [str(a) for a in args])
    assert isinstance(done.exception, SystemExit), done.exception  # never a traceback
    assert done.exit_code == 2, done.output
    lines = done.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("exubrush: error: "), done.output
    assert named in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize(("command", "file", "damage"), [
    ("frames", "shapes.npz", "not a zip"),
    ("frames", "run.json", "a JSON list"),
    ("frames", "tips.npz", "foreign"),
    ("view", "shapes.npz", "cut short"),
    ("view", "tips.npz", "empty"),
    ("view", "shapes.npz", "without coordinates"),
    ("compare", "tips.npz", "cut short"),
    ("compare", "shapes.npz", "foreign"),
    ("compare", "forces.csv", "garbage"),
    ("compare", "run.json", "not JSON"),
])
def test_a_damaged_result_file_is_named_in_one_line_with_exit_2(solved, tmp_path, command,
                                                                 file, damage):
    run = _copy(solved, tmp_path)
    DAMAGES[damage](run / file)
    measured = tmp_path / "measured.csv"
    shutil.copy(run / "forces.csv" if file != "forces.csv" else solved / "saved/forces.csv",
                measured)
    args = {"frames": ["frames", run, "--gif-frames", "0", "--out", tmp_path / "frames"],
            "view": ["view", run, "--write-only"],
            "compare": ["compare", run, measured, "--out", tmp_path / "compare"]}[command]
    message = _refused(args, str(run / file))
    if file != "run.json":
        assert "make the run again" in message


def _forces_cell(column, cell):
    """forces.csv with the cell of its third sample in ``column`` (0: time) set to ``cell``."""
    def change(path):
        lines = path.read_text().splitlines()
        cells = lines[3].split(",")
        cells[column] = cell
        lines[3] = ",".join(cells)
        path.write_text("\n".join(lines) + "\n")
    return change


def _head(rows, columns):
    def change(path):
        record = json.loads(path.read_text())
        record["parameters"]["head"].update(rows=rows, columns=columns)
        path.write_text(json.dumps(record))
    return change


POISONED = {  # (file, damage, the reason given): whole files no run of this run.json writes
    "a node fewer": ("shapes.npz", lambda p: _rewritten(p, _set("nodes", lambda a: a[:, :, :-1])),
        '2 bristles of 3 nodes'),
    "no nodes": ("shapes.npz", lambda p: _rewritten(p, _set("nodes", lambda a: a[:, :, :0])),
        'nodes (15, 2, 0, 3)'),
    "no bristles": ("shapes.npz", lambda p: _rewritten(p, _set("nodes", lambda a: a[:, :0])),
        'nodes (15, 0, 3, 3)'),
    "a shape fewer": ("shapes.npz", lambda p: _rewritten(
        p, lambda arrays: arrays.update(time=arrays["time"][:-1], nodes=arrays["nodes"][:-1])),
        '145 times of forces.csv make 15 shape samples'),
    "complex nodes": ("shapes.npz", lambda p: _rewritten(
        p, _set("nodes", lambda a: a.astype(complex))),
        'complex128'),
    "boolean coordinates": ("shapes.npz", lambda p: _rewritten(
        p, _set("coordinates", lambda a: a != 0)),
        'bool'),
    "coordinates without rows": ("shapes.npz", lambda p: _rewritten(
        p, _set("coordinates", lambda a: a[:0])),
        'coordinates (0, 35) are not rows of 35'),
    "coordinates without columns": ("shapes.npz", lambda p: _rewritten(
        p, _set("coordinates", lambda a: a[:, :0])),
        'coordinates (15, 0) are not rows of 35'),
    "NaN shape time": ("shapes.npz", lambda p: _rewritten(p, _set("time", np.nan)),
        "'time' holds a value that is not finite"),
    "nodes of 1e300 mm": ("shapes.npz", lambda p: _rewritten(p, _set("nodes", 1e300)),
        "'nodes' holds a value beyond 1e+20"),
    "shape times shifted": ("shapes.npz", lambda p: _rewritten(
        p, _set("time", lambda a: a + 100.0)), "its times are not every 10th time"),
    "coordinates at other times": ("shapes.npz", lambda p: _rewritten(
        p, _set("coordinates", lambda a: a + np.eye(1, a.shape[1]))),
        "coordinates are not at its shapes' times"),
    "infinite tip force": ("tips.npz", lambda p: _rewritten(p, _set("force", np.inf)),
        "'force' holds a value that is not finite"),
    "tips of another head": ("tips.npz", lambda p: _rewritten(
        p, lambda arrays: arrays.update(position=arrays["position"][:, :1],
                                        force=arrays["force"][:, :1])),
        "the run's 2 bristles"),
    "NaN time": ("forces.csv", _forces_cell(0, "nan"),
        'finite numbers only'),
    "normal force of 1e300 N": ("forces.csv", _forces_cell(3, "1e300"), "beyond 1e+20"),
    "time going back": ("forces.csv", _forces_cell(0, "-1"),
        'times must increase strictly'),
    "a head of 10^10 bristles": ("run.json", _head(100_000, 100_000),
        '10000000000 bristles'),
    "a head of 3 bristles": ("run.json", _head(1, 3),
        'has 3 bristles'),
}


@pytest.mark.parametrize("command", ["frames", "view", "compare"])
@pytest.mark.parametrize("poison", POISONED)
def test_a_saved_file_that_does_not_fit_its_run_is_refused_by_every_reader(
        solved, tmp_path, command, poison):
    """Every reader of a saved run reads it through one checked loader (read_results):
    whole files with values their run.json cannot have are refused in one line naming the
    file, never drawn, replayed or compared; a claimed head is compared with the arrays
    before any work that grows with it (10^10 bristles: refused at once)."""
    run = _copy(solved, tmp_path)
    file, damage, reason = POISONED[poison]
    shutil.copy(run / "forces.csv", tmp_path / "measured.csv")
    damage(run / file)
    args = {"frames": ["frames", run, "--gif-frames", "0", "--out", tmp_path / "frames"],
            "view": ["view", run, "--write-only"],
            "compare": ["compare", run, tmp_path / "measured.csv", "--out",
                        tmp_path / "compare"]}[command]
    named = str(run / ("shapes.npz" if file == "run.json" else file))
    assert reason in _refused(args, named)
    assert not (run / "exudyn-solution.txt").exists()
    assert not (tmp_path / "frames").exists() and not (tmp_path / "compare").exists()


def test_view_checks_the_coordinates_against_the_head_before_it_writes(solved, tmp_path):
    """Coordinates of another head (a column more: 1 + 6 + 2 x 14 is the run's) are refused
    before the solution file is written: a refused run gets no exudyn-solution.txt."""
    run = _copy(solved, tmp_path)
    _rewritten(run / "shapes.npz", _set("coordinates", lambda a: np.hstack([a, a[:, -1:]])))
    message = _refused(["view", run, "--write-only"], str(run / "shapes.npz"))
    assert "node coordinates (15, 36) are not rows of 35 coordinates" in message
    assert not (run / "exudyn-solution.txt").exists()


@pytest.mark.parametrize("status", ["completed", "failed"])
def test_coordinates_a_row_short_are_a_stopped_runs_not_a_completed_ones(solved, tmp_path,
                                                                          status):
    """A run that stopped early keeps the coordinate rows of its shortest group, which may
    end a shape sample before its shapes; a completed run has a row at every sample."""
    from exubrush.output.results import ResultsError, read_results

    run = _copy(solved, tmp_path)
    record = json.loads((run / "run.json").read_text())
    (run / "run.json").write_text(json.dumps({**record, "status": status}))
    _rewritten(run / "shapes.npz", _set("coordinates", lambda a: a[:-1]))
    if status == "completed":
        with pytest.raises(ResultsError, match=r"coordinates \(14, 35\) are not rows"):
            read_results(run)
    else:
        assert len(read_results(run).shape_coordinates) == 14


def test_a_prb_run_json_without_its_gamma_is_refused_by_frames(solved, tmp_path):
    run = _copy(solved, tmp_path)
    meta = json.loads((run / "run.json").read_text())
    (run / "run.json").write_text(json.dumps({**meta, "model": "prb", "derived": []}))
    _refused(["frames", run, "--gif-frames", "0"], str(run / "run.json"))


def test_the_intact_checkpoint_resumes(solved, tmp_path):
    run = _copy(solved, tmp_path, "resumable")
    done = CliRunner().invoke(main, [*RUN, "--out", str(run)])
    assert done.exit_code == 0, done.output
    assert "resuming: 2 finished bristle groups" in done.output


@pytest.mark.parametrize(("file", "damage"), [
    ("group-00000.npz", "cut short"),
    ("group-00001.npz", "foreign"),
    ("group-00000.npz", "not a zip"),
    ("code.json", "not JSON"),
    ("code.json", "a JSON list"),
    ("fingerprint", "garbage"),
])
def test_a_damaged_checkpoint_is_named_in_one_line_with_exit_2(solved, tmp_path, file,
                                                               damage):
    run = _copy(solved, tmp_path, "resumable")
    checkpoint = run / ".checkpoint"
    if damage == "foreign":  # the result files of the run in its place
        shutil.copy(solved / "saved" / "shapes.npz", checkpoint / file)
    else:
        DAMAGES[damage](checkpoint / file)
    message = _refused([*RUN, "--out", run], str(checkpoint / file))
    assert "--overwrite" in message
    assert not (run / "run.json").exists()


def _rewritten(path, change):
    """The .npz file ``path`` written again with its arrays as ``change(arrays)`` makes them
    (a file whose zip and headers are whole, only its values poisoned)."""
    with np.load(path) as archive:
        arrays = {name: archive[name] for name in archive.files}
    change(arrays)
    with open(path, "wb") as handle:
        np.savez(handle, **arrays)


def _scalars(arrays, **values):
    arrays["scalars"] = np.array(json.dumps({**json.loads(str(arrays["scalars"])), **values}))


def _set(name, value):
    def change(arrays):
        arrays[name] = value(arrays[name]) if callable(value) else arrays[name] * 0 + value
    return change


POISONS = {  # what a fresh solve never keeps, each refused on resume: (damage, the reason)
    "NaN reaction": (_set("reaction", np.nan), "'reaction' holds a value that is not finite"),
    "infinite tip": (_set("tips", np.inf), "'tips' holds a value that is not finite"),
    "NaN coordinate": (_set("coordinates", np.nan), "'coordinates' holds a value"),
    # the bound of two bristles of the 1 x 2 head: ~2 N
    "force beyond the bound": (_set("reaction", 1e3), "normal force 1000 N at t = 0 s"),
    "complex nodes": (_set("nodes", lambda a: a.astype(complex)), "complex128"),
    "single-precision nodes": (_set("nodes", lambda a: a.astype(np.float32)), "float32"),
    "boolean tip forces": (_set("tip_force", lambda a: a != 0), "bool"),
    "not finished": (lambda arrays: _scalars(arrays, completed=False),
                     "says its solve did not finish"),
    "times backwards": (_set("time", lambda a: a[::-1].copy()), "times are not those"),
    "times shifted": (_set("time", lambda a: a + 0.005), "times are not those"),
    "ends early": (lambda arrays: arrays.update(  # 145 -> 125 times, 15 -> 13 shapes
        {name: arrays[name][:-20] for name in ("time", "reaction", "tips", "tip_force",
                                               "drive_moment")},
        nodes=arrays["nodes"][:13], coordinates=arrays["coordinates"][:13]),
        "times are not those"),
    "a node fewer": (_set("nodes", lambda a: a[:, :, :-1]), "bristles of 2 nodes"),
    "tips of 1e300 mm": (_set("tips", 1e300), "'tips' holds a value beyond 1e+20"),
    "coordinates without rows": (_set("coordinates", lambda a: a[:0]),
                                 "coordinates (0, 21) are not a row of 21"),
    "a coordinate more": (_set("coordinates", lambda a: np.hstack([a, a[:, -1:]])),
                          "coordinates (15, 22) are not a row of 21"),
    "no coordinates": (lambda arrays: arrays.pop("coordinates"),
                       "lacks the node coordinates its run keeps"),
    "NaN handle mass": (lambda arrays: _scalars(arrays, handle_mass=float("nan")),
                        "'scalars' are not those of a finished group"),
    "negative handle mass": (lambda arrays: _scalars(arrays, handle_mass=-1e-6),
                             "'scalars' are not those of a finished group"),
    "infinite inertia": (lambda arrays: _scalars(arrays, handle_inertia=[[float("inf")] * 3] * 3),
                         "'scalars' are not those of a finished group"),
    "negative step count": (lambda arrays: _scalars(arrays, statistics={
        **json.loads(str(arrays["scalars"]))["statistics"], "steps": -1}),
        "'scalars' are not those of a finished group"),
}


@pytest.mark.parametrize("poison", POISONS)
def test_a_checkpoint_group_a_fresh_solve_would_not_keep_is_refused(solved, tmp_path, poison):
    """A group file read back passes the checks a fresh solve's group passes before it is
    kept (finite, finished, within the physical bound); else the run stops before solving
    anything and names the file (deleting it solves that group again)."""
    run = _copy(solved, tmp_path, "resumable")
    group = run / ".checkpoint" / "group-00001.npz"
    damage, reason = POISONS[poison]
    _rewritten(group, damage)
    message = _refused([*RUN, "--out", run], str(group))
    assert reason in message
    assert "delete that file to solve its bristle group again" in message
    assert not (run / "run.json").exists()


def test_a_run_over_results_with_a_damaged_run_json_names_it(solved, tmp_path):
    run = _copy(solved, tmp_path)
    DAMAGES["not JSON"](run / "run.json")
    message = _refused([*RUN, "--out", run], f"{run / 'run.json'} cannot be read")
    assert "--overwrite" in message


def test_a_checkpoint_file_of_no_group_is_refused(solved, tmp_path):
    run = _copy(solved, tmp_path, "resumable")
    shutil.copy(run / ".checkpoint" / "group-00000.npz", run / ".checkpoint" / "group-00007.npz")
    _refused([*RUN, "--out", run], "group-00007.npz' is not a group of this run")


@pytest.mark.parametrize(("file", "damage"), [
    ("shapes.npz", "cut short"), ("forces.csv", "garbage"), ("run.json", "not JSON")])
def test_a_resumed_sweep_names_a_damaged_finished_run_before_it_starts(solved, tmp_path,
                                                                       file, damage):
    from exubrush.sweep.plan import read_sweep
    from exubrush.sweep.runner import check_folder, claim_folder, prepare_runs

    sweep_file = tmp_path / "one.toml"
    sweep_file.write_text(SWEEP)
    plan = read_sweep(sweep_file)
    prepared = prepare_runs(plan)
    folder = tmp_path / "sweep"
    claim_folder(folder, plan, prepared)
    run = shutil.copytree(solved / "saved", folder / plan.runs[0].name)
    check_folder(folder, plan, prepared)  # intact: accepted
    DAMAGES[damage](run / file)
    # refused before a cluster is started: 'local' would take seconds
    message = _refused(["sweep", sweep_file, "--out", folder, "--quiet"], str(run / file))
    assert f"delete {run} and run the sweep again" in message


def test_a_resumed_sweep_says_how_to_solve_a_run_with_a_poisoned_group_anew(solved,
                                                                            tmp_path):
    """A sweep has no --overwrite: a refused checkpoint of one of its runs says to delete
    that run's folder."""
    from exubrush.execution.local import SerialExecutor
    from exubrush.output.rundir import RunDirectoryError
    from exubrush.sweep.plan import read_sweep
    from exubrush.sweep.runner import claim_folder, prepare_runs, run_sweep

    sweep_file = tmp_path / "one.toml"
    sweep_file.write_text(SWEEP.replace('"head.columns=2"]', '"head.columns=2", ' + ", ".join(
        f'"{o}"' for o in OVERRIDES[:3]) + "]"))
    plan = read_sweep(sweep_file)
    folder = tmp_path / "sweep"
    claim_folder(folder, plan, prepare_runs(plan))
    run = folder / plan.runs[0].name
    shutil.copytree(solved / "resumable", run)  # the same case: its checkpoint resumes
    _rewritten(run / ".checkpoint" / "group-00000.npz", _set("reaction", np.nan))
    with pytest.raises(RunDirectoryError) as refused:
        run_sweep(plan, folder, SerialExecutor(), progress=False)
    assert f"delete {run} to solve that run anew" in str(refused.value)
    assert "--overwrite" not in str(refused.value)


POSE = "time [s],z [mm]\n0,0\n0.5,{lift}\n10,{lift}\n"
POSE_SWEEP = """
[sweep]
name = "posed"
base = "posed.toml"
[grid]
"head.seed" = [1, 2]
"""


def test_a_sweep_whose_pose_csv_changed_since_is_refused_naming_it(tmp_path):
    """A sweep's identity holds the content of every file its runs read (each run's as a
    single run's resume knows it): run again after its pose CSV changed, it is refused
    before anything is solved, not reported as done with the old file's results. A file
    rewritten with the same data (a comment added) is the same input."""
    from exubrush.execution.local import SerialExecutor
    from exubrush.parameters.fields import to_toml
    from exubrush.parameters.io import load_case
    from exubrush.sweep.plan import read_sweep
    from exubrush.sweep.runner import check_folder, prepare_runs, run_sweep

    pose = tmp_path / "pose.csv"
    pose.write_text(POSE.format(lift="0.01"))
    case = load_case("orthogonal", [*OVERRIDES[:2], "head.rows=1", "head.columns=1",
                                    f"motion.pose_csv={str(pose)!r}"])
    (tmp_path / "posed.toml").write_text(to_toml(case))
    sweep_file = tmp_path / "sweep.toml"
    sweep_file.write_text(POSE_SWEEP)
    folder = tmp_path / "out"
    outcome = run_sweep(read_sweep(sweep_file), folder, SerialExecutor(), progress=False)
    assert outcome.counts["completed"] == 2
    forces = (folder / "000-seed=1" / "forces.csv").read_bytes()
    pose.write_text(f"# the same table\n{POSE.format(lift='0.01')}")
    plan = read_sweep(sweep_file)
    check_folder(folder, plan, prepare_runs(plan))  # the same data: resumed
    pose.write_text(POSE.format(lift="0.02"))
    message = _refused(["sweep", sweep_file, "--out", folder, "--quiet"],
                       "a file its runs read, was changed since")
    assert "motion.pose_csv of run 000-seed=1 has other content" in message
    assert (folder / "000-seed=1" / "forces.csv").read_bytes() == forces  # not touched


# Property tests: any damage to a saved file ends in the file read or one clean error line


damages = st.one_of(
    st.tuples(st.just("cut"), st.floats(0.0, 1.0)),
    st.tuples(st.just("flip"), st.floats(0.0, 1.0), st.integers(0, 7)),
    st.tuples(st.just("overwrite"), st.floats(0.0, 1.0), st.binary(min_size=1, max_size=64)),
    st.tuples(st.just("random"), st.binary(max_size=2000)),
)


def _damaged(data: bytes, damage) -> bytes:
    """``data`` cut short, a bit flipped, a stretch overwritten, or replaced whole."""
    kind, *what = damage
    if kind == "random":
        return what[0]
    at = min(int(what[0] * len(data)), len(data) - 1)
    if kind == "cut":
        return data[:at]
    if kind == "flip":
        return data[:at] + bytes([data[at] ^ (1 << what[1])]) + data[at + 1:]
    return data[:at] + what[1] + data[at + len(what[1]):]


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(name=st.sampled_from(["run.json", "forces.csv", "shapes.npz", "tips.npz"]),
       damage=damages)
def test_any_damaged_result_file_is_read_or_refused_in_one_line(solved, tmp_path, name,
                                                                damage):
    from exubrush.output.frames import load_shapes
    from exubrush.output.results import ResultsError, read_results
    from exubrush.output.viewer import prepare

    run = tmp_path / "run"
    shutil.rmtree(run, ignore_errors=True)
    shutil.copytree(solved / "saved", run)
    (run / name).write_bytes(_damaged((run / name).read_bytes(), damage))
    try:
        read_results(run)
        load_shapes(run)  # exubrush frames
        prepare(run)  # exubrush view, up to its solution file
    except ResultsError as err:
        assert "\n" not in str(err) and name in str(err), err


@pytest.fixture(scope="module")
def prepared_case():
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare

    return prepare(load_case("orthogonal", OVERRIDES))


@settings(max_examples=30, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(name=st.sampled_from(["group-00000.npz", "group-00001.npz"]), damage=damages)
def test_any_damaged_checkpoint_group_is_read_or_refused_in_one_line(
        solved, prepared_case, tmp_path, name, damage):
    from exubrush.output.rundir import RunDirectory, RunDirectoryError

    run = tmp_path / "resumable"
    shutil.rmtree(run, ignore_errors=True)
    shutil.copytree(solved / "resumable", run)
    path = run / ".checkpoint" / name
    path.write_bytes(_damaged(path.read_bytes(), damage))
    try:
        RunDirectory(run, prepared_case)
    except RunDirectoryError as err:
        assert "\n" not in str(err) and name in str(err), err


# Property tests: whole files with poisoned values (the zip and headers intact)


ARRAYS = {"shapes.npz": ("time", "nodes", "coordinates"), "tips.npz": ("position", "force"),
          "group-00000.npz": ("time", "reaction", "tips", "nodes", "tip_force", "coordinates",
                              "drive_moment")}
poisons = st.one_of(
    st.tuples(st.just("value"), st.sampled_from([np.nan, np.inf, -np.inf, 1e300, -3e20])),
    st.tuples(st.just("type"), st.sampled_from([complex, bool, np.float16, np.int8])),
    st.tuples(st.just("cut"), st.integers(0, 3), st.integers(0, 2)),
)


def _poisoned(array: np.ndarray, poison, at: float) -> np.ndarray:
    """``array`` with one value set, its type changed, or an axis cut to ``keep`` entries."""
    kind, *what = poison
    if kind == "value":
        flat = array.astype(float).ravel()
        flat[min(int(at * flat.size), flat.size - 1)] = what[0]
        return flat.reshape(array.shape)
    if kind == "type":
        return array.astype(what[0])
    axis = min(what[0], array.ndim - 1)
    return np.take(array, range(min(what[1], array.shape[axis])), axis=axis)


@settings(max_examples=60, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(file=st.sampled_from(sorted(ARRAYS)), data=st.data())
def test_any_poisoned_array_is_refused_in_one_line_or_changes_nothing(
        solved, prepared_case, tmp_path, file, data):
    """An array of a saved run or a checkpoint group with one value NaN, infinite or beyond
    1e20, of another type, or with an axis cut: every reader (read_results, frames, view,
    a resume) refuses it in one line naming the file, or reads what was written (a cast
    that changes nothing)."""
    from exubrush.output.frames import load_shapes
    from exubrush.output.results import ResultsError, read_results
    from exubrush.output.rundir import RunDirectory, RunDirectoryError
    from exubrush.output.viewer import prepare

    name = data.draw(st.sampled_from(ARRAYS[file]))
    poison, at = data.draw(poisons), data.draw(st.floats(0.0, 1.0))
    which = "resumable" if file.startswith("group") else "saved"
    run = tmp_path / which
    shutil.rmtree(run, ignore_errors=True)
    shutil.copytree(solved / which, run)
    path = run / ".checkpoint" / file if which == "resumable" else run / file
    with np.load(path) as archive:
        original = archive[name]
    _rewritten(path, lambda arrays: arrays.update({name: _poisoned(original, poison, at)}))
    with np.load(path) as archive:
        unchanged = (archive[name].shape == original.shape
                     and np.array_equal(archive[name].astype(complex), original))
    try:
        if which == "resumable":
            RunDirectory(run, prepared_case)
        else:
            read_results(run)
            load_shapes(run)
            prepare(run)
    except (ResultsError, RunDirectoryError) as err:
        assert "\n" not in str(err) and str(path) in str(err), err
    else:
        assert unchanged, f"{file} {name} {poison} read without a word"
