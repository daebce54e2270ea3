"""Hostile input, refused before anything is built: each case ends in one ParameterError
line with the exact message, the way the command line reads input (load_case, then
prepare). Grouped as the faults are: work that must be bounded, numbers and text that break
conversion, files that are not what they claim, settings that would give a silently wrong
answer. The command-line side (exit codes, file system, nothing written outside the output
directory) is tests/integration/test_hostile_cli.py.
"""

import os

import numpy as np
import pytest

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.world.slide import TabulatedSlide

SLIDE = "time [s],slider_position [mm]\n0,0\n1,5\n2,0\n"

BOUNDED_WORK = [
    (["motion.periods=1e9"], "the run needs at least 6,000,000,000,600 time steps per "
     "system (end time / solver.step_size), more than Exudyn can count (2,147,483,647); "
     "shorten the run or take a longer step"),
    (["motion.periods=1e5"], "the run needs at least 600,000,600 time steps per system (end "
     "time / solver.step_size), more than limits.steps = 20,000,000; to run it anyway, "
     "--set limits.steps=600000600"),
    (["head.rows=100000", "head.columns=100000"], "the head has 10,000,000,000 bristles, "
     "more than limits.bristles = 10,000; to run it anyway, --set limits.bristles=10000000000"),
    (["model.segments=5000"], "model.segments = 5,000 is more than limits.segments = 200; "
     "to run it anyway, --set limits.segments=5000"),
    # 48 bristles' tips (position and force) at 25.2e6 rows: 2 x 25.2e6 x 48 x 3 doubles,
    # three copies
    (["output.interval='1e-6 s'"], "its recorded results would take about 174 GB, more than "
     "limits.memory = 8 GB; a longer output.interval records less, or --set "
     "limits.memory='175 GB'"),
    (["solver.step_size='1e-9 s'", "solver.minimum_step_size='1e-10 s'"],
     "the run needs at least 25,200,000,000 time steps per system"),
    (["head.rows=3000000000"], "head.rows: 3000000000 does not fit a 32-bit integer "
     "(at most 2147483647)"),
    (["limits.steps=99999999999"], "limits.steps: 99999999999 does not fit a 32-bit integer"),
    (["model.segments=-5"], "model.segments: -5 must be > 0"),
]

CONVERSION = [
    (["head.bristle.length='1e308 mm'"], "head.bristle.length: 1e308 mm is outside the "
     "magnitudes exubrush computes with (1e-20 to 1e+20 mm)"),
    (["head.bristle.length='1e-30 mm'"], "head.bristle.length: 1e-30 mm is outside the "
     "magnitudes exubrush computes with"),
    (["head.bristle.length='1e308 km'"], "head.bristle.length: '1e308 km' is not a finite "
     "number"),
    (["contact.stiffness='1e25 N/mm^1.3'"], "contact.stiffness: 1e25 N/mm^1.3 is outside the "
     "magnitudes"),
    (["solver.relative_tolerance=1e-30"], "solver.relative_tolerance: 1e-30 is outside the "
     "magnitudes exubrush computes with (1e-20 to 1e+20)"),
    (["solver.relative_tolerance=10**12"], "solver.relative_tolerance: 10**12 must be < 1"),
    (["solver.touching_relative_tolerance=1"],
     "solver.touching_relative_tolerance: 1 must be < 1"),
    (["motion.amplitude='inf mm'"], "motion.amplitude: 'inf mm' is not a finite number"),
    (["name='" + "n" * 101 + "'"], "must be 1 to 100 printable characters"),
    (["name=''"], "name '' must be 1 to 100 printable characters"),
    (['name="tab\\there"'], "name 'tab\\there' must be 1 to 100 printable characters"),
    (["limits.memory='8 GHz'"], "limits.memory: '8 GHz' has unit 'GHz', which cannot be "
     "converted to 'B'"),
]

