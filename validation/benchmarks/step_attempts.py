"""Step attempts of one bristle's solve: how many failed, and what they cost.

    python validation/benchmarks/step_attempts.py [--case interdental] [--model dfm|prb]
        [--periods 1] [--bristle 23] [--group] [--bins 0.5] [--watch T0 T1]
        [--set KEY=VALUE ...]

Builds one bristle of the case's head as exubrush does and solves it in this process
(Exudyn's fast core), reading the solver's counters before every step attempt: Exudyn
calls the pre-step function before each attempt, a retry after a failed Newton solve
included, and a retry starts where the failed attempt started. Prints the attempts, the
failed ones, and the Newton iterations and Jacobians spent in failed and in accepted
attempts; with ``--bins`` the same per interval of simulated time [s] (where in the
stroke the Jacobians go, by the attempts' start times). ``--group`` solves the whole group
the bristle is solved in (with contact.between_bristles, the bristles that can touch it):
where a touching group's steps go (docs/decisions/0023). With ``--watch T0 T1`` it also
prints, for every Newton iteration of the attempts that end between T0 and T1 [s], the
residual of the iteration before and the tip's penetration [mm], normal speed [mm/s] and
slip [mm/s] on each surface feature it touches (analytic surfaces, the paper's law).
What it found: docs/decisions/0021.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from one_bristle import add_arguments, build

from exubrush.contact.laws import feature_slip
from exubrush.run.solve import solver_statistics
from exubrush.world.surfaces import features, taken

MAX_BINS = 10_000  # rows of the --bins table
STEP_DECADES = 10.0 ** np.arange(-10, 1)  # [s]: the accepted steps' lengths, by decade


def record_attempts(scene) -> list:
    """Set ``scene``'s pre-step function to its step hooks behind a recorder; return the
    list it fills with (t at the attempt's end, t at its start, Jacobians so far, Newton
    iterations so far), one row per attempt."""
    import exudyn as exu  # here: exubrush, imported first, chooses Exudyn's fast core

    rows = []
    start = exu.ConfigurationType.StartOfStep

    def recorded(mbs, t):
        counters = mbs.sys["dynamicSolver"].it
        rows.append((t, mbs.systemData.GetTime(start), counters.newtonJacobiCount,
                     counters.newtonStepsCount))
        return scene.run_step_hooks(mbs, t)

    scene.mbs.SetPreStepUserFunction(recorded)
    return rows


def watch_newton(scene, surface, radius: float, window: tuple[float, float]) -> None:
    """Print the tip's contact state (sphere of ``radius`` [mm]) at every Newton iteration
    of the attempts whose end time lies in ``window`` [s] (Exudyn calls the pre-residual
    function with the iterate in place, before each residual)."""
    import exudyn as exu

    output = exu.OutputVariableType
    contact = scene.contacts[0].connector

    def show(mbs, t, iteration, _discontinuous):
        if not window[0] <= t <= window[1]:
            return
        solver = mbs.sys["dynamicSolver"]
        centre = mbs.GetObjectOutput(contact, output.DisplacementLocal)
        velocity = mbs.GetObjectOutput(contact, output.VelocityLocal)
        omega = mbs.GetObjectOutput(contact, output.AngularVelocityLocal)
        touching = []
        for feature in features(surface, centre, radius):
            feature = taken(feature)
            if feature.distance < radius:
                normal_speed, slip = feature_slip(radius, feature.normal, velocity, omega)
                touching.append(f"depth {radius - feature.distance:.5f} normal speed "
                                f"{normal_speed:.0f} slip {np.round(slip, 1)}")
        print(f"t {t:.9f} h {solver.it.currentStepSize:.2e} iteration {iteration:2d} "
              f"residual before {solver.conv.residual:.3g}: {'; '.join(touching) or '-'}")

    scene.mbs.SetPreNewtonResidualUserFunction(show)


def attempt_costs(rows: list, final_jacobians: int, final_iterations: int,
                  finished: bool = True):
    """Per attempt: (its start time [s], failed?, Jacobians, Newton iterations) as arrays.

    An attempt failed if the next one starts at the same time (a retry), the last one if
    the solve did not finish; an attempt's cost is the counters' growth up to the next
    attempt (the last one's: up to the solve's end)."""
    table = np.array(rows, dtype=float)
    ends = np.append(table[:, 2:], [[final_jacobians, final_iterations]], axis=0)
    costs = np.diff(ends, axis=0)
    failed = np.append(table[1:, 1] == table[:-1, 1], not finished)
    return table[:, 1], failed, costs[:, 0], costs[:, 1]


def watch_error(prepared, scene, index: int) -> str | None:
    """Why ``--watch`` cannot show this bristle's contact, or None."""
    case = prepared.case
    if case.contact.backend == "exudyn-builtin":
        return "--watch: contact.backend 'exudyn-builtin' has no tip state to show"
    if case.surface.kind == "mesh":
        return "--watch: shows analytic surfaces only (the plane, cylinder, sphere, tooth row)"
    if not scene.contacts:
        return f"--watch: bristle {index} has no contact with the surface"
    return None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser, case="interdental", bristle=23, group=True)
    parser.add_argument("--bins", type=float, default=0.0,
                        help="also tabulate per interval of simulated time [s]")
    parser.add_argument("--watch", type=float, nargs=2, metavar=("T0", "T1"),
                        help="print each Newton iterate's tip contact between these times [s]")
    args = parser.parse_args()
    if not (args.bins == 0.0 or 0.0 < args.bins < math.inf):
        parser.error(f"--bins {args.bins:g}: give an interval > 0 s, or 0 for none")
    if args.watch and not (math.isfinite(args.watch[0]) and math.isfinite(args.watch[1])
                           and args.watch[0] <= args.watch[1]):
        parser.error(f"--watch {args.watch[0]:g} {args.watch[1]:g}: give two times [s], "
                     "T0 not after T1")
    if args.watch and args.group:
        parser.error("--watch shows one bristle's tip: leave out --group")
    prepared, scene, settings = build(parser, args, group=args.group)
    end = prepared.motion.end_time
    if args.bins and end / args.bins > MAX_BINS:
        parser.error(f"--bins {args.bins:g}: {end / args.bins:.3g} intervals over the run's "
                     f"{end:g} s, more than {MAX_BINS:,}; give at least {end / MAX_BINS:.3g} s")
    if args.watch:
        problem = watch_error(prepared, scene, args.bristle)
        if problem:
            parser.error(problem)
        watch_newton(scene, prepared.case.surface, prepared.bristles[args.bristle].tip_radius,
                     tuple(args.watch))
    rows = record_attempts(scene)
    clock = time.perf_counter()
    try:
        finished = bool(scene.mbs.SolveDynamic(settings))
    except RuntimeError as error:  # Exudyn's SolverError: the step cut reached its minimum
        print(f"the solve stopped: {error}")
        finished = False
    wall = time.perf_counter() - clock
    statistics = solver_statistics(scene.mbs, scene.line_search)
    starts, failed, jacobians, iterations = attempt_costs(
        rows, statistics.jacobian_updates, statistics.newton_iterations, finished)
    print(f"wall {wall:.3f} s, {statistics} (Exudyn's steps: accepted attempts + 1)")
    print(f"attempts {len(starts)}, failed {int(failed.sum())}")
    for label, mask in (("failed", failed), ("accepted", ~failed)):
        print(f"  {label:8s}: Jacobians {int(jacobians[mask].sum()):6d}, "
              f"Newton iterations {int(iterations[mask].sum()):7d}")
    lengths = np.array([end for end, *_ in rows]) - starts
    counts = np.histogram(lengths[~failed], STEP_DECADES)[0]
    print("accepted steps by length: " + ", ".join(
        f"{low:.0e}-{high:.0e} s: {n}" for low, high, n in
        zip(STEP_DECADES[:-1], STEP_DECADES[1:], counts, strict=True) if n))
    if args.bins > 0.0:
        print(f"{'from [s]':>9s} {'attempts':>9s} {'failed':>7s} {'Jacobians':>10s} "
              f"{'Newton':>8s}")
        which = np.floor(starts / args.bins).astype(int)
        for b in range(which.max() + 1):
            mask = which == b
            print(f"{b * args.bins:9.2f} {int(mask.sum()):9d} {int(failed[mask].sum()):7d} "
                  f"{int(jacobians[mask].sum()):10d} {int(iterations[mask].sum()):8d}")


if __name__ == "__main__":
    main()
