"""The sweep's summary plots: every metric against each swept parameter (PNG)."""

from __future__ import annotations

import math
import re
from pathlib import Path

from exubrush.output.plotting import figure
from exubrush.sweep.summary import METRICS
from exubrush.util.files import atomic_file

COLUMNS = 4  # metric panels per row
MOST_SERIES = 8  # more combinations of the other parameters than this: points, no lines


def plot_summary(name: str, swept: dict, statuses, metrics, folder: Path) -> list[str]:
    """One ``summary-PARAMETER.png`` per swept parameter with more than one value: each
    metric of each finished run against that parameter's value. Runs that share the values
    of every other varied parameter are joined by a line and labelled by them (for up to 8
    such series, as in a grid); failed runs are red crosses; text values are categories.
    ``swept`` maps each parameter's column label ("key [unit]") to its values over the
    runs. Returns the file names written."""
    written = []
    varied = {label: values for label, values in swept.items()
              if len({str(v) for v in values}) > 1}  # a parameter with one value: no axis
    for label, values in varied.items():
        categorical = any(isinstance(v, str) for v in values)
        categories = sorted({str(v) for v in values}) if categorical else []
        x = [categories.index(str(v)) if categorical else v for v in values]
        others = [(other.split(" [")[0].split(".")[-1], vals)
                  for other, vals in varied.items() if other != label]
        series: dict[str, list[int]] = {}
        for run in range(len(values)):
            key = ", ".join(f"{short}={_shown(vals[run])}" for short, vals in others)
            series.setdefault(key, []).append(run)
        lines = len(series) <= MOST_SERIES
        rows = math.ceil(len(METRICS) / COLUMNS)
        fig, axes = figure(rows, COLUMNS, figsize=(4 * COLUMNS, 3 * rows + 0.6),
                           squeeze=False)
        for axis, (metric, unit) in zip(axes.flat, METRICS, strict=False):
            for number, (key, runs) in enumerate(series.items()):
                done = sorted((x[r], metrics[r][metric]) for r in runs
                              if statuses[r] == "completed" and not math.isnan(metrics[r][metric]))
                if done:
                    axis.plot(*zip(*done, strict=True), "o-" if lines else "o", ms=4,
                              color=f"C{number % 10}" if lines else "C0",
                              label=(key or None) if lines else None)
                failed = [(x[r], metrics[r][metric]) for r in runs if statuses[r] == "failed"
                          and not math.isnan(metrics[r][metric])]
                if failed:
                    axis.plot(*zip(*failed, strict=True), "x", color="tab:red", ms=6)
            axis.set_title(f"{metric} [{unit}]", fontsize=8)
            axis.grid(True, alpha=0.3)
            if categorical:
                axis.set_xticks(range(len(categories)), categories, fontsize=7)
        for axis in list(axes.flat)[len(METRICS):]:
            axis.set_visible(False)
        handles, names = axes.flat[0].get_legend_handles_labels()
        if names:
            fig.legend(handles, names, loc="lower center", ncol=min(len(names), 4), fontsize=8)
        key = label.split(" [")[0]
        fig.suptitle(f"sweep {name}: metrics against {label} (simulation; failed runs: red x)")
        fig.tight_layout(rect=(0, 0.06 if names else 0, 1, 1))
        file = "summary-" + re.sub(r"[^A-Za-z0-9._-]", "_", key) + ".png"
        with atomic_file(folder / file, "wb") as handle:
            fig.savefig(handle, format="png", dpi=100)
        written.append(file)
    return written


def _shown(value) -> str:
    return f"{value:.4g}" if isinstance(value, float) else str(value)