SILENTLY_WRONG = [
    (["solver.step_size='20 s'"], "solver.step_size 20 s does not resolve the motion: 20 "
     "steps per approach (motion.approach_duration) need a step of at most 50 ms"),
    (["solver.step_size='200 ms'", "motion.approach_duration='10 s'",
      "motion.hold_duration='1 s'"], "solver.step_size 200 ms does not resolve the motion: "
     "100 steps per slide period (motion.period) need a step of at most 120 ms"),
    (["motion.hold_duration='4 ms'"], "solver.step_size 2 ms does not resolve the motion: 4 "
     "steps per hold (motion.hold_duration) need a step of at most 1 ms"),
    (["output.interval='20 s'", "output.shape_interval='20 s'"], "output.interval 20 s is "
     "more than half the run (25.2 s): it would record only the start; use at most 12.6 s"),
    (["motion.periods=0.01", "output.shape_interval='1 s'"], "output.shape_interval 1 s is "
     "more than half the run (1.32 s)"),
]


@pytest.mark.parametrize("overrides, message", BOUNDED_WORK + CONVERSION + SILENTLY_WRONG)
def test_refused_with_its_message(overrides, message):
    with pytest.raises(ParameterError) as info:
        prepare(load_case("orthogonal", overrides))
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_a_raised_limit_lets_the_run_through():
    prepared = prepare(load_case("orthogonal", ["model.segments=300", "limits.segments=300"]))
    assert prepared.work.steps == 12600  # 25.2 s at 2 ms


def _csv_case(tmp_path, content: bytes | None, overrides=()):
    path = tmp_path / "slide.csv"
    if content is not None:
        path.write_bytes(content)
    return prepare(load_case("orthogonal", ["motion.profile='csv'",
                                            f"motion.csv_file='{path}'", *overrides]))


@pytest.mark.parametrize("content, message", [
    (b"\xff\xfe\x00t\x00i\x00m\x00e", "is not UTF-8 text (byte 0)"),
    (b"time [s],slider_position [mm]\n0,0\n1,\xe9\n", "is not UTF-8 text"),
    (b"time [s],slider_position [mm]\n0,0\n0.05,5\n0.1,0\n", "solver.step_size 2 ms does not "
     "resolve the motion: 100 steps over the slide CSV's duration need a step of at most "
     "1 ms"),
    # beyond what a brush head can do (exubrush.world.slide.TABLE_REACH, TABLE_RATE): a
    # solver failure (exit 1) before, not a refusal of the input
    (b"time [s],slider_position [mm]\n0,0\n1,1e300\n2,0\n", "'slider_position' is 1e+300 mm "
     "from its first row at sample 2 (t = 1 s), beyond the 10000 mm a brush head can move"),
    (b"time [s],slider_position [mm]\n0,0\n1e-6,1\n12,1\n", "'slider_position' changes at "
     "up to"),
    (b"\xef\xbb\xbftime [s],slider_position [mm]\n0,0\n6,15\n12,0\n1,2,3\n",
     "line 5 has 3 cells for 2 columns"),  # the byte-order mark is read, the row is not
])
def test_a_hostile_slide_csv_is_refused(tmp_path, content, message):
    with pytest.raises(ParameterError, match="motion.csv_file|step_size") as info:
        _csv_case(tmp_path, content)
    assert message in str(info.value)


def test_a_slide_csv_that_is_a_directory_or_a_dangling_link(tmp_path):
    (tmp_path / "slide.csv").mkdir()
    with pytest.raises(ParameterError, match="slide.csv' is not a file"):
        _csv_case(tmp_path, None)
    link = tmp_path / "gone"
    link.mkdir()
    os.symlink(tmp_path / "nowhere.csv", link / "slide.csv")
    with pytest.raises(ParameterError, match=r"does not exist \(a link to nothing\)"):
        _csv_case(link, None)


