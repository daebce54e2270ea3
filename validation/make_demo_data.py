"""Write the demonstration "measurement" for ``exubrush compare`` -- made by a model run.

No measured data ships with the paper, so ``exubrush compare`` is demonstrated on a file
produced by a converged exubrush run (DFM, 12 segments, orthogonal case, default head). The
file says so in its name and its header, with the command that made it. It is model output
and must never be presented as experimental data.

    python validation/make_demo_data.py [--out validation/data]
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

from exubrush.parameters.io import load_case
from exubrush.simulation import simulate

NAME = "MODEL-OUTPUT-demo-orthogonal-dfm12.csv"
SEGMENTS = 12


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "data")
    args = parser.parse_args()
    case = load_case("orthogonal", ["model.kind='dfm'", f"model.segments={SEGMENTS}"])
    results = simulate(case, progress=True)
    if results.metadata["status"] != "completed":
        raise SystemExit(f"the model run did not complete: {results.metadata['message']}")
    args.out.mkdir(parents=True, exist_ok=True)
    target = args.out / NAME
    temporary = target.with_name(f".{NAME}.partial")
    versions = results.metadata["versions"]
    with temporary.open("w", newline="") as handle:
        handle.write(
            "# NOT MEASURED DATA: exubrush model output for demonstrating 'exubrush compare'.\n"
            f"# made by: python validation/make_demo_data.py (exubrush {versions['exubrush']}, "
            f"Exudyn {versions['exudyn']}): orthogonal case, default head, DFM model with "
            f"{SEGMENTS} segments, default solver settings.\n"
            "# schema: time, slider displacement, head normal and tangential force, units in the "
            "header (see validation/data/README.md).\n")
        writer = csv.writer(handle)
        writer.writerow(["time [s]", "slider_position [mm]", "normal_force [N]",
                         "tangential_force [N]"])
        for row in zip(results.time, results.slider_position, results.normal_force,
                       results.tangential_force, strict=True):
            writer.writerow([f"{value:.6g}" for value in row])
    temporary.replace(target)
    print(f"written {target} ({len(results.time)} rows, {results.metadata['wall_time_s']:.0f} s)")


if __name__ == "__main__":
    main()
