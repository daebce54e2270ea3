"""Plots of results, drawn headless with matplotlib's Figure objects.

No pyplot and no back-end switch: a notebook that imports exubrush keeps its own back end,
and PNG files are written on any machine, with or without a display.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from exubrush.models.geometry import head_bristles
from exubrush.output.cleaning import footprint, gap_depth_history
from exubrush.output.metrics import friction_coefficient, travelled_distance
from exubrush.output.vibration import ROTATION_PLANES
from exubrush.parameters.surface_kinds import TOOTH_ROW
from exubrush.util.files import atomic_file


def figure(rows: int, columns: int = 1, **options):
    """A figure and its axes (a 2-D array if ``squeeze=False``), with no pyplot state."""
    fig = Figure(figsize=options.pop("figsize", None))
    return fig, fig.subplots(rows, columns, **options)


def plot_forces(results, target) -> None:
    """F_n, F_t and μ_eff against travelled distance (against time where the head does
    not slide, motion.profile "none"), written as PNG to ``target``."""
    distance = results.travelled_distance
    sliding = len(distance) > 0 and distance[-1] > 0.0
    x = distance if sliding else results.time
    fig, axes = figure(3, 1, figsize=(8, 8), sharex=True)
    axes[0].plot(x, results.normal_force, lw=0.8)
    axes[0].set_ylabel("normal force [N]")
    axes[1].plot(x, results.tangential_force, lw=0.8, color="tab:orange")
    axes[1].set_ylabel("tangential force [N]" if sliding else "force along the slide axis [N]")
    axes[2].plot(x, results.friction_coefficient, lw=0.8, color="tab:green")
    axes[2].set_ylabel("|F_t| / F_n [-]")
    axes[2].set_xlabel("travelled distance [mm]" if sliding else "time [s]")
    meta = results.metadata
    status = meta.get("status", "completed")
    partial = "" if status == "completed" else f" - PARTIAL, {status}"
    fig.suptitle(f"exubrush {meta.get('case', '')}: {meta.get('model', '')} model "
                 f"(simulation){partial}")
    for axis in axes:
        axis.grid(True, alpha=0.3)
    # fixed margins: tight_layout's measuring draw was a third of the run's plotting time
    fig.subplots_adjust(left=0.11, right=0.97, bottom=0.07, top=0.94, hspace=0.12)
    fig.savefig(target, format="png", dpi=120)


def _series_axes(axes, x, aligned, xlabel, reference_label="measured"):
    """F_n, F_t and |F_t|/F_n of simulation and measurement against ``x`` on three axes."""
    for series, label, style in ((aligned.measured, reference_label, dict(color="0.3", lw=0.8)),
                                 (aligned.simulated, "simulation", dict(color="tab:blue",
                                                                        lw=1.0))):
        ratio = friction_coefficient(series.normal_force, series.tangential_force)
        axes[0].plot(x, series.normal_force, label=label, **style)
        axes[1].plot(x, series.tangential_force, **style)
        axes[2].plot(x, ratio, **style)
    axes[0].set_ylabel("normal force [N]")
    axes[1].set_ylabel("tangential force [N]")
    axes[2].set_ylabel("|F_t| / F_n [-]")
    axes[2].set_xlabel(xlabel)
    axes[0].legend(loc="best", fontsize=8)
    for axis in axes:
        axis.grid(True, alpha=0.3)


def plot_comparison(aligned, comparison, title, directory,
                    reference_label="measured") -> list[str]:
    """Write the whole-run, flat-zone and one-period comparison plots; return file names.

    ``reference_label`` names the file's curve in the legends. Flat zone: the last stroke
    with a complete flat zone (shaded). One period: the last two
    consecutive strokes that the measurement covers, reversal to reversal, forces against
    slider position.
    """
    names = []
    rows = comparison["strokes"]
    distance = travelled_distance(aligned.slider_position)
    fig, axes = figure(3, 1, figsize=(9, 8), sharex=True)
    _series_axes(axes, distance, aligned, "travelled distance [mm] (simulated slider)",
                 reference_label)
    for row in rows:
        mask = (aligned.time >= row["flat_start"]) & (aligned.time <= row["flat_end"])
        for axis in axes:
            axis.axvspan(distance[mask][0], distance[mask][-1], color="tab:green", alpha=0.08)
    fig.suptitle(f"{title}\nwhole run (flat zones shaded)", fontsize=10)
    names.append(_save(fig, directory, "compare_run.png"))
    if rows:
        last = rows[-1]
        margin = 0.15 * (last["flat_end"] - last["flat_start"])
        mask = ((aligned.time >= last["flat_start"] - margin)
                & (aligned.time <= last["flat_end"] + margin))
        fig, axes = figure(3, 1, figsize=(9, 8), sharex=True)
        _series_axes(axes, aligned.time[mask], _masked(aligned, mask), "time [s]", reference_label)
        for axis in axes:
            axis.axvspan(last["flat_start"], last["flat_end"], color="tab:green", alpha=0.08)
        fig.suptitle(f"{title}\nflat zone of stroke {last['index']}", fontsize=10)
        names.append(_save(fig, directory, "compare_flat.png"))
    if len(rows) >= 2 and rows[-1]["index"] == rows[-2]["index"] + 1:
        first, last = rows[-2], rows[-1]
        mask = ((aligned.time >= first["start"]) & (aligned.time <= last["end"]))
        fig, axes = figure(3, 1, figsize=(9, 8), sharex=True)
        _series_axes(axes, aligned.slider_position[mask], _masked(aligned, mask),
                     "slider position [mm] (simulated slider)", reference_label)
        fig.suptitle(f"{title}\none period (strokes {first['index']} and {last['index']})",
                     fontsize=10)
        names.append(_save(fig, directory, "compare_period.png"))
    return names


def _masked(aligned, mask):
    from dataclasses import replace

    def cut(series):
        return replace(series, **{k: getattr(series, k)[mask] for k in
                                  ("time", "slider_position", "normal_force",
                                   "tangential_force")})

    return replace(aligned, simulated=cut(aligned.simulated), measured=cut(aligned.measured))


def _save(fig, directory, name) -> str:
    fig.tight_layout()
    with atomic_file(directory / name, "wb") as handle:
        fig.savefig(handle, format="png", dpi=110)
    return name


def plot_cleaning(results, summary: dict, contacts, target) -> None:
    """Footprint of contact on the surface, tips in contact against time, on a tooth row
    the deepest tip in a gap against time (elsewhere the wiped area per stroke), and each
    bristle's force share; PNG to ``target``. ``contacts``: the run's
    exubrush.output.cleaning.TipContacts."""
    case = results.case()
    surface = case.surface
    radius = [b.tip_radius for b in head_bristles(case.head)]
    teeth = surface.kind == TOOTH_ROW
    fig, axes = figure(2, 2, figsize=(11, 8), squeeze=False)
    counts, x_edges, y_edges = footprint(results.time, contacts, cell=0.25)
    image = axes[0][0].pcolormesh(x_edges, y_edges, counts.T, cmap="viridis")
    fig.colorbar(image, ax=axes[0][0], label="contact time per 0.25 mm cell [tip-s]")
    axes[0][0].set_aspect("equal")
    axes[0][0].set_xlabel("surface x [mm]")
    axes[0][0].set_ylabel("surface y [mm]")
    axes[0][0].set_title("footprint of the contact points", fontsize=9)
    axes[0][1].plot(results.time, contacts.touching.sum(axis=1), lw=0.8)
    axes[0][1].set_ylabel("tips in contact")
    axes[0][1].set_xlabel("time [s]")
    if teeth:
        depth_axis = axes[1][0]
        depth_axis.plot(results.time, gap_depth_history(surface, results.tip_position, radius),
                        lw=0.8, color="tab:red")
        depth_axis.set_ylabel("deepest tip below the tooth tops [mm]")
        depth_axis.set_xlabel("time [s]")
        depth_axis.set_title("interdental penetration", fontsize=9)
    else:
        stroke_axis = axes[1][0]
        wiped = [s["wiped_area_mm2"] for s in summary["strokes"]]
        stroke_axis.bar(np.arange(len(wiped)), wiped, color="tab:green")
        stroke_axis.set_xlabel("stroke (the first and an unfinished last one are partial)")
        stroke_axis.set_ylabel("wiped area [mm²]")
        stroke_axis.set_title(f"area swept by the contact patches ({summary['grid_mm']:g} mm "
                              "grid)", fontsize=9)
    strokes = [s for s in summary["strokes"] if s["whole"]] or summary["strokes"]
    if strokes:
        share = np.mean([s["force_share"] for s in strokes], axis=0)
        axes[1][1].bar(np.arange(len(share)), 100.0 * share, color="tab:purple")
    axes[1][1].set_xlabel("bristle")
    axes[1][1].set_ylabel("share of the normal force [%]")
    axes[1][1].set_title("force share, mean over the whole strokes", fontsize=9)
    for axis in (axes[0][1], axes[1][0], axes[1][1]):
        axis.grid(True, alpha=0.3)
    fig.suptitle(f"exubrush {results.metadata.get('case', '')}: what the brush cleans on the "
                 f"{surface.kind} (simulation)", fontsize=10)
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.08, top=0.92, wspace=0.28, hspace=0.32)
    fig.savefig(target, format="png", dpi=110)


def plot_vibration(results, entries: list[dict], amplitudes: list, target) -> None:
    """For each sine pose term that was measured, every tip's amplitude against its
    distance from the pivot's axis (a turn) or from the head's centre (a shake), with the
    head's own amplitude as a line; PNG to ``target`` (exubrush.output.vibration)."""
    measured = [(e, a) for e, a in zip(entries, amplitudes, strict=True) if a is not None]
    fig, axes = figure(1, len(measured), figsize=(5.5 * len(measured), 4.5), squeeze=False)
    case = results.case()
    roots = np.array([b.root for b in head_bristles(case.head)])
    pivot = np.asarray(case.motion.pivot)
    for axis, (entry, amplitude) in zip(axes[0], measured, strict=True):
        if entry["unit"] == "rad":
            u, v = ROTATION_PLANES[entry["axis"]]
            distance = np.hypot(roots[:, u] - pivot[u], roots[:, v] - pivot[v])
            label = f"root's distance from the {entry['axis'][1]} axis through the pivot [mm]"
            scale, unit = 180.0 / np.pi, "deg"
        else:
            distance = np.hypot(roots[:, 0], roots[:, 1])
            label, scale, unit = "root's distance from the head's centre [mm]", 1.0, "mm"
        axis.plot(distance, amplitude * scale, ".", ms=3, label="tips")
        axis.axhline(entry["head_amplitude"] * scale, color="tab:red", lw=1.0, label="head")
        axis.set_xlabel(label)
        axis.set_ylabel(f"amplitude at {entry['frequency_Hz']:.4g} Hz [{unit}]")
        axis.set_title(f"{entry['term']} ({entry['axis']}): tips / head "
                       f"{entry['amplification_median']:.3g} (median)", fontsize=9)
        axis.legend(fontsize=8)
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.14, top=0.9, wspace=0.3)
    fig.savefig(target, format="png", dpi=100)
