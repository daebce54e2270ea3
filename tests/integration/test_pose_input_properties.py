"""Property-based tests (hypothesis) of the head's pose inputs: sine terms and pose tables
of random units, values and damage. Each is either read to the value worked out by hand
from the units' definitions (not from pint: 1 in = 25.4 mm, 1 rpm = 1/60 Hz, 1 rad/s =
1/(2π) Hz...) or refused with one line (ParameterError, ValueError); a few damaged ones go
through the command line, which must exit with status 2 and one line.
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from exubrush.parameters.case import Motion
from exubrush.parameters.fields import ParameterError, build
from exubrush.world.pose import AXES, read_pose_csv

# unit -> internal units per unit, by hand
LENGTHS = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "um": 1e-3, "in": 25.4, "ft": 304.8}
ANGLES = {"rad": 1.0, "deg": math.pi / 180.0, "turn": 2.0 * math.pi,
          "arcmin": math.pi / 10800.0, "mrad": 1e-3}
TIMES = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "min": 60.0}
FREQUENCIES = {"Hz": 1.0, "kHz": 1e3, "1/min": 1.0 / 60.0, "rpm": 1.0 / 60.0, "rps": 1.0,
               "rad/s": 1.0 / (2.0 * math.pi), "deg/s": 1.0 / 360.0}
KINDS = {"length": LENGTHS, "angle": ANGLES, "time": TIMES, "frequency": FREQUENCIES}
# units of some other dimension, or none, for each kind: every one must be refused
WRONG = {"length": ["N", "s", "deg", "1", "%", "Hz"],
         "angle": ["1", "%", "mm", "Hz", "rad/s", "sr"],
         "time": ["mm", "Hz", "deg", "1"],
         "frequency": ["s", "deg", "mm", "1", "rad"]}
# a conversion by pint: its factor composed from a few definitions, a few roundings
RELATIVE = 1e-14

# each sine field: its kind and the range of its internal value that the case accepts
SINE_FIELDS = {"amplitude": ("length", 1e-3, 10.0), "angle": ("angle", 1e-2, 3.0),
               "frequency": ("frequency", 1.0, 1000.0), "phase": ("angle", -6.0, 6.0),
               "start": ("time", 0.0, 1.0)}


@st.composite
def quantity(draw, kind: str, low: float, high: float):
    """(text, value [internal unit] by hand) of a value in [low, high] written in a random
    unit of ``kind``."""
    unit, factor = draw(st.sampled_from(sorted(KINDS[kind].items())))
    # to nine decimals: a value of 1e-200 is refused as out of exubrush's magnitudes
    internal = draw(st.floats(low, high).map(lambda x: round(x, 9)))
    written = internal / factor
    return f"{written!r} {unit}", written * factor


@st.composite
def damage(draw, kind: str):
    """A value of ``kind`` that must be refused: a bare number (text or TOML number), a
    unit of another dimension, a number that is not finite, or no number at all."""
    number = draw(st.floats(0.1, 100.0))
    return draw(st.sampled_from([
        f"{number!r}", number, f"{number!r} {draw(st.sampled_from(WRONG[kind]))}",
        f"{draw(st.sampled_from(['nan', 'inf', '-inf', '1e999']))} "
        f"{draw(st.sampled_from(sorted(KINDS[kind])))}",
        draw(st.sampled_from(["", "deg", "fast", "12 furlongs per", "1/0 Hz"])),
    ]))


@st.composite
def sine_entries(draw):
    """(entry, expected internal values or None if damaged) of one [[motion.sine]] entry."""
    axis = draw(st.sampled_from(AXES))
    size = "angle" if axis.startswith("r") else "amplitude"
    entry, expected = {"axis": axis, "ramp_cycles": 0}, {}
    for name in (size, "frequency", "phase", "start"):
        if name in ("phase", "start") and draw(st.booleans()):
            continue  # the default
        entry[name], expected[name] = draw(quantity(*SINE_FIELDS[name]))
    broken = draw(st.sampled_from([None, None, size, "frequency", "phase", "start",
                                   "ramp_cycles"]))
    if broken == "ramp_cycles":  # a count: an angle is no number
        entry[broken] = draw(st.sampled_from(["2 rad", "1 turn", "3 deg"]))
    elif broken is not None:
        entry[broken] = draw(damage(SINE_FIELDS[broken][0]))
    return entry, None if broken else expected


@settings(max_examples=300, deadline=None)
@given(entries=st.lists(sine_entries(), min_size=1, max_size=3))
def test_a_sine_term_is_read_as_written_or_refused_in_one_line(entries):
    data = {"sine": [entry for entry, _ in entries]}
    if any(expected is None for _, expected in entries):
        with pytest.raises(ParameterError) as caught:
            build(Motion, data, "motion.")
        assert str(caught.value).startswith("motion.sine[")
        assert "\n" not in str(caught.value)
        return
    motion = build(Motion, data, "motion.")
    for term, (_, expected) in zip(motion.sine, entries, strict=True):
        for name, value in expected.items():
            assert getattr(term, name) == pytest.approx(value, rel=RELATIVE, abs=0), name


TABLE_DAMAGE = ["none", "no unit", "number unit", "wrong unit", "twice", "cell", "huge",
                "backwards"]


@st.composite
def pose_tables(draw):
    """(CSV text, expected {axis: values [internal]} or None if damaged, time factor)."""
    rows = draw(st.integers(2, 6))
    time_unit, time_factor = draw(st.sampled_from(sorted(TIMES.items())))
    # at least 10 ms between rows, values within 100 mm and 3 rad: well inside the
    # speeds and reaches a brush head is held to (exubrush.world.slide.TABLE_RATE)
    steps = draw(st.lists(st.floats(0.01, 1.0), min_size=rows - 1, max_size=rows - 1))
    times = np.concatenate([[0.0], np.cumsum(steps)]) / time_factor
    axes = draw(st.lists(st.sampled_from(AXES), min_size=1, max_size=3, unique=True))
    header, columns, expected = [f"time [{time_unit}]"], [times], {}
    for axis in axes:
        kind, bound = ("angle", 3.0) if axis.startswith("r") else ("length", 100.0)
        unit, factor = draw(st.sampled_from(sorted(KINDS[kind].items())))
        values = np.array(draw(st.lists(st.floats(-bound, bound), min_size=rows,
                                        max_size=rows))) / factor
        header.append(f"{axis} [{unit}]")
        columns.append(values)
        expected[axis] = (values - values[0]) * factor
    broken = draw(st.sampled_from(TABLE_DAMAGE[:1] * 4 + TABLE_DAMAGE[1:]))
    column = draw(st.integers(1, len(header) - 1))
    label = header[column].split(" [")[0]
    if broken == "no unit":
        header[column] = label
    elif broken == "number unit":
        header[column] = f"{label} [{draw(st.sampled_from(['1', '%', '']))}]"
    elif broken == "wrong unit":
        kind = "angle" if label.startswith("r") else "length"
        header[column] = f"{label} [{draw(st.sampled_from(WRONG[kind][:4]))}]"
    elif broken == "twice":
        header.append(f"{label} [{draw(st.sampled_from(['mm', 'deg', 'cm', 'rad']))}]")
        columns.append(columns[column])
    cells = [[repr(float(value)) for value in row] for row in np.column_stack(columns)]
    row = draw(st.integers(1, rows - 1))
    if broken == "cell":
        cells[row][column] = draw(st.sampled_from(["nan", "inf", "x", "", "1,5"]))
    elif broken == "huge":
        cells[row][column] = draw(st.sampled_from(["1e300", "-1e300", "1e20", "1e308"]))
    elif broken == "backwards":
        cells[row][0] = cells[row - 1][0]
    bom = draw(st.sampled_from(["", "\ufeff"]))  # a spreadsheet's byte-order mark: read
    comment = draw(st.sampled_from(["", "# measured\n"]))
    text = bom + comment + ",".join(header) + "\n" + "".join(
        ",".join(line) + "\n" for line in cells)
    return text, (None if broken != "none" else expected), time_factor, times


@settings(max_examples=300, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(table=pose_tables(), start=st.floats(0.0, 2.0))
def test_a_pose_table_is_read_as_written_or_refused_in_one_line(tmp_path, table, start):
    text, expected, time_factor, times = table
    path = tmp_path / "pose.csv"
    path.write_text(text, encoding="utf-8")
    if expected is None:
        with pytest.raises(ValueError) as caught:
            read_pose_csv(path, start)
        assert str(caught.value).startswith(f"pose CSV '{path}'")
        assert "\n" not in str(caught.value)
        return
    term = read_pose_csv(path, start)
    elapsed = (times - times[0]) * time_factor  # by hand, in s
    assert term.end_time == pytest.approx(start + elapsed[-1], rel=RELATIVE)
    for k, tau in enumerate(elapsed):
        pose = term.evaluate(start + tau)[0]
        for axis, values in expected.items():
            # at a row's time, up to the rounding of that time times the slope (< 1e5 mm/s
            # or rad/s) and of the unit's factor
            assert pose[AXES.index(axis)] == pytest.approx(values[k], rel=1e-12, abs=1e-9)


# A few damaged inputs at the command line: exit status 2 and one line, nothing solved.
CLI_DAMAGE = [
    ('[[motion.sine]]\naxis = "rz"\nangle = "5 deg"\nfrequency = "50 Hz"\nphase = "90"\n',
     None, "motion.sine[0].phase: '90' has no unit; write it with one, e.g. '90 deg' or "
           "'90 rad'"),
    ('[[motion.sine]]\naxis = "ry"\nangle = "0.5"\nfrequency = "7600 rpm"\n', None,
     "motion.sine[0].angle: '0.5' has no unit"),
    ('pose_csv = "pose.csv"\n', "time [s],rz [1]\n0,0\n1,0.5\n",
     "column 'rz [1]' has no unit of 'rad'"),
    ('pose_csv = "pose.csv"\n', "time [s],x [mm],x [cm]\n0,0,0\n1,1,0.1\n",
     "has 2 columns for 'x' ('x [mm]', 'x [cm]'); keep one"),
    ('pose_csv = "pose.csv"\n', "time [s],x [mm]\n0,0\n1,1e300\n2,0\n",
     "'x' is 1e+300 mm from its first row"),
    ('pose_csv = "pose.csv"\npose_csv_start = "100 s"\n', "time [s],x [mm]\n0,0\n1,1\n",
     "motion.pose_csv starts 100 s after the slide, at or after the run's end"),
]


@pytest.mark.parametrize("motion, table, message", CLI_DAMAGE)
def test_damaged_pose_input_exits_2_with_one_line(tmp_path, cli_here, motion, table,
                                                  message):
    (tmp_path / "case.toml").write_text("[head]\nrows = 1\ncolumns = 1\n[motion]\n" + motion)
    if table is not None:
        (tmp_path / "pose.csv").write_text(table)
    done = cli_here("run", "case.toml", "--periods", "0.02", "--quiet", "--out", "out",
                    cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert message in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert not (tmp_path / "out").exists()  # refused before anything was written
