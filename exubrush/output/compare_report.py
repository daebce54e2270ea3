"""Files of a comparison with measured data: comparison.json, comparison.md and plots."""

from __future__ import annotations

import json
import math
from pathlib import Path

from exubrush.output.experiment import Aligned
from exubrush.util.files import atomic_file


def _pct(value) -> str:
    return "n/a" if value is None or math.isnan(value) else f"{100.0 * value:+.1f} %"


def summary_markdown(comparison: dict, sources: dict, flat_speed_fraction: float,
                     time_offset: float) -> str:
    """Short Markdown summary: sources, flat-zone table per stroke, reversal peaks."""
    lines = [
        "# exubrush comparison: simulation against measurement",
        "",
        f"- simulation: `{sources['simulation']}` ({sources['model']} model; "
        "exubrush model output)",
        f"- measurement: `{sources['measurement']}`"
        + (" **(its header declares it model output, not a measurement: this compares two "
           "models)**" if sources.get("model_output") else ""),
        f"- alignment: measured time + {time_offset:.6g} s = simulation time "
        f"({sources['alignment']})",
        f"- flat zone: slide speed >= {flat_speed_fraction:g} x the stroke's peak speed",
        "- differences are (simulation - measurement) / measurement",
        "",
        "## Flat zone, per stroke",
        "",
        "Means over the flat zone; F_t is the mean magnitude of the tangential force and",
        "μ_eff = mean F_t / mean F_n.",
        "",
        "| stroke | direction | samples | F_n sim [N] | F_n meas [N] | ΔF_n | F_t sim [N] "
        "| F_t meas [N] | ΔF_t | μ_eff sim | μ_eff meas | Δμ |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for row in comparison["strokes"]:
        sim, meas, rel = row["simulated"], row["measured"], row["relative_difference"]
        lines.append(
            f"| {row['index']} | {'+' if row['direction'] > 0 else '-'} | {row['samples']} "
            f"| {sim['normal_force']:.4g} | {meas['normal_force']:.4g} "
            f"| {_pct(rel['normal_force'])} | {sim['tangential_force']:.4g} "
            f"| {meas['tangential_force']:.4g} | {_pct(rel['tangential_force'])} "
            f"| {sim['friction_coefficient']:.3f} | {meas['friction_coefficient']:.3f} "
            f"| {_pct(rel['friction_coefficient'])} |")
    if not comparison["strokes"]:
        lines.append("| (no stroke has its whole flat zone inside the measurement) |"
                     + " |" * 11)
    largest = comparison["largest_flat_difference"]
    lines += [
        "",
        "Largest flat-zone difference of the stroke means: "
        f"F_n {_pct(largest['normal_force'])}, F_t {_pct(largest['tangential_force'])}, "
        f"μ_eff {_pct(largest['friction_coefficient'])}.",
        "",
        "## Reversal peaks",
        "",
        "Largest F_n and largest tangential force magnitude between two flat zones; ratio is",
        "simulation / measurement.",
        "",
        "| after stroke | F_n sim [N] | F_n meas [N] | ratio | F_t sim [N] | F_t meas [N] "
        "| ratio |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for row in comparison["reversals"]:
        sim, meas, ratio = row["simulated"], row["measured"], row["ratio"]
        lines.append(
            f"| {row['after_stroke']} | {sim['normal_force']:.4g} | {meas['normal_force']:.4g} "
            f"| {ratio['normal_force']:.2f} | {sim['tangential_force']:.4g} "
            f"| {meas['tangential_force']:.4g} | {ratio['tangential_force']:.2f} |")
    if not comparison["reversals"]:
        lines.append("| (no reversal between two complete flat zones) |" + " |" * 6)
    return "\n".join(lines) + "\n"


def write_comparison(aligned: Aligned, comparison: dict, directory: Path, sources: dict,
                     flat_speed_fraction: float) -> list[str]:
    """Write comparison.json, comparison.md and the plots into ``directory``; return names."""
    from exubrush.output.plotting import plot_comparison

    directory.mkdir(parents=True, exist_ok=True)
    record = {"sources": sources, "time_offset_s": aligned.time_offset,
              "flat_speed_fraction": flat_speed_fraction, **comparison}
    with atomic_file(directory / "comparison.json", "w") as handle:
        json.dump(record, handle, indent=2)
    with atomic_file(directory / "comparison.md", "w") as handle:
        handle.write(summary_markdown(comparison, sources, flat_speed_fraction,
                                      aligned.time_offset))
    title = f"{sources['model']} simulation vs {Path(sources['measurement']).name}"
    if sources.get("model_output"):
        title += " (model output, not measured)"
    label = "file (model output)" if sources.get("model_output") else "measured"
    plots = plot_comparison(aligned, comparison, title, directory, label)
    return ["comparison.json", "comparison.md", *plots]
