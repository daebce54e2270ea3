"""What a user pays around a result: the commands' start-up, the default run's time beyond
its solve, and (``--fresh``) a first run and the fast test tier right after an install.

    python validation/benchmarks/startup.py [--repeat 5] [--fresh]
        [--out validation/results/benchmarks]

Rows, each against its target:

- ``exubrush --help`` and ``exubrush case orthogonal``: the command's wall time, median of
  ``--repeat`` (target: under 0.5 s);
- ``exubrush run orthogonal --periods 1``: the command's wall time against its solve, the
  run.json's ``wall_time_s`` (the workers' start, scenes, solves and assembly), median of
  the runs' ratios (target: at most 1.3x);
- with ``--fresh``: this tree's committed state cloned into a temporary folder and installed
  (``pip install ".[test]"``, not editable) into a new virtual environment, then the default
  run twice (target: the first within 10 % of the second: nothing compiled or cached on
  first use costs it) and the fast tier ``python -m pytest -m "not slow"`` in the clone,
  caches cold (target: under 60 s on 2 cores). The install itself is not timed.

Wall times depend on what else the machine runs: the script prints the user CPU time of
each command beside it. Output in ``--out``: ``startup.md`` and ``startup.csv``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from benchmark import output_folder  # noqa: E402  (a script beside this one)

from exubrush.util.files import write_csv  # noqa: E402

REPOSITORY = Path(__file__).resolve().parents[2]
RUN = ["run", "orthogonal", "--periods", "1", "--quiet", "--overwrite"]


def timed(command: list[str], cwd: Path | None = None, env: dict | None = None
          ) -> tuple[float, float]:
    """Wall and user CPU time [s] of ``command`` (children included); stops the script with
    the command's own output if it fails."""
    before = os.times()
    start = time.perf_counter()
    done = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = os.times()
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stdout[-2000:]}"
                 f"\n{done.stderr[-2000:]}")
    return wall, after.children_user - before.children_user


def exubrush_command(python: Path) -> list[str]:
    """The ``exubrush`` script beside ``python`` (as a user types it), else ``-m``."""
    script = python.parent / "exubrush"
    return [str(script)] if script.exists() else [str(python), "-m", "exubrush"]


def run_overhead(exubrush: list[str], folder: Path, env: dict | None = None) -> dict:
    """One default run as a command: its wall time, its solve's and their ratio."""
    wall, user = timed([*exubrush, *RUN, "--out", str(folder)], env=env)
    solve = json.loads((folder / "run.json").read_text())["wall_time_s"]
    return {"wall_s": wall, "user_s": user, "solve_s": solve, "ratio": wall / solve}


def quick_rows(exubrush: list[str], repeat: int, folder: Path) -> list[dict]:
    rows = []
    for label, arguments in (("exubrush --help", ["--help"]),
                             ("exubrush case orthogonal", ["case", "orthogonal"])):
        times = [timed([*exubrush, *arguments]) for _ in range(repeat)]
        rows.append({"row": label, "measured": statistics.median(t[0] for t in times),
                     "user_s": statistics.median(t[1] for t in times), "unit": "s",
                     "target": 0.5})
    runs = [run_overhead(exubrush, folder / "run") for _ in range(max(1, repeat // 2))]
    rows.append({"row": "default run: command / solve",
                 "measured": statistics.median(r["ratio"] for r in runs),
                 "user_s": statistics.median(r["user_s"] for r in runs), "unit": "x",
                 "target": 1.3,
                 "detail": "; ".join(f"{r['wall_s']:.1f} s / {r['solve_s']:.1f} s"
                                     for r in runs)})
    return rows


def fresh_rows(folder: Path) -> list[dict]:
    """A clone of the committed tree, installed into a new environment: the first and
    second default runs, then the fast tier, caches cold."""
    clone, venv = folder / "clone", folder / "venv"
    subprocess.run(["git", "clone", "--quiet", str(REPOSITORY), str(clone)], check=True)
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    subprocess.run([str(python), "-m", "pip", "install", "--quiet", ".[test]"], cwd=clone,
                   check=True)
    env = {**os.environ, "PATH": f"{venv / 'bin'}{os.pathsep}{os.environ['PATH']}"}
    env.pop("NUMBA_CACHE_DIR", None)
    exubrush = exubrush_command(python)
    first = run_overhead(exubrush, folder / "first", env)
    second = run_overhead(exubrush, folder / "second", env)
    wall, user = timed([str(python), "-m", "pytest", "-q", "-m", "not slow"], cwd=clone,
                       env=env)
    return [
        {"row": "first run after install / second", "unit": "x", "target": 1.1,
         "measured": first["wall_s"] / second["wall_s"], "user_s": first["user_s"],
         "detail": f"{first['wall_s']:.1f} s then {second['wall_s']:.1f} s"},
        {"row": "fast tier, fresh clone and install", "unit": "s", "target": 60.0,
         "measured": wall, "user_s": user},
    ]


def table(rows: list[dict], machine: str) -> str:
    lines = [f"Start-up and overheads ({machine})", "",
             "| row | measured | target | user CPU [s] | detail |",
             "| --- | --- | --- | --- | --- |"]
    for row in rows:
        verdict = "met" if row["measured"] <= row["target"] else "MISSED"
        lines.append(f"| {row['row']} | {row['measured']:.2f} {row['unit']} | "
                     f"<= {row['target']:g} {row['unit']} ({verdict}) | {row['user_s']:.1f} | "
                     f"{row.get('detail', '')} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="timings per quick row")
    parser.add_argument("--fresh", action="store_true",
                        help="also install a clone into a new environment (a few minutes)")
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).parent.parent / "results" / "benchmarks")
    args = parser.parse_args()
    if not 1 <= args.repeat <= 100:
        parser.error("--repeat must be 1 to 100 (each quick row runs a command that many times)")
    machine = output_folder(parser, args.out)
    with tempfile.TemporaryDirectory(prefix="exubrush-startup-") as scratch:
        rows = quick_rows(exubrush_command(Path(sys.executable)), args.repeat, Path(scratch))
        if args.fresh:
            rows += fresh_rows(Path(scratch))
    text = table(rows, machine)
    print(text)
    (args.out / "startup.md").write_text(text)
    write_csv(args.out / "startup.csv", ["row", "measured", "unit", "target", "user_s"],
              [[r["row"], r["measured"], r["unit"], r["target"], r["user_s"]] for r in rows])


if __name__ == "__main__":
    main()
