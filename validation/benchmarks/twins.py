"""Twins solved once against twins solved apart: how far the outputs differ.

Two tufts of seven filaments, swung side to side at 258 Hz on a slow stroke along the
handle (the sonic case's motion), pressed ``--distance`` onto the plane, run with
``solver.share_identical`` on and off. Prints the wall time of each and the largest
differences: forces and moments as a share of their largest value, positions in mm, and,
for the run solved apart, how far each tuft's filaments part from the tuft's first
(docs/decisions/0022).

    python validation/benchmarks/twins.py --distance 8.4 --periods 0.005
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from exubrush.parameters.io import load_case
from exubrush.simulation import simulate

TUFTS = Path(__file__).parent / "twin_tufts.toml"  # also the twins' test case


def share_of_peak(a: np.ndarray, b: np.ndarray) -> float:
    """Largest |a - b| over the largest |b| [-]."""
    return float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(b))), 1e-300))


def parting(results, tufts: list[range]) -> list[float]:
    """Per tuft, the largest distance [mm] between a filament's tip and the tuft's first
    filament's, each relative to its root."""
    roots = results.shape_nodes[0, :, 0, :]
    tips = results.tip_position - roots[None]
    return [float(np.max(np.abs(tips[:, list(tuft)] - tips[:, [tuft[0]]]))) for tuft in tufts]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--distance", type=float, default=8.4,
                        help="motion.interaction_distance [mm] (filaments 10.4 mm + 0.1 mm tip)")
    parser.add_argument("--periods", type=float, default=0.005,
                        help="motion.periods of the 4 s stroke (0.005: 0.02 s of swing)")
    args = parser.parse_args()
    runs = {}
    for share in ("true", "false"):
        start = time.perf_counter()
        runs[share] = simulate(load_case(str(TUFTS), [
            f"solver.share_identical={share}",
            f"motion.interaction_distance='{args.distance} mm'",
            f"motion.periods={args.periods}"]), progress=False)
        derived = runs[share].metadata["derived"]
        print(f"share_identical={share}: {derived['systems_solved']} systems, "
              f"{time.perf_counter() - start:.1f} s wall, "
              f"status {runs[share].metadata['status']}")
    once, each = runs["true"], runs["false"]
    print(f"normal force: {share_of_peak(once.normal_force, each.normal_force):.3g} of its peak;"
          f" mean {once.normal_force.mean():.6g} N against {each.normal_force.mean():.6g} N")
    print(f"tangential force: {share_of_peak(once.tangential_force, each.tangential_force):.3g}"
          " of its peak")
    for name in ("moment", "head_moment"):
        print(f"{name}: {share_of_peak(getattr(once.wrench, name), getattr(each.wrench, name)):.3g}"
              " of its peak")
    print(f"tip forces: {share_of_peak(once.tip_force, each.tip_force):.3g} of their peak")
    print(f"tips: {np.max(np.abs(once.tip_position - each.tip_position)):.3g} mm; shapes: "
          f"{np.max(np.abs(once.shape_nodes - each.shape_nodes)):.3g} mm")
    spread = parting(each, [range(0, 7), range(7, 14)])
    print("solved apart, each tuft's tips part from its first filament's by "
          + ", ".join(f"{s:.3g} mm" for s in spread))


if __name__ == "__main__":
    main()
