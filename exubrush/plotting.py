"""Headless plots of results (matplotlib, Agg back end)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot_forces(results, target) -> None:
    """F_n, F_t and μ_eff against travelled distance, written as PNG to ``target``."""
    distance = results.travelled_distance
    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    axes[0].plot(distance, results.normal_force, lw=0.8)
    axes[0].set_ylabel("normal force [N]")
    axes[1].plot(distance, results.tangential_force, lw=0.8, color="tab:orange")
    axes[1].set_ylabel("tangential force [N]")
    axes[2].plot(distance, results.friction_coefficient, lw=0.8, color="tab:green")
    axes[2].set_ylabel("|F_t| / F_n [-]")
    axes[2].set_xlabel("travelled distance [mm]")
    meta = results.metadata
    status = meta.get("status", "completed")
    partial = "" if status == "completed" else f" - PARTIAL, {status}"
    fig.suptitle(f"exubrush {meta.get('case', '')}: {meta.get('model', '')} model "
                 f"(simulation){partial}")
    for axis in axes:
        axis.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(target, format="png", dpi=120)
    plt.close(fig)
