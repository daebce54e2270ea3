"""The friction band's sensitivity: flat-zone forces and reversal peaks of saved runs.

The paper's friction law is regularised: μ rises from 0 to μ_s over the slip speeds 0 to
v_s and falls to μ_d by v_d (docs/model.md, 'Friction'), so a tip under a tangential load
below μ_s F_n creeps instead of sticking. This script reads runs that differ in that band
and prints, per run, the numbers that move with it (docs/model.md, 'The friction band's
sensitivity', holds the table and the commands that made it)::

    for v in "1.2 1.5" "0.12 0.15" "0.012 0.015"; do set -- $v
      for slide in orthogonal parallel; do
        exubrush run $slide --workers 1 --out band/$slide-vs$1 \\
          --set "contact.static_velocity='$1 mm/s'" --set "contact.dynamic_velocity='$2 mm/s'"
      done
    done
    python validation/benchmarks/friction_band.py band/orthogonal-vs1.2 band/orthogonal-vs0.12 \\
      band/orthogonal-vs0.012 band/parallel-vs1.2 band/parallel-vs0.12 band/parallel-vs0.012

Per run (mN, s): the flat-zone forces per direction, the peak per reversal, R and the
peak's duration of :func:`exubrush.output.reversal.reversal_metrics` (one definition with
the sweep summary and validation/reversal_peaks), and the run's wall time (run.json
``wall_time_s``: simulate() alone).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from exubrush.output.experiment import ForceSeries
from exubrush.output.results import ResultsError, read_results
from exubrush.output.reversal import reversal_metrics


def table_row(directory: str) -> str:
    """One Markdown row (mN, s) of the run saved in ``directory``."""
    results = read_results(directory)
    case = results.case()
    metrics = reversal_metrics(ForceSeries.from_results(results))
    flat = metrics["flat"]

    def both(key):
        return " / ".join(f"{1e3 * flat[d][key]:.2f}" if d in flat else "–" for d in (1, -1))

    peaks = " / ".join(f"{1e3 * p:.1f}" for p in metrics["peaks"])
    duration = "–" if np.isnan(metrics["duration"]) else f"{metrics['duration']:.2f}"
    return (f"| {case.motion.direction} | {case.contact.static_velocity:g} | "
            f"{both('normal_force')} | {both('tangential_force')} | {peaks} | "
            f"{metrics['ratio']:.2f} | {duration} | "
            f"{results.metadata['wall_time_s']:.1f} |")


HEADER = ("| slide | v_s [mm/s] | flat F_n +/− [mN] | flat F_t +/− [mN] | peak F_n per reversal "
          "[mN] | R | peak duration [s] | wall time [s] |\n"
          "| --- | --- | --- | --- | --- | --- | --- | --- |")


def main(argv: list[str] | None = None) -> None:
    """Print the table of the runs named on the command line."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="result directories of exubrush run")
    args = parser.parse_args(argv)
    rows = []
    for directory in args.runs:
        try:
            rows.append(table_row(directory))
        except (OSError, ResultsError, ValueError) as error:
            parser.error(f"{directory}: {error}")
    print(HEADER, *rows, sep="\n")


if __name__ == "__main__":
    sys.exit(main())
