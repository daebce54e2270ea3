"""Exudyn's own timers on one bristle: where a solve spends its time.

    python validation/benchmarks/profile_bristle.py [--case orthogonal] [--model dfm|prb]
        [--periods 1] [--bristle 0] [--group] [--set KEY=VALUE ...]

Builds one bristle of the case's head as exubrush does (the drive set before every step),
or with ``--group`` the whole group it is solved in (the bristles that can touch it, with
contact.between_bristles), and solves it in this process with Exudyn's computation-time
statistics on. Exudyn's fast core has no timers, so this script loads the checked one
(EXUBRUSH_EXUDYN_CHECKS=1): the shares are those of the checked core, the wall time is
longer than a run's.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ["EXUBRUSH_EXUDYN_CHECKS"] = "1"  # before exubrush chooses Exudyn's core

from one_bristle import add_arguments, build  # noqa: E402

from exubrush.run.solve import solver_statistics  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser, case="orthogonal", bristle=0, group=True)
    args = parser.parse_args()
    _, scene, settings = build(parser, args, group=args.group)
    settings.show.computationTime = True  # printed by Exudyn at the end of the solve
    settings.timeIntegration.verboseMode = 1

    scene.mbs.SetPreStepUserFunction(scene.run_step_hooks)
    start = time.perf_counter()
    scene.mbs.SolveDynamic(settings)
    print(f"wall {time.perf_counter() - start:.3f} s, "
          f"{solver_statistics(scene.mbs, scene.line_search)}")


if __name__ == "__main__":
    main()
