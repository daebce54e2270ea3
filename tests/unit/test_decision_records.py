"""The decision records (docs/decisions/) and the benchmark README that indexes them: every
record is numbered, titled and dated, the index lists each one, and every citation of a
record in code, docs, notebooks and tests names one that exists."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).parents[2]
DECISIONS = ROOT / "docs" / "decisions"
BENCHMARKS = ROOT / "validation" / "benchmarks" / "README.md"
CITATION = re.compile(r"decisions/(\d{4})")
CITING = ("exubrush", "docs", "tests", "validation", "README.md")
SUFFIXES = {".py", ".md", ".ipynb", ".toml"}


def _records() -> dict[str, Path]:
    return {path.name[:4]: path for path in sorted(DECISIONS.glob("[0-9][0-9][0-9][0-9]-*.md"))}


def test_records_are_numbered_in_a_row_titled_and_dated():
    records = _records()
    assert list(records) == [f"{n:04d}" for n in range(1, len(records) + 1)]
    for number, path in records.items():
        lines = path.read_text(encoding="utf-8").splitlines()
        assert lines[0].startswith(f"# {number} — "), path.name
        assert any(re.match(r"Date: \d{4}-\d{2}-\d{2}\b", line) for line in lines[:6]), path.name
        assert "## Context" in lines, path.name


def test_the_benchmark_readme_indexes_every_record_and_keeps_its_targets():
    text = BENCHMARKS.read_text(encoding="utf-8")
    assert "\n## Targets\n" in text  # cited by title from the records
    linked = re.findall(r"\]\(\.\./\.\./docs/decisions/([^)]+)\)", text)
    assert sorted(set(linked)) == sorted(path.name for path in _records().values())


def test_every_cited_record_exists():
    records = _records()
    cited = set()
    for top in CITING:
        base = ROOT / top
        files = [base] if base.is_file() else [p for p in base.rglob("*") if p.suffix in SUFFIXES]
        for path in files:
            for number in CITATION.findall(path.read_text(encoding="utf-8", errors="ignore")):
                assert number in records, f"{path.relative_to(ROOT)} cites decisions/{number}"
                cited.add(number)
    assert cited  # the code and docs do cite records
