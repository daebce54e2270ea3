"""What contact between filaments, a tooth row and a powered head cost, against targets.

    python validation/benchmarks/contact_cost.py [--only ROW ...] [--repeat 1]
        [--seeds N ...] [--code LABEL=SOURCE_TREE ...] [--out validation/results/benchmarks]

Each row is a pair (or set) of runs whose wall times are compared with a target:

- ``tuft window``: the ``tuft`` case (37 filaments), approach and 0.1 period, with contact
  between the filaments against without (target: at most 20x, issue 47; the 3x before it was
  out of reach); without, every filament is
  solved (``solver.share_identical=false``: twins solved once would make the free run 37
  times cheaper, and the row is about what touching costs a filament that is solved; a
  source tree before 0.16.0 does not know the key, and solves every filament anyway: drop
  it there);
- ``19 filaments``: the same window on ``tuft7.toml`` with 19 filaments in a 1.2 mm hole,
  with contact against without, every filament solved (target: at most 10x, issue 47);
- ``tuft period``: the same with contact, approach and one period (target: under 120 s);
- ``filaments``: tufts of 7, 19, 37 and 61 filaments (``tuft7.toml`` in 0.8, 1.2, 1.6 and
  2.0 mm holes), approach and 0.1 period with contact: the wall time per filament (target:
  the largest within 1.5x of the smallest);
- ``blade head``: the paper's head (``orthogonal``), approach and 0.1 period, with contact
  between its blades against without (target: at most 15x, issue 47; 5x before);
- ``tooth row``: ``interdental`` against ``orthogonal``, approach and half a period
  (target: at most 1.5x);
- ``oscillating-rotating``: the round head of 703 filaments, approach and 0.5 s of turning,
  filaments passing through each other as the case has it (target: under 600 s; the
  target asks it with contact between the filaments once that is the tufted heads'
  default);
- ``sonic``: the manual head of 1,480 filaments swung at 258 Hz, approach and 0.5 s of
  brushing, filaments passing through each other (target: under 600 s, as above);
  ``sonic window``: the same with 0.05 s of brushing (no target: the row a session can
  afford, its time per filament and step counts).

``--seeds 1 2 3`` runs every run once per root-tilt seed (``head.seed``) and makes each
row's figure from the runs' wall times summed over the seeds: touching filaments settle
into one of several arrangements, which one depends on the seed and on Newton's path, and
one arrangement's window cost 3.5x another's on a 19-filament tuft (docs/decisions/0023),
so a figure from one seed compares arrangements as much as code.

Every run is a fresh process (benchmark.run_in_tree) that times ``simulate`` alone.
``--code old=/path/to/old/checkout new=.`` runs each row with each source tree in turn
(old, new, old, new, ...), and compares the forces of every later tree's run with the
first tree's (benchmark.errors: flat-zone means per stroke, reversal peaks, tips), so the
old solver's accuracy and time sit beside the new one's. Without ``--code`` this tree runs
alone. A run that took N Jacobians is also worth its counts (run.json's
``solver_statistics``): timings depend on what else the machine runs.

Output in ``--out``: ``contact-cost.md`` and ``.csv``.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from benchmark import (  # noqa: E402  (a script beside this one)
    errors,
    output_folder,
    run_in_tree,
    source_trees,
)

from exubrush.util.files import write_csv  # noqa: E402

HERE = Path(__file__).parent
CONTACT = "contact.between_bristles=true"
NO_CONTACT = "contact.between_bristles=false"
EACH = "solver.share_identical=false"  # every filament solved, none taken from a twin
# filaments and the hole that holds them hexagonally packed (tuft7.toml's packing)
TUFTS = {7: "0.8 mm", 19: "1.2 mm", 37: "1.6 mm", 61: "2.0 mm"}


def _tuft_file(folder: Path, filaments: int) -> str:
    """tuft7.toml with ``filaments`` in their hole (TUFTS), written into ``folder``."""
    text = (HERE / "tuft7.toml").read_text()
    text = text.replace("filaments = 7", f"filaments = {filaments}").replace(
        'diameter = "0.8 mm"', f'diameter = "{TUFTS[filaments]}"')
    path = folder / f"tuft{filaments}.toml"
    path.write_text(text)
    return str(path)


def rows(folder: Path) -> dict[str, dict]:
    """Each row: its runs as label -> (case, overrides), how its figure is made from their
    wall times (``figure``), the target and what the figure means."""
    nineteen = _tuft_file(folder, 19)
    return {
        "tuft window": {
            "runs": {"contact": ("tuft", ["motion.periods=0.1", CONTACT]),
                     "free": ("tuft", ["motion.periods=0.1", NO_CONTACT, EACH])},
            "figure": lambda w: w["contact"] / w["free"], "target": 20.0,
            "unit": "x (contact / free)"},
        "19 filaments": {
            "runs": {"contact": (nineteen, ["motion.periods=0.1"]),
                     "free": (nineteen, ["motion.periods=0.1", NO_CONTACT, EACH])},
            "figure": lambda w: w["contact"] / w["free"], "target": 10.0,
            "unit": "x (contact / free)"},
        "tuft period": {
            "runs": {"contact": ("tuft", ["motion.periods=1", CONTACT])},
            "figure": lambda w: w["contact"], "target": 120.0, "unit": "s"},
        "filaments": {
            "runs": {f"{n}": (_tuft_file(folder, n), ["motion.periods=0.1"]) for n in TUFTS},
            "figure": lambda w: (max(w[str(n)] / n for n in TUFTS)
                                 / min(w[str(n)] / n for n in TUFTS)),
            "target": 1.5, "unit": "x (largest / smallest s per filament)"},
        "blade head": {
            "runs": {"contact": ("orthogonal", ["motion.periods=0.1", CONTACT]),
                     "free": ("orthogonal", ["motion.periods=0.1"])},
            "figure": lambda w: w["contact"] / w["free"], "target": 15.0,
            "unit": "x (contact / free)"},
        "tooth row": {
            "runs": {"interdental": ("interdental", ["motion.periods=0.5"]),
                     "plane": ("orthogonal", ["motion.periods=0.5"])},
            "figure": lambda w: w["interdental"] / w["plane"], "target": 1.5,
            "unit": "x (tooth row / plane)"},
        "oscillating-rotating": {
            "runs": {"case": ("oscillating-rotating", [])},
            "figure": lambda w: w["case"], "target": 600.0, "unit": "s"},
        "sonic": {
            "runs": {"case": ("sonic", [])},
            "figure": lambda w: w["case"], "target": 600.0, "unit": "s"},
        "sonic window": {
            "runs": {"case": ("sonic", ["motion.periods=0.0125"])},
            "figure": lambda w: w["case"], "target": float("inf"), "unit": "s"},
    }


def measure(row: dict, code: dict[str, Path], repeat: int,
            seeds: list[int] | None = None) -> list[dict]:
    """Run every run of ``row`` with every tree of ``code`` ``repeat`` times, trees in
    turn, once per seed of ``seeds`` (``head.seed``; None: the case's own); one record per
    run, seed and tree (median wall time, counts, errors against the first tree's
    forces)."""
    records = []
    for label, (case, base) in row["runs"].items():
        for seed in seeds or [None]:
            overrides = base if seed is None else [*base, f"head.seed={seed}"]
            records += _measure_run(label, seed, case, overrides, code, repeat)
    return records


def _measure_run(label: str, seed: int | None, case: str, overrides: list[str],
                 code: dict[str, Path], repeat: int) -> list[dict]:
    walls: dict[str, list[float]] = {tree: [] for tree in code}
    first = {}
    for _ in range(repeat):
        for tree_label, tree in code.items():
            results, report = run_in_tree(tree, "simulate", case, overrides, None)
            walls[tree_label].append(report["wall"])
            first.setdefault(tree_label, results)
    reference = first[next(iter(code))]
    records = []
    for tree_label in code:
        results = first[tree_label]
        meta = results.metadata
        record = {"run": label, "seed": seed, "code": tree_label,
                  "wall_time_s": statistics.median(walls[tree_label]),
                  "completed": meta["completed"],
                  **meta["solver_statistics"],
                  "deepest_overlap_um": 1e3 * meta["derived"].get("bristle_overlap_max_mm",
                                                                  0.0)}
        if results is not reference:
            record.update({f"vs_{next(iter(code))}_{key}": value for key, value
                           in errors(results, reference).items()})
        records.append(record)
        seeded = "" if seed is None else f" seed {seed}"
        print(f"  {label}{seeded} [{tree_label}]: {record['wall_time_s']:.1f} s, "
              f"{record['steps']} steps, {record['jacobian_updates']} Jacobians", flush=True)
    return records


def summed_walls(records: list[dict], tree_label: str) -> dict[str, float]:
    """Each run's wall time [s] for the tree ``tree_label``, summed over its seeds."""
    walls: dict[str, float] = {}
    for record in records:
        if record["code"] == tree_label:
            walls[record["run"]] = walls.get(record["run"], 0.0) + record["wall_time_s"]
    return walls


def write(out: Path, table: list[dict], runs: list[dict], machine: str) -> None:
    """contact-cost.md (targets, then every run) and contact-cost.csv (every run)."""
    lines = [f"# Contact cost ({machine})", "",
             "| row | code | figure | target | met |", "| --- | --- | --- | --- | --- |"]
    for entry in table:
        lines.append(f"| {entry['row']} | {entry['code']} | {entry['figure']:.2f} "
                     f"{entry['unit']} | {entry['target']:g} | "
                     f"{'yes' if entry['figure'] <= entry['target'] else 'no'} |")
    keys = list(dict.fromkeys(key for run in runs for key in run))
    lines += ["", "| " + " | ".join(keys) + " |", "|" + " --- |" * len(keys)]
    for run in runs:
        lines.append("| " + " | ".join(_cell(run.get(key)) for key in keys) + " |")
    (out / "contact-cost.md").write_text("\n".join(lines) + "\n")
    write_csv(out / "contact-cost.csv", keys, ([run.get(key) for key in keys] for run in runs))


def _cell(value) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return "" if value is None else str(value)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", metavar="ROW",
                        choices=["tuft window", "19 filaments", "tuft period", "filaments",
                                 "blade head", "tooth row", "oscillating-rotating", "sonic",
                                 "sonic window"])
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--seeds", type=int, nargs="+", metavar="N",
                        help="run each run once per root-tilt seed (head.seed) and sum")
    parser.add_argument("--code", nargs="+", metavar="LABEL=SOURCE_TREE")
    parser.add_argument("--out", type=Path,
                        default=HERE.parent / "results" / "benchmarks")
    args = parser.parse_args()
    code = source_trees(parser, args.code, "this")
    if not 1 <= args.repeat <= 20:
        parser.error(f"--repeat {args.repeat}: give 1 to 20 runs per tree")
    if args.seeds and (min(args.seeds) < 0 or len(set(args.seeds)) != len(args.seeds)):
        parser.error(f"--seeds {' '.join(map(str, args.seeds))}: give distinct seeds >= 0")
    machine = output_folder(parser, args.out)
    table, runs = [], []
    with tempfile.TemporaryDirectory() as folder:
        every = rows(Path(folder))
        for name in args.only or every:
            row = every[name]
            print(f"{name} ...", flush=True)
            records = measure(row, code, args.repeat, args.seeds)
            runs += [{"row": name, **record} for record in records]
            for tree_label in code:
                figure = row["figure"](summed_walls(records, tree_label))
                table.append({"row": name, "code": tree_label, "figure": figure,
                              "target": row["target"], "unit": row["unit"]})
                print(f"{name} [{tree_label}]: {figure:.2f} {row['unit']} "
                      f"(target {row['target']:g})", flush=True)
            write(args.out, table, runs, machine)
    print(f"written {args.out}/contact-cost.md")


if __name__ == "__main__":
    main()
