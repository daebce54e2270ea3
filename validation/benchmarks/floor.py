"""The floor of a benchmark variant: its Exudyn systems with the tip contacts switched off.

Each bristle group is built as the variant builds it (handle, bodies, springs, joints, the
drive set before every step) and stepped through the same motion with the same solver
settings, but with every contact connector inactive: no contact law is evaluated and the
bristles hang straight, so Newton converges at once and steps stay at the step cap. What a
variant takes beyond its floor is the contact's doing (its law, and the Newton iterations,
Jacobians and step cuts it causes). Run by benchmark.py in a fresh process per run.
"""

from __future__ import annotations

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
    """Step one group's system without contacts; its solve time [s] and solver counts."""
    scene = build_scene(prepared, selection)
    for contact in scene.contacts:
        scene.mbs.SetObjectParameter(contact, "activeConnector", False)
    for compiled in scene.compiled_contacts.values():  # contact.backend "paper-compiled"
        scene.mbs.SetObjectParameter(compiled.item, "forceUserFunction", 0)
        scene.mbs.SetObjectParameter(compiled.item, "jacobianUserFunction", 0)
    settings = group_settings(prepared, scene, selection)

    scene.mbs.SetPreStepUserFunction(scene.run_step_hooks)
    start = time.perf_counter()
    if not scene.mbs.SolveDynamic(settings):
        raise RuntimeError(f"the floor of group {selection} did not finish")
    wall = time.perf_counter() - start
    return {"wall": wall, **dataclasses.asdict(solver_statistics(scene.mbs))}


def floor_run(case: Case, workers: int | None) -> dict:
    """The floor of ``case``: every group in ``workers`` processes (default: every core, as
    exubrush's local executor); summed solver counts and the groups' summed solve time."""
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
