"""Peak memory of the solving processes against the number of slide periods.

    python validation/benchmarks/memory_benchmark.py [--case orthogonal] [--periods 1 2 4]
        [--workers 2] [--set KEY=VALUE ...] [--tree SOURCE_TREE]

Runs the case (default head) once per number of periods, each in a fresh process (the
benchmark harness's ``run_in_tree``), and prints the largest resident set (VmHWM,
peak_memory.py) of a worker process and of the main process. A worker solves one bristle
group after another and returns each group's time series, so its peak should not grow with
the periods beyond that one group's output; the main process holds the whole head's
results, which do. ``--tree`` measures another source tree of exubrush (an older commit:
``git worktree add ../tree-old COMMIT``).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from benchmark import run_in_tree

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare

TREE = Path(__file__).resolve().parents[2]  # this source tree


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="orthogonal")
    parser.add_argument("--periods", type=float, nargs="+", default=[1.0, 2.0, 4.0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE")
    parser.add_argument("--tree", type=Path, default=TREE,
                        help="the exubrush source tree to run (default: this one)")
    args = parser.parse_args()
    if not (args.tree / "exubrush" / "__init__.py").is_file():
        parser.error(f"--tree {args.tree}: no exubrush package in that tree")
    for periods in args.periods:  # every case is valid before anything runs
        try:
            prepare(load_case(args.case, [*args.overrides, f"motion.periods={periods:g}"]))
        except ParameterError as err:
            parser.error(str(err))
    print("| periods | wall time [s] | peak per worker [MB] | peak of the main process [MB] |")
    print("| --- | --- | --- | --- |")
    for periods in args.periods:
        overrides = [*args.overrides, f"motion.periods={periods:g}"]
        results, report = run_in_tree(args.tree, "simulate", args.case, overrides, args.workers)
        status = results.metadata["status"]
        if status != "completed":
            raise SystemExit(f"the run with {periods:g} periods ended {status}")
        print(f"| {periods:g} | {report['wall']:.1f} | {report['peak_memory_mb']:.1f} "
              f"| {report['main_memory_mb']:.1f} |", flush=True)


if __name__ == "__main__":
    main()
