"""Run time against error: solver and model variants of a brushing case against a reference.

    python validation/benchmarks/benchmark.py [--case orthogonal] [--head default|small]
        [--periods 1] [--repeat 3] [--only NAME ...] [--out validation/results/benchmarks]
        [--code LABEL=SOURCE_TREE ...]

Each variant is the case (approach plus ``--periods`` slide periods) with a few parameters
changed. It runs ``--repeat`` times, each run a fresh process; the wall time is the median
(of ``simulate`` alone), the errors come from the first run (runs are deterministic). Errors
are against a converged reference (DFM, 24 segments, 0.25 ms step, Newton rtol 1e-8),
computed once per case, head and periods and kept with the overrides that made it:

- flat zone, per whole stroke (flat zone: slide speed >= 80 % of the stroke's peak; a whole
  stroke runs from one reversal to the next): the relative difference of the flat-zone
  means of F_n and |F_t| in the first whole stroke, and the largest one over the later
  strokes (none with one period), so that what the first reversal leaves behind is never
  taken for the steady error;
- reversal peaks: largest relative difference of the peak F_n around each reversal;
- tips: largest distance between a tip in the variant and in the reference [mm].

A ``floor`` variant steps the same systems with their tip contacts switched off
(floor.py): the part of a variant's time that is not the contact's. The peak memory column
is the largest resident set (VmHWM, peak_memory.py) of a process that solved bristle groups.

Output in ``--out``: ``benchmark-CASE-HEAD.csv`` and ``.md`` (one row per variant) and
``pareto-CASE-HEAD.png`` (wall time against flat-zone error). Timings depend on the machine
and on what else runs: compare variants within one run of the harness.

``--code old=/path/to/old/checkout new=.`` times the same variants with several source
trees of exubrush (e.g. a commit before a change and after it) in one run: every run is a
fresh process with that tree first on its path, the trees take turns (old, new, old, new,
...) so that a drift of the machine's speed hits all of them alike, and each row is named
``variant [label]``. The trees must accept the variant's parameter keys, and floor variants
need ``Scene.run_step_hooks`` (0.5.0 on).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from exubrush.output.experiment import (
    Alignment,
    ForceSeries,
    align,
    compare,
    reversal_zones,
    strokes,
)
from exubrush.output.plotting import figure
from exubrush.output.results import Results, read_results
from exubrush.output.rundir import unusable_directory
from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.presets import PRESETS
from exubrush.run.prepared import prepare
from exubrush.simulation import simulate

FLAT_SPEED = 0.8
HEADS = {"default": [], "small": ["head.rows=2", "head.columns=2"]}
IMPLICIT_DROP = "solver.friction_drop='implicit'"
EULER = "model.rotation='euler-parameters'"  # PRB's nodes before model.rotation = "auto"
JOINT_PIVOT = "model.prb_pivot='joint'"  # PRB's sliding link on a constraint, before 0.10.0
# how a failed step was cut and how soon it grew again before 0.9.0
OLD_STEP_CONTROL = ["solver.step_cut=0.5", "solver.step_recovery_steps=2"]
REFERENCE = ["model.kind='dfm'", "model.segments=24", "solver.step_size='0.25 ms'",
             "solver.relative_tolerance=1e-8", "solver.force_tolerance=0",
             "solver.sliding_step_factor=1", IMPLICIT_DROP, *OLD_STEP_CONTROL]
# every variant starts from fixed solver settings (the defaults before the presets), so a
# row means the same thing whatever the case defaults are today
BASELINE = ["solver.step_size='1 ms'", "solver.relative_tolerance=1e-8",
            "solver.force_tolerance=0", "solver.sliding_step_factor=1", IMPLICIT_DROP,
            *OLD_STEP_CONTROL]
DFM6 = ["model.kind='dfm'", "model.segments=6"]
LOOSE = ["solver.relative_tolerance=1e-6"]
BUILTIN = "contact.backend='exudyn-builtin'"
VARIANTS = {
    "PRB": ["model.kind='prb'"],
    **{f"DFM N={n}": ["model.kind='dfm'", f"model.segments={n}"] for n in (2, 3, 4, 6, 8, 12)},
    **{f"DFM N=6, step {h} ms": [*DFM6, f"solver.step_size='{h} ms'"] for h in (0.5, 2, 5)},
    "DFM N=6, Newton rtol 1e-6": [*DFM6, *LOOSE],
    "DFM N=6, full Newton": [*DFM6, "solver.modified_newton=false"],
    **{f"DFM N={n}, step {h} ms, rtol 1e-6": ["model.kind='dfm'", f"model.segments={n}",
                                               f"solver.step_size='{h} ms'", *LOOSE]
       for n, h in ((4, 5), (6, 2), (6, 5), (6, 10), (8, 5), (12, 5))},
    "PRB, step 5 ms, rtol 1e-6": ["model.kind='prb'", "solver.step_size='5 ms'", *LOOSE],
    "DFM N=6, Python user functions": [*DFM6, "contact.backend='paper-python'"],
    "DFM N=6, EXUdense": [*DFM6, "solver.linear_solver='EXUdense'"],
    "DFM N=6, 25 Newton iterations": [*DFM6, "solver.newton_iterations=25"],
    "DFM N=6, rotation vector": [*DFM6, "model.rotation='rotation-vector'"],
    "DFM N=6, mass x100": [*DFM6, "head.material.density='1.1e5 kg/m^3'"],
    "DFM N=6, one process": DFM6,
    "DFM N=12, step 2 ms, rtol 1e-6": ["model.kind='dfm'", "model.segments=12",
                                       "solver.step_size='2 ms'", *LOOSE],
    **{f"preset {name}": ["model.kind='dfm'", *preset.overrides]
       for name, preset in PRESETS.items()},
    **{f"PRB, preset {name}": [*preset.overrides, "model.kind='prb'"]
       for name, preset in PRESETS.items()},
    # the paper's PRB link of fixed length (before model.prb_link = "buckling")
    "PRB, rigid link, preset balanced": [*PRESETS["balanced"].overrides, "model.kind='prb'",
                                         "model.prb_link='rigid'"],
    # Exudyn's built-in sphere-triangle contact instead of the paper's law (an approximation:
    # one μ, linear damping), per bristle and as one coupled system on 1 and 2 threads
    "DFM N=6, built-in contact": [*DFM6, BUILTIN],
    **{f"preset {name}, built-in contact": ["model.kind='dfm'", *PRESETS[name].overrides,
                                            BUILTIN] for name in ("fast", "balanced")},
    "PRB, preset fast, built-in contact": [*PRESETS["fast"].overrides, "model.kind='prb'",
                                           BUILTIN],
    **{f"preset fast, built-in contact, coupled, {n} thread{'s' * (n > 1)}": [
        "model.kind='dfm'", *PRESETS["fast"].overrides, BUILTIN, "solver.partition='coupled'",
        f"solver.threads={n}"] for n in (1, 2)},
    # the presets without the force tolerance of Newton (before 0.7.0), and with it doubled
    **{f"preset {name}, force tolerance {tolerance}": [
        "model.kind='dfm'", *PRESETS[name].overrides, f"solver.force_tolerance={tolerance}"]
       for name in ("fast", "balanced") for tolerance in ("0", "1e-3")},
    # the presets with the step held at solver.step_size through the strokes (before 0.7.0)
    **{f"preset {name}, sliding factor {factor}": [
        "model.kind='dfm'", *PRESETS[name].overrides, f"solver.sliding_step_factor={factor}"]
       for name in ("fast", "balanced") for factor in ("1", "2", "5")},
    **{f"preset balanced, larger steps above {fraction} of the peak speed": [
        "model.kind='dfm'", *PRESETS["balanced"].overrides,
        f"solver.sliding_speed_fraction={fraction}"] for fraction in ("0.3", "0.2")},
    # the presets as 0.6.0 ran them: no force tolerance, the step held through the strokes
    **{f"preset {name}, 0.6.0 settings": [
        "model.kind='dfm'", *PRESETS[name].overrides, "solver.force_tolerance=0",
        "solver.sliding_step_factor=1", IMPLICIT_DROP, *OLD_STEP_CONTROL]
       for name in ("fast", "balanced")},
    **{f"PRB, preset {name}, 0.6.0 settings": [
        *PRESETS[name].overrides, "model.kind='prb'", "solver.force_tolerance=0",
        "solver.sliding_step_factor=1", IMPLICIT_DROP, EULER, *OLD_STEP_CONTROL,
        JOINT_PIVOT] for name in ("fast", "balanced")},
    # the presets as 0.7.0 ran them: the friction's drop within Newton
    **{f"preset {name}, 0.7.0 settings": [
        "model.kind='dfm'", *PRESETS[name].overrides, IMPLICIT_DROP, *OLD_STEP_CONTROL]
       for name in PRESETS},
    **{f"PRB, preset {name}, 0.7.0 settings": [
        *PRESETS[name].overrides, "model.kind='prb'", IMPLICIT_DROP, EULER, *OLD_STEP_CONTROL,
        JOINT_PIVOT] for name in PRESETS},
    # the presets as 0.8.0 ran them: the step cut by 2 and grown again after 2 steps
    **{f"preset {name}, 0.8.0 settings": [
        "model.kind='dfm'", *PRESETS[name].overrides, *OLD_STEP_CONTROL] for name in PRESETS},
    **{f"PRB, preset {name}, 0.8.0 settings": [
        *PRESETS[name].overrides, "model.kind='prb'", EULER, *OLD_STEP_CONTROL, JOINT_PIVOT]
       for name in PRESETS},
    # PRB on Euler-parameter nodes, as before 0.9.0
    **{f"PRB, preset {name}, Euler parameters": [
        *PRESETS[name].overrides, "model.kind='prb'", EULER, JOINT_PIVOT] for name in PRESETS},
    # PRB's sliding link held on the pivot by Exudyn's joint, as 0.9.0 ran it
    **{f"PRB, preset {name}, 0.9.0 settings": [
        *PRESETS[name].overrides, "model.kind='prb'", JOINT_PIVOT] for name in PRESETS},
    **{f"PRB, preset {name}, force tolerance 0": [
        *PRESETS[name].overrides, "model.kind='prb'", "solver.force_tolerance=0"]
       for name in ("fast", "balanced")},
    # the fast preset with the linear solver and Newton limit of before (Exudyn's defaults)
    "preset fast, EXUdense, 25 Newton iterations": [
        "model.kind='dfm'", *PRESETS["fast"].overrides, "solver.linear_solver='EXUdense'",
        "solver.newton_iterations=25"],
}
FLOORS = {f"floor, preset {name}": f"preset {name}" for name in PRESETS}
FLOORS.update({f"floor, PRB, preset {name}": f"PRB, preset {name}" for name in PRESETS})
VARIANTS.update({floor: VARIANTS[variant] for floor, variant in FLOORS.items()})
SINGLE_PROCESS = {"DFM N=6, one process"}


def errors(results: Results, reference: Results) -> dict:
    """Per-stroke flat-zone, reversal-peak and tip errors of ``results`` against
    ``reference`` (module text)."""
    ref = ForceSeries.from_results(reference)
    aligned = align(ForceSeries.from_results(results), ref, Alignment())
    velocity = ref.slide_velocity
    rows = compare(aligned, strokes(ref.time, velocity, FLAT_SPEED))["strokes"]
    flat = {}
    for quantity, key in (("normal_force", "flat_normal"), ("tangential_force",
                                                              "flat_tangential")):
        differences = [row["relative_difference"][quantity] for row in rows]
        flat[f"{key}_first"] = differences[0] if differences else None
        flat[key] = max(differences[1:], key=abs) if len(differences) > 1 else None
    peaks = []
    for start, end in reversal_zones(ref.time, velocity, FLAT_SPEED):
        zone = (aligned.time >= start) & (aligned.time <= end)
        if zone.any():
            simulated = aligned.simulated.normal_force[zone].max()
            exact = aligned.measured.normal_force[zone].max()
            peaks.append((simulated - exact) / exact)
    tips = float("nan")
    if results.shape_time.shape == reference.shape_time.shape:
        tips = float(np.max(np.linalg.norm(results.shape_nodes[:, :, -1]
                                           - reference.shape_nodes[:, :, -1], axis=-1)))
    return {**flat, "reversal_peak": max(peaks, key=abs) if peaks else None, "tip_mm": tips}


def _overrides(head: str, periods: float, overrides: list[str]) -> list[str]:
    return [*HEADS[head], f"motion.periods={periods:g}", *BASELINE, *overrides]


def reference_results(case_name: str, head: str, periods: float, out: Path) -> Results:
    """The converged reference, solved once and kept in ``out`` with how it was made."""
    directory = out / (f"reference-{case_name}-{head}"
                       + ("" if periods == 1 else f"-{periods:g}-periods"))
    made = {"case": case_name, "head_overrides": HEADS[head], "overrides": REFERENCE}
    if periods != 1:
        made["periods"] = periods
    if (directory / "run.json").is_file() and (directory / "made.json").is_file():
        if json.loads((directory / "made.json").read_text()) == made:
            return read_results(directory)
    print(f"reference {case_name} {head}: {' '.join(REFERENCE)}", flush=True)
    results = simulate(load_case(case_name, _overrides(head, periods, REFERENCE)),
                       progress=True)
    if results.metadata["status"] != "completed":
        raise SystemExit(f"the reference did not complete: {results.metadata['message']}")
    results.save(directory)
    (directory / "made.json").write_text(json.dumps(made, indent=2))
    return results


def run_variant(case_name: str, head: str, periods: float, name: str, repeat: int,
                code: dict[str | None, Path]) -> list[tuple[Results | None, dict]]:
    """Run a variant ``repeat`` times with each source tree of ``code`` in turn (label None:
    this tree, rows named without a label); return each tree's first results (None for a
    floor) and timing record."""
    walls = {label: [] for label in code}
    first = {}
    workers = 1 if name in SINGLE_PROCESS else None
    mode = "floor" if name in FLOORS else "simulate"
    overrides = _overrides(head, periods, VARIANTS[name])
    for _ in range(repeat):
        for label, tree in code.items():
            results, report = run_in_tree(tree, mode, case_name, overrides, workers)
            walls[label].append(report["wall"])
            first.setdefault(label, (results, report))
    return [(first[label][0], _record(name if label is None else f"{name} [{label}]",
                                      *first[label], walls[label])) for label in code]


# a fresh interpreter started in one source tree (python -c puts the working directory
# first on the path, before an installed exubrush); times simulate() (or the floor) only,
# and reports the peak resident memory of the processes that solved (peak_memory.py)
WORKER = """
import json, sys, time
import exubrush
from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
mode, case, overrides, workers, out, here = json.loads(sys.argv[1])
sys.path.insert(0, here)
from peak_memory import PeakMemory
parameters = load_case(case, overrides)
with PeakMemory() as peak:
    start = time.perf_counter()
    if mode == "floor":
        from floor import floor_run
        report = floor_run(parameters, workers)
        wall = time.perf_counter() - start
    else:
        from exubrush.simulation import simulate
        results = simulate(parameters, progress=False, workers=workers)
        wall = time.perf_counter() - start
        results.save(out)
        report = {}
