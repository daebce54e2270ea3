"""What a setting does to a case's forces and run time over seeds: the first whole stroke's
flat-zone means, the reversal peaks and the solve time, before and after.

    python validation/benchmarks/setting_forces.py [--case validation/benchmarks/tuft7.toml]
        [--periods 1] [--seeds 1 2 3 4 5 6] [--before KEY=VALUE ...] [--after KEY=VALUE ...]

Runs ``simulate`` on the case for each root-tilt seed (``head.seed``), once with the
``--before`` overrides and once with the ``--after`` ones, each run a fresh process
(benchmark.run_in_tree), and prints per seed and summed over the seeds: the first whole
stroke's flat-zone mean F_n and F_t (exubrush.output.reversal.stroke_flat_means), the
largest relative change of a reversal peak, and the groups' solve time. Touching filaments
settle into one of several arrangements by seed and by Newton's path (docs/decisions/0023):
the sums over seeds tell a setting's bias from an arrangement's jump. Issue 47 asks a lever
to keep the sums within 1 % (flat zones) and the peaks within 5 % (docs/decisions/0026).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from benchmark import run_in_tree

from exubrush.output.experiment import ForceSeries
from exubrush.output.reversal import FLAT_SPEED, reversal_metrics, stroke_flat_means
from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case

ROOT = Path(__file__).parents[2]  # the source tree whose exubrush runs


def stroke_figures(results) -> dict:
    """First whole stroke's flat-zone means [N], the reversal peaks [N] and the solve time
    [s] of one run."""
    series = ForceSeries.from_results(results)
    first = stroke_flat_means(series, FLAT_SPEED)[0]
    return {"normal": first["normal_force"], "tangential": first["tangential_force"],
            "peaks": reversal_metrics(series)["peaks"],
            "solve": results.metadata["solver_wall_time_s_sum"],
            "jacobians": results.metadata["solver_statistics"]["jacobian_updates"]}


def compare(before: dict[int, dict], after: dict[int, dict]) -> dict:
    """Per seed and summed over the seeds, the relative changes of after against before:
    flat F_n and F_t, the largest change of a reversal peak, and the solve time's ratio."""
    seeds = sorted(before)
    rows = {}
    for seed in seeds:
        b, a = before[seed], after[seed]
        rows[seed] = {
            "normal": a["normal"] / b["normal"] - 1.0,
            "tangential": a["tangential"] / b["tangential"] - 1.0,
            "peak": max(abs(x / y - 1.0) for x, y in zip(a["peaks"], b["peaks"], strict=False)),
        }
    total = {key: sum(run[key] for run in before.values()) for key in ("normal", "tangential",
                                                                       "solve")}
    changed = {key: sum(run[key] for run in after.values()) for key in total}
    return {"seeds": rows,
            "normal": changed["normal"] / total["normal"] - 1.0,
            "tangential": changed["tangential"] / total["tangential"] - 1.0,
            "peak": max(row["peak"] for row in rows.values()),
            "speed_up": total["solve"] / changed["solve"]}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="validation/benchmarks/tuft7.toml")
    parser.add_argument("--periods", type=float, default=1.0)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5, 6])
    parser.add_argument("--before", nargs="*", default=[], metavar="KEY=VALUE")
    parser.add_argument("--after", nargs="*", default=[], metavar="KEY=VALUE")
    args = parser.parse_args()
    if not args.periods >= 1.0:
        parser.error(f"--periods {args.periods:g}: a whole stroke and a reversal after it "
                     "need 1 period or more")
    if min(args.seeds) < 0 or len(set(args.seeds)) != len(args.seeds):
        parser.error(f"--seeds {' '.join(map(str, args.seeds))}: give distinct seeds >= 0")
    if args.before == args.after:
        parser.error("--before and --after are the same: give the setting to compare")
    for overrides in (args.before, args.after):  # a bad case or value: one line, not a run
        try:
            load_case(args.case, [f"motion.periods={args.periods:g}",
                                  f"head.seed={max(args.seeds)}", *overrides])
        except ParameterError as error:
            parser.error(str(error))
    runs: dict[str, dict[int, dict]] = {"before": {}, "after": {}}
    for seed in args.seeds:
        for label, overrides in (("before", args.before), ("after", args.after)):
            results, _ = run_in_tree(ROOT, "simulate", args.case,
                                     [f"motion.periods={args.periods:g}",
                                      f"head.seed={seed}", *overrides], 1)
            if not results.metadata["completed"]:
                raise SystemExit(f"seed {seed} ({label}): the run did not complete: "
                                 f"{results.metadata['message']}")
            runs[label][seed] = stroke_figures(results)
            run = runs[label][seed]
            print(f"seed {seed} {label:6s}: flat F_n {1e3 * run['normal']:.3f} mN, F_t "
                  f"{1e3 * run['tangential']:.3f} mN, solve {run['solve']:.1f} s, "
                  f"{run['jacobians']} Jacobians", flush=True)
    result = compare(runs["before"], runs["after"])
    for seed, row in result["seeds"].items():
        print(f"seed {seed}: F_n {100 * row['normal']:+.3f} %, F_t {100 * row['tangential']:+.3f} %"
              f", peaks within {100 * row['peak']:.3f} %")
    print(f"over the seeds: flat F_n {100 * result['normal']:+.2f} %, F_t "
          f"{100 * result['tangential']:+.2f} %, peaks within {100 * result['peak']:.2f} %, "
          f"solve {result['speed_up']:.2f}x faster")


if __name__ == "__main__":
    main()
