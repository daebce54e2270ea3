"""The reversal-peak study's table from sweep folders (issue 46, docs/reversal-peaks.md).

Reads the runs of one or more `exubrush sweep` folders of one slide (the sweep files of this
folder), measures each completed run with exubrush.output.reversal.reversal_metrics (the
definition the sweep summary and the friction-band benchmark share) and prints one Markdown
table: per configuration, mean and min to max over the seeds of the flat-zone F_n and |F_t|
per slide direction, R, the peak's duration and the wall time, the change of R and of the
flat F_n against the reference configuration with the same seed, and whether the flat F_n
stays within the paper's band (16 % orthogonal, 8 % parallel) and R within the experiment's
inferred level (0.5 x R_ideal, ±20 %)::

    python validation/reversal_peaks/study.py --slide orthogonal \\
        /work/study-results/orthogonal-ideal /work/study-results/orthogonal-tilt_x ...

A run's configuration is named by its sweep's swept values other than head.seed (summary.csv's
columns between status and compute_time), e.g. ``tilt_spread_x = 0.5 deg``; a run whose swept
values are all 0 or false is ``ideal``, the default reference. Wall time: run.json's
``solver_wall_time_s_sum`` (the run's solves; runs of a sweep overlap on the workers).
"""

from __future__ import annotations

import argparse
import csv
import re
import sys
from pathlib import Path

from exubrush.output.experiment import ForceSeries
from exubrush.output.results import ResultsError, read_results
from exubrush.output.reversal import (
    FLAT_BAND,
    SeedRun,
    configuration_table,
    markdown_table,
    reversal_metrics,
)

_HEADER = re.compile(r"^(?P<key>[^\[]+?)(?: \[(?P<unit>[^\]]*)\])?$")


def _label(swept: dict[str, tuple[str, str]]) -> str:
    """``ideal`` or ``name = value unit, ...`` of a run's swept values {key: (value, unit)}."""
    if all(value.lower() in ("0", "false") for value, _ in swept.values()):
        return "ideal"
    return ", ".join(f"{key.split('.')[-1]} = {value}{' ' + unit if unit else ''}"
                     for key, (value, unit) in swept.items())


def sweep_runs(folder: Path) -> list[SeedRun]:
    """The completed runs of one sweep folder, measured (module text).

    Raises
    ------
    ValueError
        If the folder has no summary.csv, or a completed run is too short or does not touch
        (reversal_metrics' message, with the run's name).
    """
    summary = folder / "summary.csv"
    if not summary.is_file():
        raise ValueError(f"{folder}: no summary.csv (not a finished exubrush sweep folder)")
    with open(summary, newline="", encoding="utf-8") as handle:
        table = list(csv.reader(handle))
    header = table[0]
    swept_columns = range(header.index("status") + 1, header.index("compute_time [s]"))
    runs = []
    for row in table[1:]:
        if row[1] != "completed":
            continue
        swept, seed = {}, None
        for column in swept_columns:
            match = _HEADER.match(header[column])
            if match["key"] == "head.seed":
                seed = int(row[column])
            else:
                swept[match["key"]] = (row[column], match["unit"] or "")
        results = read_results(folder / row[0])
        try:
            metrics = reversal_metrics(ForceSeries.from_results(results))
        except ValueError as error:
            raise ValueError(f"{folder / row[0]}: {error}") from None
        runs.append(SeedRun(_label(swept), 0 if seed is None else seed, metrics,
                            float(results.metadata["solver_wall_time_s_sum"])))
    return runs


def study_table(folders: list[Path], slide: str, reference: str = "ideal") -> list[dict]:
    """:func:`exubrush.output.reversal.configuration_table` of every completed run in
    ``folders``, against ``reference``, with the band of ``slide``."""
    runs = [run for folder in folders for run in sweep_runs(folder)]
    return configuration_table(runs, reference, FLAT_BAND[slide])


def main(argv: list[str] | None = None) -> None:
    """Print (and with --out write) the table of the sweep folders named."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folders", nargs="+", type=Path, help="exubrush sweep folders")
    parser.add_argument("--slide", required=True, choices=sorted(FLAT_BAND),
                        help="the slide the sweeps brush (sets the flat-force band)")
    parser.add_argument("--reference", default="ideal",
                        help="the configuration the changes are taken against")
    parser.add_argument("--out", type=Path, help="also write the table to this file")
    args = parser.parse_args(argv)
    try:
        table = markdown_table(study_table(args.folders, args.slide, args.reference))
    except (OSError, ResultsError, ValueError) as error:
        parser.error(str(error))
    print(table)
    if args.out:
        args.out.write_text(table + "\n", encoding="utf-8")


if __name__ == "__main__":
    sys.exit(main())