@pytest.mark.parametrize("content, message", [
    (b"name = \"a\\u0000b\"\n", "name 'a\\x00b' must be 1 to 100 printable characters"),
    (b"name = \"caf\xe9\"\n", "not UTF-8 text (byte 11); case files are TOML, which is UTF-8"),
    (b"[head]\nrows = 4294967296\n", "head.rows: 4294967296 does not fit a 32-bit integer"),
    (b"[solver]\nuser_functions = \"builtin\"\n", "solver.user_functions: renamed "
     "contact.backend"),
])
def test_a_hostile_case_file_is_refused(tmp_path, content, message):
    path = tmp_path / "case.toml"
    path.write_bytes(content)
    with pytest.raises(ParameterError) as info:
        prepare(load_case(str(path)))
    assert message in str(info.value)


def test_a_case_file_with_a_byte_order_mark_is_read(tmp_path):
    path = tmp_path / "case.toml"
    path.write_bytes(b"\xef\xbb\xbf[head]\nrows = 1\ncolumns = 3\n")
    assert load_case(str(path)).head.count == 3


def test_a_case_file_that_is_a_directory(tmp_path):
    (tmp_path / "case.toml").mkdir()
    with pytest.raises(ParameterError, match="case.toml' is not a file"):
        load_case(str(tmp_path / "case.toml"))


def test_a_stepped_slide_never_leaves_the_range_of_its_data():
    # 0 -> 10 mm in one sample interval, then a ramp with a corner: a C² spline overshot
    # the step by about 11 %; the monotone interpolant stays inside every interval's data
    times = np.array([0.0, 1.0, 1.1, 2.0, 3.0, 3.5, 4.0])
    positions = np.array([0.0, 0.0, 10.0, 10.0, 4.0, 4.0, 9.0])
    slide = TabulatedSlide(times, positions)
    for left, right in zip(range(len(times) - 1), range(1, len(times)), strict=True):
        dense = np.linspace(times[left], times[right], 201)
        values = np.array([slide.evaluate(t)[0] for t in dense])
        low, high = sorted((positions[left], positions[right]))
        assert np.all(values >= low - 1e-12) and np.all(values <= high + 1e-12)


def test_a_changed_slide_csv_is_never_resumed_into(tmp_path):
    from exubrush.output.rundir import RunDirectory, RunDirectoryError

    first = _csv_case(tmp_path, SLIDE.encode())
    RunDirectory(tmp_path / "run", first)
    again = _csv_case(tmp_path, SLIDE.encode())
    assert RunDirectory(tmp_path / "run", again).resumed == 0  # same content: resumes
    changed = _csv_case(tmp_path, SLIDE.replace("1,5", "1,6").encode())
    with pytest.raises(RunDirectoryError, match="a changed slide CSV"):
        RunDirectory(tmp_path / "run", changed)
    # the limits change no result: a run that only raises one resumes
    raised = _csv_case(tmp_path, SLIDE.encode(), ["limits.bristles=20000"])
    RunDirectory(tmp_path / "run", raised)


def test_a_slide_csv_faster_than_the_step_is_warned_about(tmp_path):
    jump = b"time [s],slider_position [mm]\n0,0\n1,0\n1.1,10\n2,10\n"
    warnings = _csv_case(tmp_path, jump).warnings
    assert len(warnings) == 1
    assert "more than contact.static_velocity = 1.2 mm/s; the solver will cut" in warnings[0]
    assert _csv_case(tmp_path, SLIDE.encode()).warnings == ()  # 5 mm/s², well resolved


def test_a_finely_sampled_smooth_slide_is_not_warned_about(tmp_path):
    # 10 kHz samples of the orthogonal sine, positions to 0.01 µm as an encoder gives them:
    # the steps of that resolution make the monotone cubic's acceleration spike to
    # 6000 mm/s² inside single 0.1 ms intervals (peak acceleration x step = 12 mm/s would
    # warn), but within any 2 ms step the speed changes by 0.1 mm/s (measured), below
    # contact.static_velocity = 1.2 mm/s
    t = np.arange(0.0, 12.0, 1e-4)
    rows = "".join(f"{a:.4f},{15 * np.sin(np.pi * a / 6):.5f}\n" for a in t)
    smooth = ("time [s],slider_position [mm]\n" + rows).encode()
    assert _csv_case(tmp_path, smooth).warnings == ()
