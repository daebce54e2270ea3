"""Reversal peaks against the flat zone: the ratio R and the peak's duration (pure).

One definition for the sweep summary (exubrush.sweep.summary), the friction-band benchmark
(validation/benchmarks/friction_band.py) and the reversal-peak study
(validation/reversal_peaks/, docs/reversal-peaks.md). Per run, in the series' units:

- flat-zone means of F_n and |F_t| per slide direction, over the whole strokes
  (exubrush.output.experiment.stroke_flat_means: flat zone where the slide speed is at
  least 80 % of the stroke's peak; the first movement from upright bristles and a stroke
  cut off by the end of the run are no whole strokes);
- the largest F_n in each reversal zone (exubrush.output.experiment.reversal_zones), in
  order;
- R: the largest of those peaks at a later reversal (not the first one, which follows the
  first movement from upright bristles) over the flat-zone mean F_n of all whole strokes;
- that peak's duration: the time F_n stays above the flat mean plus half the peak's excess
  over it (the width at half the excess), crossings interpolated linearly.
"""

from __future__ import annotations

import numpy as np

from exubrush.output.experiment import ForceSeries, reversal_zones, stroke_flat_means

FLAT_SPEED = 0.8  # flat zone: slide speed >= this fraction of the stroke's peak


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


def reversal_metrics(series: ForceSeries, flat_speed_fraction: float = FLAT_SPEED) -> dict:
    """Flat-zone forces and reversal peaks of one run (module text), in the series' units.

    Returns
    -------
    dict
        ``flat``: {direction (+1, -1): {normal_force, tangential_force}} (means of the
        whole strokes' flat-zone means in that direction); ``flat_normal``: the mean over
        all whole strokes; ``peaks``: the largest F_n in each reversal zone, in order;
        ``ratio``: R, the largest later peak over ``flat_normal``; ``duration``: that
        peak's width at half its excess [s], NaN if it does not rise above the flat mean.

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