report.update(wall=wall, module=exubrush.__file__,
              # no worker seen: the groups were solved in this process
              peak_memory_mb=peak.children_mb or peak.self_mb, main_memory_mb=peak.self_mb)
print(json.dumps(report))
"""


def run_in_tree(tree: Path, mode: str, case_name: str, overrides: list[str],
                workers: int | None) -> tuple[Results | None, dict]:
    """One run of ``mode`` ("simulate" or "floor") in a fresh interpreter started in the
    source tree ``tree``: its results (None for a floor) and its report (``wall`` [s],
    ``peak_memory_mb`` of a solving process, ``main_memory_mb`` of the main process)."""
    with tempfile.TemporaryDirectory() as out:
        environment = {**os.environ, "PYTHONPATH": str(tree.resolve())}
        arguments = [mode, case_name, overrides, workers, out, str(Path(__file__).parent)]
        done = subprocess.run([sys.executable, "-c", WORKER, json.dumps(arguments)],
                              capture_output=True, text=True, env=environment, cwd=tree,
                              check=False)
        if done.returncode != 0:
            raise SystemExit(f"run with {tree} failed:\n{done.stderr[-2000:]}")
        report = json.loads(done.stdout.strip().splitlines()[-1])
        if not Path(report["module"]).resolve().is_relative_to(tree.resolve()):
            raise SystemExit(f"{tree}: the run imported {report['module']} instead")
        return (read_results(out) if mode == "simulate" else None), report


def _record(name: str, results: Results | None, report: dict, walls: list[float]) -> dict:
    if results is None:  # a floor: no forces, its own counts
        stats, simulated, status = report, None, "floor"
        solve = report["solve_s"]
    else:
        meta = results.metadata
        stats, simulated, status = (meta["solver_statistics"], meta["simulated_time_s"],
                                    meta["status"])
        solve = meta["solver_wall_time_s_sum"]
    wall = statistics.median(walls)
    return {
        "variant": name, "status": status,
        "wall_time_s": wall, "wall_times_s": walls, "simulated_s": simulated,
        # the groups' stepping alone, summed (no process start, imports, scene building or
        # assembly): the first run's, beside the median whole-run wall time
        "solve_s": solve,
        "real_time_factor": None if simulated is None else simulated / wall,
        "steps": stats.get("steps"), "newton_iterations": stats.get("newton_iterations"),
        "jacobian_updates": stats.get("jacobian_updates"),
        "peak_memory_mb": report["peak_memory_mb"],
        "flat_normal_first": None, "flat_tangential_first": None, "flat_normal": None,
        "flat_tangential": None, "reversal_peak": None, "tip_mm": None,
    }


def _pct(value) -> str:
    return "-" if value is None or np.isnan(value) else f"{100 * value:+.2f} %"


def _number(value, digits: int) -> str:
    return "-" if value is None or np.isnan(value) else f"{value:.{digits}f}"


def write_outputs(rows: list[dict], out: Path, stem: str, machine: str) -> None:
    """Table (CSV and Markdown) and the Pareto plot of wall time against flat-zone error."""
    columns = ["variant", "status", "wall_time_s", "solve_s", "real_time_factor", "steps",
               "newton_iterations", "jacobian_updates", "flat_normal_first",
               "flat_tangential_first", "flat_normal", "flat_tangential", "reversal_peak",
               "tip_mm", "peak_memory_mb", "wall_times_s"]
    with (out / f"{stem}.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    lines = [f"Machine: {machine}", "",
             "| variant | wall time [s] | solves summed [s] | real-time factor | steps "
             "| Newton its | Jacobians "
             "| flat F_n, 1st stroke | flat F_t, 1st stroke | flat F_n, later | flat F_t, later "
             "| reversal peak F_n | tip [mm] | peak memory per worker [MB] |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
             "| --- |"]
    for r in rows:
        lines.append(f"| {r['variant']} | {r['wall_time_s']:.1f} | {r['solve_s']:.1f} "
                     f"| {_number(r['real_time_factor'], 2)} "
                     f"| {r['steps']} | {r['newton_iterations']} | {r['jacobian_updates']} "
                     f"| {_pct(r['flat_normal_first'])} | {_pct(r['flat_tangential_first'])} "
                     f"| {_pct(r['flat_normal'])} | {_pct(r['flat_tangential'])} "
                     f"| {_pct(r['reversal_peak'])} | {_number(r['tip_mm'], 3)} "
                     f"| {_number(r['peak_memory_mb'], 0)} |")
    (out / f"{stem}.md").write_text("\n".join(lines) + "\n")

    fig, axis = figure(1, 1, figsize=(11, 5.5))
    fig.subplots_adjust(left=0.08, right=0.6, bottom=0.11, top=0.92)
    def steady(r):  # the later strokes' error where there are later strokes
        return r["flat_normal"] if r["flat_normal"] is not None else r["flat_normal_first"]

    points = [(number, r["wall_time_s"], 100 * max(abs(steady(r)), 1e-5))
              for number, r in enumerate(rows, 1) if steady(r) is not None]
    front, best = [], np.inf
    for point in sorted(points, key=lambda p: p[1]):
        if point[2] < best:
            front.append(point)
            best = point[2]
    on_front = {p[0] for p in front}
    for number, wall, error in points:
        axis.loglog(wall, error, "o", color="C0" if number in on_front else "0.6")
        axis.annotate(str(number), (wall, error), fontsize=8, xytext=(4, 3),
                      textcoords="offset points")
    axis.loglog([p[1] for p in front], [p[2] for p in front], "-", color="C0", lw=1,
                label="Pareto front")
    for r in rows:
        if r["simulated_s"] is not None:
            axis.axvline(r["simulated_s"], ls="--", color="C3", lw=1,
                         label=f"real time ({r['simulated_s']:g} s simulated)")
            break
    for number, r in enumerate(rows, 1):
        if r["status"] == "floor":
            axis.axvline(r["wall_time_s"], ls=":", color="0.4", lw=1)
            axis.annotate(f"{number} (floor)", (r["wall_time_s"], 0.5), fontsize=8,
                          rotation=90, xytext=(2, 0), textcoords="offset points",
                          xycoords=("data", "axes fraction"))
    axis.axhline(1.0, ls=":", color="C2", lw=1, label="1 % flat-zone error")
    axis.set_xlabel("wall time [s] (median)")
    axis.set_ylabel("|flat-zone F_n error| against the reference [%]\n"
                    "(later strokes; the first where there is one)")
    axis.set_title(f"exubrush run time against error: {stem}", fontsize=10)
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(loc="lower left", fontsize=8)
    names = "\n".join(f"{number:2d}  {r['variant']}" for number, r in enumerate(rows, 1))
    fig.text(0.62, 0.92, names, fontsize=8, va="top", family="monospace")
    fig.savefig(out / f"pareto-{stem.removeprefix('benchmark-')}.png", dpi=110)


def source_trees(parser: argparse.ArgumentParser, items: list[str] | None,
                 label: str | None) -> dict:
    """The source trees of ``--code LABEL=SOURCE_TREE ...`` as label -> path, or this tree
    alone under ``label`` without the option; a malformed item or a tree without an
    exubrush package ends the script with the parser's one-line error."""
    if not items:
        return {label: Path(__file__).resolve().parents[2]}
    pairs = [item.partition("=") for item in items]
    if any(not sep or not name for name, sep, _ in pairs):
        parser.error("--code takes LABEL=SOURCE_TREE, e.g. old=../exubrush-old")
    code = {name: Path(tree) for name, _, tree in pairs}
    for name, tree in code.items():
        if not (tree / "exubrush" / "__init__.py").is_file():
            parser.error(f"--code {name}={tree}: no exubrush package in that tree")
    return code


