"""What a sweep tabulates: each run's metrics, the summary table and the sensitivities.

Metrics of one run (from its forces and shapes; empty where the run has no such part):

- flat-zone means per slide direction ("forward" = +slide axis, "backward"): the normal
  force F_n, the tangential force |F_t| and μ_eff = |F_t| / F_n over the flat zones
  (slide speed >= 80 % of the stroke's peak) of every *whole* stroke, i.e. from one
  reversal to the next (exubrush.output.experiment.strokes: the first movement after the
  approach and a stroke cut off by the end of the run are left out);
- the reversal peak: the largest F_n where the slide speed is below the flat zone's
  around a reversal (exubrush.output.experiment.reversal_zones);
- the reversal ratio R, its peak's duration and the flat-zone mean F_n over all whole
  strokes (exubrush.output.reversal.reversal_metrics: R is the largest F_n at a reversal
  after the first over that mean; the duration is that peak's width at half its excess);
- the largest tip deflection: the largest distance a tip moved relative to its root,
  against the first stored shape (bristles straight before the approach).

Sensitivity of metric m to parameter p: S = (∂m/∂p) · p̄ / m(p̄), the relative change of m
per relative change of p at the sweep's mean parameters, from a least-squares fit of m
linear in all numeric swept parameters over the runs where m is defined. ``head.seed`` is
left out: it repeats a run, its spread is the metric's scatter, not a trend.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from exubrush.output.experiment import ForceSeries, reversal_zones, strokes
from exubrush.output.reversal import FLAT_SPEED, reversal_metrics
from exubrush.util.files import atomic_file

DIRECTIONS = ((1, "forward"), (-1, "backward"))
METRICS = (  # (column name, unit)
    *((f"flat_normal_force_{d}", "N") for _, d in DIRECTIONS),
    *((f"flat_tangential_force_{d}", "N") for _, d in DIRECTIONS),
    *((f"friction_coefficient_{d}", "-") for _, d in DIRECTIONS),
    ("reversal_peak_normal_force", "N"),
    ("reversal_ratio", "-"),
    ("reversal_peak_duration", "s"),
    ("flat_normal_force", "N"),
    ("largest_tip_deflection", "mm"),
    ("wiped_area_per_stroke", "mm^2"),
    ("force_share_spread", "-"),
    ("interdental_depth", "mm"),
)
NOT_SWEPT_FOR_SENSITIVITY = ("head.seed",)


def run_metrics(results) -> dict[str, float]:
    """The metrics of one run's :class:`~exubrush.output.results.Results` (NaN where undefined)."""
    metrics = dict.fromkeys((name for name, _ in METRICS), math.nan)
    time = results.time
    if time.size >= 3:
        velocity = np.gradient(results.slider_position, time)
        found = strokes(time, velocity, FLAT_SPEED)
        for sense, label in DIRECTIONS:
            flat = np.zeros(time.size, dtype=bool)
            for stroke in (s for s in found if s.direction == sense):
                flat |= (time >= stroke.flat_start) & (time <= stroke.flat_end)
            if flat.any():
                normal = float(np.mean(results.normal_force[flat]))
                tangential = float(np.mean(np.abs(results.tangential_force[flat])))
                metrics[f"flat_normal_force_{label}"] = normal
                metrics[f"flat_tangential_force_{label}"] = tangential
                if normal > 0.0:
                    metrics[f"friction_coefficient_{label}"] = tangential / normal
        peaks = [float(np.max(results.normal_force[(time >= a) & (time <= b)]))
                 for a, b in reversal_zones(time, velocity, FLAT_SPEED)]
        if peaks:
            metrics["reversal_peak_normal_force"] = max(peaks)
        metrics.update(_reversal(ForceSeries.from_results(results)))
    nodes = results.shape_nodes
    if nodes.shape[0] >= 1 and nodes.shape[2] >= 2:
        span = nodes[:, :, -1, :] - nodes[:, :, 0, :]  # tip relative to root [mm]
        metrics["largest_tip_deflection"] = float(
            np.max(np.linalg.norm(span - span[0], axis=-1)))
    metrics.update(_cleaning_metrics(results))
    return metrics


def _reversal(series: ForceSeries) -> dict[str, float]:
    """R, its peak's duration [s] and the flat-zone mean F_n [N] of a run long enough to have
    them (none for a run without a whole stroke or a later reversal, or one that does not
    touch: those stay NaN)."""
    try:
        found = reversal_metrics(series, FLAT_SPEED)
    except ValueError:
        return {}
    return {"reversal_ratio": found["ratio"], "reversal_peak_duration": found["duration"],
            "flat_normal_force": found["flat_normal"]}


def _cleaning_metrics(results) -> dict[str, float]:
    """Means over the whole strokes of the run's cleaning summary (exubrush.output.cleaning):
    wiped area, force-share spread and, on a tooth row, the deepest tip in a gap."""
    summary = results.cleaning()
    whole = [s for s in summary["strokes"] if s["whole"]] if summary else []
    if not whole:
        return {}
    found = {"wiped_area_per_stroke": float(np.mean([s["wiped_area_mm2"] for s in whole])),
             "force_share_spread": float(np.mean([s["force_share_spread"] for s in whole]))}
    if "interdental" in whole[0]:
        found["interdental_depth"] = max(s["interdental"]["max_depth_mm"] for s in whole)
    return found


def write_parquet(path: Path, header: Sequence[str], rows: Sequence[Sequence]) -> bool:
    """The same table as Parquet where pandas and pyarrow are installed (else False)."""
    try:
        import pandas
        import pyarrow  # noqa: F401  (pandas' Parquet engine)
    except ImportError:
        return False
    with atomic_file(path, "wb") as handle:
        pandas.DataFrame(list(rows), columns=list(header)).to_parquet(handle, index=False)
    return True


def sensitivities(parameters: dict[str, np.ndarray],
                  metrics: dict[str, np.ndarray]) -> dict[str, dict[str, float]]:
    """S[metric][parameter] = (∂m/∂p) · p̄ / m(p̄) from a least-squares fit of each metric
    linear in all ``parameters`` (arrays over the runs); NaN where the runs cannot
    determine it (fewer runs with the metric defined than parameters + 1, parameters that
    do not vary independently, a parameter whose mean is 0, or m(p̄) = 0)."""
    names = [n for n, values in parameters.items()
             if n not in NOT_SWEPT_FOR_SENSITIVITY and np.ptp(values) > 0.0
             and np.mean(values) != 0.0]
    result = {m: dict.fromkeys(parameters, math.nan) for m in metrics}
    if not names:
        return result
    matrix = np.column_stack([parameters[n] for n in names])
    means = matrix.mean(axis=0)
    design = np.column_stack([np.ones(len(matrix)), (matrix - means) / means])
    for metric, values in metrics.items():
        usable = np.isfinite(values)
        if usable.sum() < len(names) + 1:
            continue
        if np.linalg.matrix_rank(design[usable]) < len(names) + 1:
            continue
        coefficients, *_ = np.linalg.lstsq(design[usable], values[usable], rcond=None)
        if coefficients[0] == 0.0:
            continue
        for name, slope in zip(names, coefficients[1:], strict=True):
            result[metric][name] = float(slope / coefficients[0])
    return result
