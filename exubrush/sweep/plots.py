"""The sweep's summary plots: every metric against each swept parameter (PNG)."""

from __future__ import annotations

import math
import re
from pathlib import Path

from exubrush.files import atomic_file
from exubrush.plotting import figure
from exubrush.sweep.summary import METRICS

COLUMNS = 4  # metric panels per row
STATUS_COLOURS = {"completed": "tab:blue", "failed": "tab:red"}


def plot_summary(name: str, swept: dict, statuses, metrics, folder: Path) -> list[str]:
    """One ``summary-PARAMETER.png`` per swept parameter: each metric of each finished run
    against that parameter's value (failed runs in red, text values as categories).
    ``swept`` maps each parameter's column label ("key [unit]") to its values over the
    runs. Returns the file names written."""
    written = []
    for label, values in swept.items():
        categorical = any(isinstance(v, str) for v in values)
        categories = sorted({str(v) for v in values}) if categorical else []
        x = [categories.index(str(v)) if categorical else v for v in values]
        rows = math.ceil(len(METRICS) / COLUMNS)
        fig, axes = figure(rows, COLUMNS, figsize=(4 * COLUMNS, 3 * rows), squeeze=False)
        for axis, (metric, unit) in zip(axes.flat, METRICS, strict=False):
            for status, colour in STATUS_COLOURS.items():
                points = [(xi, m[metric]) for xi, m, s in zip(x, metrics, statuses, strict=True)
                          if s == status and metric in m and not math.isnan(m[metric])]
                if points:
                    axis.plot(*zip(*points, strict=True), "o", color=colour, ms=4,
                              label=status)
            axis.set_title(f"{metric} [{unit}]", fontsize=8)
            axis.grid(True, alpha=0.3)
            if categorical:
                axis.set_xticks(range(len(categories)), categories, fontsize=7)
        for axis in list(axes.flat)[len(METRICS):]:
            axis.set_visible(False)
        key = label.split(" [")[0]
        fig.supxlabel(label)
        fig.suptitle(f"sweep {name}: metrics against {key} (simulation)")
        fig.tight_layout()
        file = "summary-" + re.sub(r"[^A-Za-z0-9._-]", "_", key) + ".png"
        with atomic_file(folder / file, "wb") as handle:
            fig.savefig(handle, format="png", dpi=100)
        written.append(file)
    return written
