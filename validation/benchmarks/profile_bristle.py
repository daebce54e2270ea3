"""Exudyn's own timers on one bristle: where a solve spends its time.

    python validation/benchmarks/profile_bristle.py [--case orthogonal] [--model dfm|prb]
        [--periods 1] [--bristle 0] [--set KEY=VALUE ...]

Builds one bristle of the case's head as exubrush does (the drive set before every step)
and solves it in this process with Exudyn's computation-time statistics on. Exudyn's fast
core has no timers, so this script loads the checked one (EXUBRUSH_EXUDYN_CHECKS=1): the
shares are those of the checked core, the wall time is longer than a run's.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ["EXUBRUSH_EXUDYN_CHECKS"] = "1"  # before exubrush chooses Exudyn's core

from exubrush.parameters.io import load_case  # noqa: E402
from exubrush.prepared import prepare  # noqa: E402
from exubrush.scene import build_scene  # noqa: E402
from exubrush.solve import group_settings, solver_statistics  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="orthogonal")
    parser.add_argument("--model", default="dfm", choices=["dfm", "prb"])
    parser.add_argument("--periods", type=float, default=1.0)
    parser.add_argument("--bristle", type=int, default=0, help="index in the head")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE")
    args = parser.parse_args()
    case = load_case(args.case, [f"model.kind='{args.model}'",
                                 f"motion.periods={args.periods:g}", *args.overrides])
    prepared = prepare(case)
    scene = build_scene(prepared, (args.bristle,))
    settings = group_settings(prepared, scene, (args.bristle,))
    settings.show.computationTime = True  # printed by Exudyn at the end of the solve
    settings.timeIntegration.verboseMode = 1

    scene.mbs.SetPreStepUserFunction(scene.run_step_hooks)
    start = time.perf_counter()
    scene.mbs.SolveDynamic(settings)
    print(f"wall {time.perf_counter() - start:.3f} s, {solver_statistics(scene.mbs)}")


if __name__ == "__main__":
    main()
