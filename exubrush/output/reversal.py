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

The study's table (:func:`configuration_table`, :func:`markdown_table`): per configuration
of the head or the physics, the spread of these over seeds and their change against the
ideal head with the same seed, flagged against the paper's flat-force band and the
experiment's inferred R (half the ideal DFM's, ±20 %: docs/reversal-peaks.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

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


# --- the reversal-peak study (issue 46; validation/reversal_peaks, docs/reversal-peaks.md) ---

FLAT_BAND = {"orthogonal": 0.16, "parallel": 0.08}  # the paper's DFM against its measured
# flat-zone F_n: the relative change of flat F_n a configuration may bring against the ideal
# head and still agree with the experiment as well as the ideal DFM does
EXPERIMENT_RATIO = 0.5  # the experiment's R over the ideal DFM's (its peaks are half the
# DFM's, its flat forces within the band above): the study's target
TARGET_TOLERANCE = 0.2  # ± relative, around EXPERIMENT_RATIO x R_ideal (docs/reversal-peaks.md)
QUANTITIES = (  # (key of a row's statistics, unit): mean, min and max over the seeds
    ("flat_normal_forward", "N"), ("flat_normal_backward", "N"),
    ("flat_tangential_forward", "N"), ("flat_tangential_backward", "N"),
    ("ratio", "-"), ("duration", "s"), ("wall_time", "s"),
    ("ratio_change", "-"), ("flat_normal_change", "-"),
)


@dataclass(frozen=True)
class SeedRun:
    """One run of the study: its configuration's label, its head.seed, its
    :func:`reversal_metrics` and its wall time [s]."""

    configuration: str
    seed: int
    metrics: dict
    wall_time: float


def _spread(values: list[float]) -> dict[str, float]:
    """Mean, min and max of the finite ``values`` (NaN for none)."""
    finite = [v for v in values if math.isfinite(v)]
    if not finite:
        return {"mean": math.nan, "min": math.nan, "max": math.nan}
    return {"mean": float(np.mean(finite)), "min": min(finite), "max": max(finite)}


def _per_seed(run: SeedRun) -> dict[str, float]:
    flat = run.metrics["flat"]

    def of(direction: int, key: str) -> float:
        return flat[direction][key] if direction in flat else math.nan

    return {"flat_normal_forward": of(1, "normal_force"),
            "flat_normal_backward": of(-1, "normal_force"),
            "flat_tangential_forward": of(1, "tangential_force"),
            "flat_tangential_backward": of(-1, "tangential_force"),
            "ratio": run.metrics["ratio"], "duration": run.metrics["duration"],
            "wall_time": run.wall_time}


def configuration_table(runs: list[SeedRun], reference: str, flat_band: float) -> list[dict]:
    """Per configuration (in the order first met): its seeds' spread of every quantity and
    its change against the ``reference`` configuration with the same seed.

    ``ratio_change`` is R / R_reference - 1 per seed; ``flat_normal_change`` the relative
    change of the flat-zone F_n per slide direction and seed (both directions pooled);
    ``within_band``: every such change within ±``flat_band`` (a fraction);
    ``on_target``: the mean of R / R_reference within EXPERIMENT_RATIO x (1 ± TARGET_TOLERANCE).
    A seed the reference lacks adds nothing to the changes (NaN where no seed is shared).

    Raises
    ------
    ValueError
        If there is no run, no run has the ``reference`` configuration, or a configuration
        repeats a seed.
    """
    if not runs:
        raise ValueError("no completed run to tabulate")
    by_configuration: dict[str, dict[int, dict[str, float]]] = {}
    for run in runs:
        seeds = by_configuration.setdefault(run.configuration, {})
        if run.seed in seeds:
            raise ValueError(f"configuration {run.configuration!r} has seed {run.seed} twice")
        seeds[run.seed] = _per_seed(run)
    if reference not in by_configuration:
        raise ValueError(f"no run of the reference configuration {reference!r} (there are "
                         f"{', '.join(map(repr, by_configuration))})")
    ideal = by_configuration[reference]
    rows = []
    for configuration, seeds in by_configuration.items():
        shared = [s for s in seeds if s in ideal]
        values = {key: [seeds[s][key] for s in seeds] for key, _ in QUANTITIES[:7]}
        values["ratio_change"] = [seeds[s]["ratio"] / ideal[s]["ratio"] - 1.0 for s in shared]
        values["flat_normal_change"] = [
            seeds[s][key] / ideal[s][key] - 1.0 for s in shared
            for key in ("flat_normal_forward", "flat_normal_backward")]
        stats = {key: _spread(values[key]) for key, _ in QUANTITIES}
        changes = [c for c in values["flat_normal_change"] if math.isfinite(c)]
        low, high = (EXPERIMENT_RATIO * (1.0 + s * TARGET_TOLERANCE) for s in (-1, 1))
        on = 1.0 + stats["ratio_change"]["mean"]
        rows.append({"configuration": configuration, "seeds": sorted(seeds), **stats,
                     "within_band": bool(changes) and max(map(abs, changes)) <= flat_band,
                     "on_target": bool(low <= on <= high)})
    return rows


def markdown_table(rows: list[dict]) -> str:
    """The rows of :func:`configuration_table` as a Markdown table (mN, s, %): mean and, in
    brackets, min to max over the seeds."""

    def cell(stats: dict, scale: float, digits: int, sign: str = "") -> str:
        if not math.isfinite(stats["mean"]):
            return "–"
        return (f"{scale * stats['mean']:{sign}.{digits}f} ({scale * stats['min']:{sign}.{digits}f}"
                f" to {scale * stats['max']:{sign}.{digits}f})")

    lines = ["| configuration | seeds | flat F_n + [mN] | flat F_n − [mN] | flat F_t + [mN] | "
             "flat F_t − [mN] | R | R change [%] | peak duration [s] | flat F_n change [%] "
             "| in band | R on target | wall [s] |",
             "| --- " * 13 + "|"]
    for row in rows:
        lines.append(
            f"| {row['configuration']} | {len(row['seeds'])} | "
            f"{cell(row['flat_normal_forward'], 1e3, 1)} | "
            f"{cell(row['flat_normal_backward'], 1e3, 1)} | "
            f"{cell(row['flat_tangential_forward'], 1e3, 1)} | "
            f"{cell(row['flat_tangential_backward'], 1e3, 1)} | "
            f"{cell(row['ratio'], 1.0, 2)} | {cell(row['ratio_change'], 100.0, 1, '+')} | "
            f"{cell(row['duration'], 1.0, 2)} | {cell(row['flat_normal_change'], 100.0, 1, '+')} | "
            f"{'yes' if row['within_band'] else 'no'} | {'yes' if row['on_target'] else 'no'} | "
            f"{row['wall_time']['mean']:.1f} |")
    return "\n".join(lines)
