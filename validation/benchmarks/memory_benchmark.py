"""Peak memory of the solving processes against the number of slide periods.

    python validation/benchmarks/memory_benchmark.py [--case orthogonal] [--periods 1 2 4]
        [--workers 2] [--set KEY=VALUE ...]

Runs the case (default head) once per number of periods, each in a fresh process, and
prints the largest resident set (VmHWM, peak_memory.py) of a worker process and of the
main process. A worker solves one bristle group after another and returns each group's
time series, so its peak should not grow with the periods beyond that one group's output;
the main process holds the whole head's results, which do.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

RUN = """
import json, sys, time
sys.path.insert(0, {here!r})
from peak_memory import PeakMemory
from exubrush import load_case, simulate
if __name__ == "__main__":
    case, overrides, workers = json.loads(sys.argv[1])
    parameters = load_case(case, overrides)
    with PeakMemory() as peak:
        start = time.perf_counter()
        results = simulate(parameters, progress=False, workers=workers)
        wall = time.perf_counter() - start
    # no worker seen: the groups were solved in the main process
    print(json.dumps({{"wall_s": wall, "status": results.metadata["status"],
                      "worker_mb": peak.children_mb or peak.self_mb, "main_mb": peak.self_mb}}))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="orthogonal")
    parser.add_argument("--periods", type=float, nargs="+", default=[1.0, 2.0, 4.0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE")
    args = parser.parse_args()
    print("| periods | wall time [s] | peak per worker [MB] | peak of the main process [MB] |")
    print("| --- | --- | --- | --- |")
    for periods in args.periods:
        overrides = [*args.overrides, f"motion.periods={periods:g}"]
        done = subprocess.run(
            [sys.executable, "-c", RUN.format(here=str(HERE)),
             json.dumps([args.case, overrides, args.workers])],
            capture_output=True, text=True, check=False)
        if done.returncode != 0:
            raise SystemExit(f"the run with {periods:g} periods failed:\n{done.stderr[-2000:]}")
        report = json.loads(done.stdout.strip().splitlines()[-1])
        if report["status"] != "completed":
            raise SystemExit(f"the run with {periods:g} periods ended {report['status']}")
        print(f"| {periods:g} | {report['wall_s']:.1f} | {report['worker_mb']:.1f} "
              f"| {report['main_mb']:.1f} |", flush=True)


if __name__ == "__main__":
    main()
