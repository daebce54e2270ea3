"""Numerical stability stress matrix: every cell must finish sanely or stop clearly.

Each cell runs ``exubrush run`` as a separate process on a small head (stability, not size,
is the point) with one parameter pushed away from the default, under a wall-time limit.
A cell passes if it either

- completed, with finite forces below the physical bound of exubrush.run.sanity, or
- stopped with status "failed" and a message that names the time and the cause, keeping
  the results up to there (a force beyond the bound stops the run: it is not physics);

A cell that writes no ``run.json`` passes only as a refusal: exit status 2 (input that
cannot be used) and one line on standard error, as the command line promises. It fails if
it hangs past the limit, crashes with a traceback, is killed (SIGKILL, the out-of-memory
killer: a negative exit status), ends with no ``run.json`` in any other way (exit 1, or
exit 2 with more than one line), or writes forces beyond the bound. The table (CSV and
Markdown) is written to ``--out``.

Usage::

    python validation/stress_matrix.py                 # reduced matrix (about 10 min)
    python validation/stress_matrix.py --full          # every cell, both models
    python validation/stress_matrix.py --only step     # cells whose name contains 'step'
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

SMALL_HEAD = ["head.rows=1", "head.columns=2"]

# a nylon filament head: round 0.2 mm filaments, 10 mm long, E about 3 GPa (nylon 6.12)
NYLON = [
    "head.material.youngs_modulus='3 GPa'", "head.material.poisson_ratio=0.4",
    "head.material.density='1070 kg/m^3'", "head.bristle.section='circle'",
    "head.bristle.width='0.2 mm'", "head.bristle.height='0.2 mm'",
    "head.bristle.length='10 mm'", "head.bristle.tip_radius='0.1 mm'",
    "head.rows=2", "head.columns=3", "head.pitch_along='0.25 mm'", "head.pitch_across='0.25 mm'",
    "motion.interaction_distance='9.3 mm'",
]


@dataclass(frozen=True)
class Cell:
    """One run of the matrix: a name, a case, a model and overrides on the small head."""

    name: str
    overrides: tuple[str, ...]
    case: str = "orthogonal"
    model: str = "dfm"
    periods: float | None = 0.5  # None: the overrides set motion.periods
    full_only: bool = False


def cells(full: bool) -> list[Cell]:
    """The matrix; ``full`` adds the parallel case, the PRB model and the costly cells."""
    axes = [
        ("default", []),
        ("step 3 ms", ["solver.step_size='3 ms'"]),
        ("step 10 ms", ["solver.step_size='10 ms'"]),
        ("E 1 MPa", ["head.material.youngs_modulus='1 MPa'"]),
        ("E 20 MPa", ["head.material.youngs_modulus='20 MPa'"]),
        ("nylon head", NYLON),
        ("contact k x0.01", ["contact.stiffness='1 N/mm^1.3'"]),
        ("contact k x100", ["contact.stiffness='1e4 N/mm^1.3'"]),
        ("speed x0.1", ["motion.period='120 s'", "motion.periods=0.1"]),
        ("speed x10", ["motion.period='1.2 s'", "motion.periods=2"]),
        ("grazing d = l + r - 0.05 mm", ["motion.interaction_distance='5.35 mm'"]),
        ("deep d = l/2", ["motion.interaction_distance='2.5 mm'"]),
        ("mu 0", ["contact.static_friction=0", "contact.dynamic_friction=0",
                  "model.prb_parameters='explicit'"]),
        ("mu 1.5", ["contact.static_friction=1.5", "contact.dynamic_friction=1.5"]),
        ("no damping", ["head.material.damping_time='0 s'", "contact.damping='0 N*s/mm^3'"]),
    ]
    matrix = []
    for case in ("orthogonal", "parallel"):
        for model in ("dfm", "prb"):
            reduced = case == "orthogonal" and model == "dfm"
            for name, overrides in axes:
                periods = 0.5 if case == "orthogonal" else 0.25
                if any(o.startswith("motion.periods") for o in overrides):
                    periods = None
                matrix.append(Cell(f"{case} {model}: {name}", tuple(overrides), case, model,
                                   periods, full_only=not reduced))
    matrix += [
        Cell("orthogonal dfm: N = 48", ("model.segments=48",), periods=0.25),
        Cell("orthogonal dfm: 10 periods", (), periods=10, full_only=True),
        Cell("orthogonal prb: 10 periods", (), model="prb", periods=10, full_only=True),
    ]
    return [c for c in matrix if full or not c.full_only]


def run_cell(cell: Cell, workdir: Path, limit: float) -> dict:
    """Run one cell under a wall-time limit and judge it."""
    out = workdir / "".join(ch if ch.isalnum() else "_" for ch in cell.name)
    command = [sys.executable, "-m", "exubrush", "run", cell.case, "--model", cell.model,
               "--quiet", "--overwrite", "--out", str(out)]
    if cell.periods is not None:
        command += ["--periods", str(cell.periods)]
    for override in (*SMALL_HEAD, *cell.overrides):
        command += ["--set", override]
    start = time.perf_counter()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return {"cell": cell.name, "outcome": "HANG", "verdict": "FAIL",
                "wall_s": round(time.perf_counter() - start, 1),
                "why": f"no result within {limit:g} s"}
    row = {"cell": cell.name, "wall_s": round(time.perf_counter() - start, 1)}
    return judge(row, done.returncode, done.stderr, out)


REFUSED = 2  # the command line's exit status for input that cannot be used (exubrush.cli)


def judge(row: dict, status: int, stderr: str, out: Path) -> dict:
    """The verdict on a finished cell from its exit status, standard error and ``out``."""
    row = {**row, "exit": status}
    lines = stderr.strip().splitlines()
    last = lines[-1] if lines else "no output"
    if "Traceback" in stderr:
        return {**row, "outcome": "crash", "verdict": "FAIL", "why": last}
    if status < 0:  # ended by a signal: SIGKILL, the out-of-memory killer, a segfault
        return {**row, "outcome": "killed", "verdict": "FAIL",
                "why": f"killed by signal {-status}; {last}"}
    if not (out / "run.json").is_file():
        # a refusal is exit status 2 with one line saying why; anything else that leaves no
        # run.json (exit 1, several lines, no message) did not end as the command promises
        refused = status == REFUSED and len(lines) == 1
        return {**row, "outcome": "refused" if refused else "no result",
                "verdict": "pass" if refused else "FAIL",
                "why": last if refused else f"exit {status}, {len(lines)} lines on "
                                            f"standard error, no run.json; {last}"}
    meta = json.loads((out / "run.json").read_text())
    sanity = meta["sanity"]
    row.update(outcome=meta["status"], simulated_s=round(meta["simulated_time_s"], 3),
               steps=meta["solver_statistics"].get("steps", 0),
               peak_normal_N=f"{sanity['peak_normal_force_N']:.4g}",
               bound_N=f"{sanity['normal_force_bound_N']:.4g}")
    # a group stopped at its bound drops its samples past it (within_bound is then false):
    # only kept samples beyond the bound are a failure, a clear stop is judged below
    if sanity["peak_normal_force_N"] > sanity["normal_force_bound_N"]:
        return {**row, "verdict": "FAIL", "why": "peak normal force beyond the physical bound"}
    if meta["status"] == "completed":
        return {**row, "verdict": "pass", "why": ""}
    clear = "stopped at t = " in meta["message"]
    return {**row, "verdict": "pass" if clear else "FAIL", "why": meta["message"][:160]}


def write_tables(rows: list[dict], out: Path) -> None:
    """stress_matrix.csv and stress_matrix.md in ``out``."""
    columns = ["cell", "outcome", "verdict", "wall_s", "simulated_s", "steps", "peak_normal_N",
               "bound_N", "why"]
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "stress_matrix.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, columns, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(str(r.get(c, "")) for c in columns) + " |" for r in rows]
    (out / "stress_matrix.md").write_text("\n".join(lines) + "\n")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="every cell, both cases and models")
    parser.add_argument("--only", default="", help="run the cells whose name contains this")
    parser.add_argument("--limit", type=float, default=900.0, help="wall-time limit per cell [s]")
    parser.add_argument("--out", type=Path, default=Path("validation/results/stress"))
    args = parser.parse_args(argv)
    selected = [c for c in cells(args.full) if args.only in c.name]
    rows = []
    with tempfile.TemporaryDirectory() as workdir:
        for number, cell in enumerate(selected, 1):
            row = run_cell(cell, Path(workdir), args.limit)
            rows.append(row)
            print(f"[{number}/{len(selected)}] {row['verdict']:4} {row['outcome']:11} "
                  f"{row['wall_s']:7.1f} s  {cell.name}  {row.get('why', '')}", flush=True)
            write_tables(rows, args.out)  # a stopped sweep keeps every finished row
    failed = [r for r in rows if r["verdict"] != "pass"]
    print(f"{len(rows) - len(failed)} of {len(rows)} cells pass; table in {args.out}/")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
