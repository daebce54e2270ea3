"""The floor of a benchmark variant: its Exudyn systems with the tip contacts switched off.

Each bristle group is built as the variant builds it (handle, bodies, springs, joints, the
drive set before every step) and stepped through the same motion with the same solver
settings, but with every contact connector inactive: no contact law is evaluated and the
bristles hang straight, so Newton converges at once and steps stay at the step cap. What a
variant takes beyond its floor is the contact's doing (its law, and the Newton iterations,
Jacobians and step cuts it causes). Run by benchmark.py in a fresh process per run.

As a script, one case's run against its floor, whole and solves alone::

    python validation/benchmarks/floor.py [--case orthogonal] [--periods 1] [--set KEY=VALUE ...]

The whole figures include each process's start, imports and scene building; the solves
alone (summed over the groups) are the stepping only, where the contact's cost shows
undiluted.
"""

from __future__ import annotations

import argparse
import dataclasses
import multiprocessing
import os
import time
from concurrent.futures import ProcessPoolExecutor

from exubrush.parameters.case import Case
from exubrush.run.prepared import PreparedCase, prepare
from exubrush.run.scene import build_scene
from exubrush.run.solve import group_settings, solver_statistics


def floor_group(prepared: PreparedCase, selection: tuple[int, ...]) -> dict:
    """Step one group's system without contacts; its solve time [s] (``solve_s``, the
    stepping alone) and solver counts."""
    scene = build_scene(prepared, selection)
    for contact in scene.contacts:
        scene.mbs.SetObjectParameter(contact.connector, "activeConnector", False)
        if contact.compiled is not None:  # contact.backend "paper-compiled"
            scene.mbs.SetObjectParameter(contact.compiled.item, "forceUserFunction", 0)
            scene.mbs.SetObjectParameter(contact.compiled.item, "jacobianUserFunction", 0)
    settings = group_settings(prepared, scene, selection)

    scene.mbs.SetPreStepUserFunction(scene.run_step_hooks)
    start = time.perf_counter()
    if not scene.mbs.SolveDynamic(settings):
        raise RuntimeError(f"the floor of group {selection} did not finish")
    solve = time.perf_counter() - start
    return {"solve_s": solve, **dataclasses.asdict(solver_statistics(scene.mbs))}


def floor_run(case: Case, workers: int | None) -> dict:
    """The floor of ``case``: every group in ``workers`` processes (default: every core, as
    exubrush's local executor); summed solver counts and the groups' summed solve time
    (``solve_s``)."""
    prepared = prepare(case)
    groups = [tuple(group) for group in prepared.groups]
    workers = min(workers or os.cpu_count() or 1, len(groups))
    if workers == 1:
        parts = [floor_group(prepared, group) for group in groups]
    else:
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(workers, mp_context=context) as pool:
            parts = list(pool.map(floor_group, [prepared] * len(groups), groups))
    return {key: sum(part[key] for part in parts) for key in parts[0]}


def main() -> None:
    parser = argparse.ArgumentParser(description="a run against its floor, whole and solves")
    parser.add_argument("--case", default="orthogonal")
    parser.add_argument("--periods", type=float, default=1.0)
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE")
    args = parser.parse_args()
    from exubrush.parameters.fields import ParameterError
    from exubrush.parameters.io import load_case
    from exubrush.simulation import simulate

    try:
        case = load_case(args.case, [f"motion.periods={args.periods}", *args.overrides])
    except ParameterError as err:
        parser.error(str(err))
    start = time.perf_counter()
    floor = floor_run(case, None)
    floor_whole = time.perf_counter() - start
    start = time.perf_counter()
    meta = simulate(case, progress=False).metadata
    run_whole = time.perf_counter() - start
    run_solves = meta["solver_wall_time_s_sum"]
    print(f"| {args.case}, {args.periods:g} period(s) | whole [s] | solves summed [s] |")
    print("| --- | --- | --- |")
    print(f"| run | {run_whole:.1f} | {run_solves:.1f} |")
    print(f"| floor | {floor_whole:.1f} | {floor['solve_s']:.1f} |")
    print(f"| run / floor | {run_whole / floor_whole:.2f}x "
          f"| {run_solves / floor['solve_s']:.2f}x |")


if __name__ == "__main__":
    main()
