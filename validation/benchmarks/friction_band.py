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

Per run (mN, s; :func:`band_metrics`):

- flat-zone means of F_n and |F_t| per slide direction, over the whole strokes
  (exubrush.output.experiment.stroke_flat_means: flat zone where the slide speed is at
  least 80 % of the stroke's peak, as benchmark.py; the first movement from upright
  bristles and a stroke cut off by the end of the run are no whole strokes);
- the largest F_n in each reversal zone (exubrush.output.experiment.reversal_zones), in
  order;
- R: the largest of those peaks at a later reversal (not the first one, which follows the
  first movement) over the flat-zone mean F_n of all whole strokes;
- that peak's duration: the time F_n stays above the flat mean plus half the peak's excess
  over it (the width at half the excess), crossings interpolated linearly;
- the run's wall time (run.json ``wall_time_s``: simulate() alone).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from exubrush.output.experiment import ForceSeries, reversal_zones, stroke_flat_means
from exubrush.output.results import ResultsError, read_results

FLAT_SPEED = 0.8  # flat zone: slide speed >= this fraction of the stroke's peak (benchmark.py)


def _crossing(time: np.ndarray, values: np.ndarray, inside: int, outside: int,
              level: float) -> float:
    """Time [s] where ``values`` crosses ``level`` between two neighbouring samples."""
    fraction = (values[inside] - level) / (values[inside] - values[outside])
    return float(time[inside] + fraction * (time[outside] - time[inside]))


def width_above(time: np.ndarray, values: np.ndarray, index: int, level: float) -> float:
    """Duration [s] of the run of samples around ``index`` where ``values`` > ``level``
    (``values[index]`` must exceed it); the crossings are interpolated linearly, the
    series' ends taken as they are."""
    first = index
    while first > 0 and values[first - 1] > level:
        first -= 1
    last = index
    while last < values.size - 1 and values[last + 1] > level:
        last += 1
    start = _crossing(time, values, first, first - 1, level) if first > 0 else time[0]
    end = _crossing(time, values, last, last + 1, level) if last < values.size - 1 else time[-1]
    return float(end - start)


def band_metrics(series: ForceSeries, flat_speed_fraction: float = FLAT_SPEED) -> dict:
    """Flat-zone forces and reversal peaks of one run (module text), in the series' units.

    Returns
    -------
    dict
        ``flat``: {direction (+1, -1): {normal_force, tangential_force}} (means of the
        whole strokes' flat-zone means in that direction); ``flat_normal``: the mean over
        all whole strokes; ``peaks``: the largest F_n in each reversal zone, in order;
        ``ratio``: R, the largest later peak over ``flat_normal``; ``duration``: that
        peak's width at half its excess [s], NaN if it does not rise above the flat mean
        (no peak: printed as "–").

    Raises
    ------
    ValueError
        If the run has no whole stroke or no reversal after the first (too short), or no
        normal force in the flat zones (the head does not touch).
    """
    rows = stroke_flat_means(series, flat_speed_fraction)
    zones = reversal_zones(series.time, series.slide_velocity, flat_speed_fraction)
    if not rows or len(zones) < 2:
        raise ValueError(f"{len(rows)} whole stroke(s) and {len(zones)} reversal(s): R needs "
                         "a whole stroke and a reversal after the first (run 1 period or more)")
    flat = {}
    for direction in sorted({row["direction"] for row in rows}):
        mine = [row for row in rows if row["direction"] == direction]
        flat[direction] = {key: float(np.mean([row[key] for row in mine]))
                           for key in ("normal_force", "tangential_force")}
    flat_normal = float(np.mean([row["normal_force"] for row in rows]))
    if flat_normal <= 0.0:
        raise ValueError("no normal force in the flat zones: the head does not touch, R is "
                         "undefined")
    peak_indices = []
    for start, end in zones:
        zone = np.flatnonzero((series.time >= start) & (series.time <= end))
        peak_indices.append(int(zone[np.argmax(series.normal_force[zone])]))
    peaks = [float(series.normal_force[i]) for i in peak_indices]
    later = 1 + int(np.argmax(peaks[1:]))
    level = flat_normal + 0.5 * (peaks[later] - flat_normal)
    duration = (width_above(series.time, series.normal_force, peak_indices[later], level)
                if peaks[later] > flat_normal else float("nan"))
    return {"flat": flat, "flat_normal": flat_normal, "peaks": peaks,
            "ratio": peaks[later] / flat_normal, "duration": duration}


def table_row(directory: str) -> str:
    """One Markdown row (mN, s) of the run saved in ``directory``."""
    results = read_results(directory)
    case = results.case()
    metrics = band_metrics(ForceSeries.from_results(results))
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
