"""Property-based test (hypothesis) over whole case files: random keys, types, units,
magnitudes and encodings. Every file must end in a prepared case or one clean
ParameterError line, within a time limit; never another exception, never a hang.

The fast tier tries 40 files, the slow tier 400.
"""

import math
import time

import pytest
import tomlkit
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from exubrush.parameters.case import Case
from exubrush.parameters.fields import ParameterError, dotted_keys, to_plain
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare

KEYS = dotted_keys(Case)
UNITS = ["mm", "m", "um", "MPa", "GPa", "s", "ms", "kg/m^3", "N", "N/mm^1.3", "N*s/mm^3",
         "mm/s", "deg", "rad", "GB", "furlong", "", "(", "1/0"]
SECONDS = 60.0  # per file: preparing a head of the largest allowed size, or a PRB fit

numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-1e3, 1e3),
    st.sampled_from([0.0, -1.0, 1e-30, 1e30, 1e308, 5e-324]),
)
integers = st.one_of(st.integers(-10, 100), st.integers(-2**70, 2**70))
quantities = st.builds(lambda x, u: f"{x!r} {u}".strip(), numbers, st.sampled_from(UNITS))
texts = st.text(max_size=20)
plausible = st.builds(lambda x, u: f"{x!r} {u}", st.floats(1e-3, 1e3),
                      st.sampled_from(UNITS[:15]))
# mostly values that may pass (a plausible quantity, a small count, a choice-like word), so
# that many files get as far as prepare; the rest is hostile
values = st.one_of(plausible, plausible, st.integers(1, 12), st.floats(0.0, 2.0),
                   st.sampled_from(["dfm", "prb", "sine", "csv", "coupled", "paper-python"]),
                   numbers, integers, st.booleans(), quantities, texts,
                   st.lists(st.integers(0, 3), max_size=3))


def _scaled(original, exponent: int):
    """The original value 10^exponent times larger, in its own unit."""
    if isinstance(original, bool) or not isinstance(original, int | float | str):
        return original
    if isinstance(original, int | float):
        return type(original)(original * 10**exponent) if exponent >= 0 else original
    magnitude, _, unit = original.partition(" ")
    try:
        return f"{float(magnitude) * 10.0**exponent!r} {unit}"
    except ValueError:
        return original


@st.composite
def mutated_cases(draw):
    """The complete default case with a few values replaced or scaled by powers of ten."""
    document = to_plain(Case())
    for key in draw(st.lists(st.sampled_from(KEYS), max_size=3, unique=True)):
        *parents, leaf = key.split(".")
        table = document
        for part in parents:
            table = table[part]
        exponent = draw(st.integers(-25, 25))
        table[leaf] = draw(st.one_of(st.just(_scaled(table[leaf], exponent)), values))
    return tomlkit.dumps(document).encode()


@st.composite
def random_cases(draw):
    known = st.sampled_from(KEYS)
    chosen = draw(st.lists(st.one_of(known, known, known, known, known, texts.filter(bool)),
                           max_size=6, unique=True))
    document = {}
    for key in chosen:
        *parents, leaf = key.split(".")
        table = document
        try:
            for part in parents:
                table = table.setdefault(part, {})
            table[leaf] = draw(values)
        except (AttributeError, TypeError):  # a key that is both a table and a value
            continue
    text = tomlkit.dumps(document)
    encoding = draw(st.sampled_from(["utf-8"] * 8 + ["latin-1", "utf-16"]))
    return text.encode(encoding, errors="replace")


def _check(tmp_path, content: bytes):
    path = tmp_path / "case.toml"
    path.write_bytes(content)
    start = time.monotonic()
    try:
        prepared = prepare(load_case(str(path)))
    except ParameterError as err:
        assert str(err) and "\n" not in str(err)
    else:
        assert all(math.isfinite(v) for v in prepared.force_limits)
        assert prepared.motion.end_time > 0.0
    assert time.monotonic() - start < SECONDS


case_files = st.one_of(mutated_cases(), random_cases())


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(content=case_files)
def test_any_case_file_ends_in_a_case_or_one_clean_line(tmp_path, content):
    _check(tmp_path, content)


@pytest.mark.slow
@settings(max_examples=400, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(content=case_files)
def test_many_case_files_end_in_a_case_or_one_clean_line(tmp_path, content):
    _check(tmp_path, content)