def output_folder(parser: argparse.ArgumentParser, out: Path) -> str:
    """Make the ``--out`` folder (a bad one ends the script with the parser's one-line
    error) and return the machine's description for the tables."""
    reason = unusable_directory(out)
    if reason:
        parser.error(f"--out {out}: {reason}")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as err:  # e.g. under /proc, which unusable_directory cannot foresee
        parser.error(f"--out {out}: {err.strerror or err}")
    return f"{platform.node()}, {os.cpu_count()} cores, Python {platform.python_version()}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="orthogonal", choices=["orthogonal", "parallel"])
    parser.add_argument("--head", default="default", choices=sorted(HEADS))
    parser.add_argument("--periods", type=float, default=1.0,
                        help="slide periods after the approach (1.5 or more: later strokes)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--only", nargs="*", choices=sorted(VARIANTS), metavar="VARIANT")
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).parent.parent / "results" / "benchmarks")
    parser.add_argument("--code", nargs="+", metavar="LABEL=SOURCE_TREE",
                        help="time these exubrush source trees in turn (see the docstring)")
    args = parser.parse_args()
    code = source_trees(parser, args.code, None)
    if args.repeat < 1:
        parser.error(f"--repeat {args.repeat}: give 1 or more runs per variant")
    for name in args.only or VARIANTS:  # every case is valid before anything runs
        try:
            prepare(load_case(args.case, _overrides(args.head, args.periods, VARIANTS[name])))
        except ParameterError as err:
            parser.error(f"{name}: {err}")
    machine = output_folder(parser, args.out)
    reference = reference_results(args.case, args.head, args.periods, args.out)
    stem = f"benchmark-{args.case}-{args.head}" + (
        "" if args.periods == 1 else f"-{args.periods:g}-periods")
    rows = []
    for name in args.only or VARIANTS:
        print(f"{name} ...", flush=True)
        for results, record in run_variant(args.case, args.head, args.periods, name,
                                           args.repeat, code):
            if results is not None:
                record.update(errors(results, reference))
            rows.append(record)
            print(f"  {record['variant']}: {record['wall_time_s']:.1f} s "
                  f"({', '.join(f'{w:.1f}' for w in record['wall_times_s'])}), "
                  f"flat F_n {_pct(record['flat_normal_first'])} first stroke, "
                  f"{_pct(record['flat_normal'])} later", flush=True)
        write_outputs(rows, args.out, stem, machine)
    print(f"written {args.out}/{stem}.md")


if __name__ == "__main__":
    main()
