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

A run's configuration is named by the study's keys its case sets away from their defaults
(the ideal head, no contact between bristles, the paper's friction law), e.g. ``tilt spread
x 0.5 deg``; a run with none is ``ideal``, the default reference. Wall time: run.json's
``solver_wall_time_s_sum`` (the run's solves; runs of a sweep overlap on the workers, and
the machine's other work slows them: indicative).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
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
from exubrush.parameters.case import Case
from exubrush.parameters.fields import describe_key
from exubrush.util.units import convert

STUDY_KEYS = {  # dotted key: its name in a configuration's label
    "head.tilt_spread_x": "tilt spread x",
    "head.tilt_spread_y": "tilt spread y",
    "head.length_spread": "length spread",
    "head.misalign_x": "misalign x",
    "head.misalign_y": "misalign y",
    "head.root_jitter": "root jitter",
    "contact.between_bristles": "contact between blades",
    "contact.friction_model": "friction",
    "contact.static_velocity": "band v_s",
    "contact.dynamic_velocity": "v_d",
}


def configuration_label(case: Case) -> str:
    """``ideal`` or the study's keys ``case`` sets away from their defaults, with units
    (a fraction in %, an angle in deg), e.g. ``tilt spread x 3 deg, root jitter 0.2 mm``."""
    parts = []
    for key, name in STUDY_KEYS.items():
        *parents, leaf = key.split(".")
        owner = case
        for part in parents:
            owner = getattr(owner, part)
        if not hasattr(owner, leaf):
            continue  # a key this version of exubrush does not have yet
        value = getattr(owner, leaf)
        default = next(f.default for f in dataclasses.fields(owner) if f.name == leaf)
        if value == default:
            continue
        if isinstance(value, bool):
            parts.append(name if value else f"no {name}")
        elif isinstance(value, str):
            parts.append(f"{name} {value}")
        else:
            _, meta = describe_key(Case, key)
            unit = "%" if meta["unit"] == "1" else meta["display"]
            shown = 100.0 * value if unit == "%" else convert(value, meta["unit"], unit)
            parts.append(f"{name} {round(shown, 6):g} {unit}")
    return ", ".join(parts) or "ideal"


def sweep_runs(folder: Path) -> list[SeedRun]:
    """The completed runs of one sweep folder (sweep.json's runs), measured (module text).

    Raises
    ------
    ValueError
        If the folder has no sweep.json, or a completed run is too short or does not touch
        (reversal_metrics' message, with the run's name).
    """
    try:
        names = json.loads((folder / "sweep.json").read_text(encoding="utf-8"))["runs"]
    except (OSError, ValueError, KeyError):
        raise ValueError(f"{folder}: no readable sweep.json (not an exubrush sweep folder)"
                         ) from None
    runs = []
    for name in names:
        try:
            results = read_results(folder / name)
        except ResultsError:
            continue  # not run yet, or failed before storing forces
        if results.metadata.get("status") != "completed":
            continue
        try:
            metrics = reversal_metrics(ForceSeries.from_results(results))
        except ValueError as error:
            raise ValueError(f"{folder / name}: {error}") from None
        case = results.case()
        runs.append(SeedRun(configuration_label(case), case.head.seed, metrics,
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
