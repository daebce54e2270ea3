"""Where a solve's Jacobians go, by its Newton attempts' iterations, and why attempts fail.

    python validation/benchmarks/newton_attempts.py [--case tuft7.toml beside it]
        [--periods 1] [--bristle 0] [--group] [--set KEY=VALUE ...]
        [--replay ITERATION RATIO] [--keep-jacobians]

Builds the bristle's group (``--group``; one bristle without) as exubrush does and solves it
in this process, recording every step attempt's Newton iterations and Jacobians
(step_attempts.record_attempts) and the residual Exudyn holds at each of its iterations
(from the pre-Newton-residual function, which it calls after each update and before that
update's residual: the residual of the iteration before). Prints the CPU time of the solve,
the attempts and Jacobians by how many iterations an attempt took (accepted, and failed:
the step cut after it), and the failed attempts' residuals against their first.

``--replay ITERATION RATIO`` replays a give-up rule on the recorded residuals, without
solving again: the iterations the failed attempts would have saved, stopped at the first
iteration from ITERATION on whose residual is above RATIO of the first, and the accepted
attempts the rule would have stopped too. Run with ``--set solver.touching_give_up=0``
for the histories without the rule. ``--keep-jacobians`` keeps Exudyn's Jacobian across
steps (a touching group renews it at every attempt) and renews it only after a failed
attempt, after an attempt of more than two iterations, or when the step size changes.
What it found: docs/decisions/0026.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from one_bristle import add_arguments, build
from step_attempts import attempt_costs, record_attempts

from exubrush.run.solve import solver_statistics
from exubrush.run.solver import fresh_jacobian_after_step_change
from exubrush.run.step_hooks import JACOBIAN

# attempts by their Newton iterations: (label, fewest, most)
CLASSES = (("1-3", 1, 3), ("4-9", 4, 9), ("10 or more", 10, 10**6))
CALM = 2  # --keep-jacobians: an attempt of more iterations renews the Jacobian
MAX_ITERATION = 100  # --replay: beyond any Newton iteration limit a solve is run with


def by_iterations(failed: np.ndarray, jacobians: np.ndarray,
                  iterations: np.ndarray) -> list[tuple[str, int, int]]:
    """(label, attempts, Jacobians) of the accepted attempts by CLASSES of their Newton
    iterations, then of the failed ones."""
    table = []
    for label, fewest, most in CLASSES:
        mask = ~failed & (iterations >= fewest) & (iterations <= most)
        table.append((f"accepted in {label} iterations", int(mask.sum()),
                      int(jacobians[mask].sum())))
    table.append(("failed", int(failed.sum()), int(jacobians[failed].sum())))
    return table


def replay(histories: list[list[float]], failed: np.ndarray, iteration: int,
           ratio: float) -> tuple[int, int]:
    """(iterations the failed attempts save, accepted attempts stopped) if an attempt were
    given up at its first iteration k >= ``iteration`` whose residual (the k-th entry of
    its history: the residual after k − 1 updates, the first entry the predictor's) is
    above ``ratio`` times its first."""
    saved = stopped = 0
    for history, lost in zip(histories, failed, strict=True):
        over = [k for k in range(iteration, len(history) + 1)
                if history[k - 1] > ratio * history[0]]
        if over:
            if lost:
                saved += len(history) - over[0]
            else:
                stopped += 1
    return saved, stopped


def record_residuals(scene) -> tuple[list[list[float]], list[float]]:
    """Wrap the scene's pre-Newton-residual function (its line search, if any) with a
    recorder; return the lists it fills: per attempt, the residual Exudyn holds at each of
    its iterations (the first: the predictor's), and its last residual (after its last
    update; the solve's last attempt's is added by :func:`close_residuals`)."""
    histories: list[list[float]] = []
    lasts: list[float] = []
    search = scene.line_search

    def recorded(mbs, t, iteration, discontinuous):
        residual = mbs.sys["dynamicSolver"].conv.residual
        if iteration == 0:  # a new attempt: Exudyn still holds the last one's residual
            if histories:
                lasts.append(residual)
            histories.append([])
        else:
            histories[-1].append(residual)
        if search is not None:
            search(mbs, t, iteration, discontinuous)

    scene.mbs.SetPreNewtonResidualUserFunction(recorded)
    return histories, lasts


def close_residuals(scene, histories: list, lasts: list) -> None:
    """Add the solve's last attempt's last residual."""
    if len(lasts) < len(histories):
        lasts.append(scene.mbs.sys["dynamicSolver"].conv.residual)


def keep_jacobians(scene, settings, rows: list) -> None:
    """Keep the Jacobian across steps; renew it after a failed attempt or a slow one (more
    than CALM iterations), read from the attempts ``rows`` records
    (step_attempts.record_attempts: the current attempt last), and at a new step size
    (exubrush.run.solver.fresh_jacobian_after_step_change)."""
    settings.timeIntegration.newton.modifiedNewtonJacUpdatePerStep = False

    def renew(mbs, t):
        if len(rows) >= 2:
            (_, start, _, its), (_, last_start, _, last_its) = rows[-1], rows[-2]
            if start == last_start or its - last_its > CALM:
                mbs.solverSignalJacobianUpdate = True

    scene.step_hooks.add(JACOBIAN, renew)
    scene.step_hooks.add(JACOBIAN, fresh_jacobian_after_step_change())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser, case=str(Path(__file__).parent / "tuft7.toml"), bristle=0,
                  group=True)
    parser.add_argument("--replay", type=float, nargs=2, metavar=("ITERATION", "RATIO"),
                        help="replay a give-up rule on the recorded residuals")
    parser.add_argument("--keep-jacobians", action="store_true",
                        help="keep the Jacobian across steps, renewed where Newton needs it")
    args = parser.parse_args()
    if args.replay and not (1 <= args.replay[0] <= MAX_ITERATION
                            and 0.0 < args.replay[1] < 1.0):
        parser.error(f"--replay {args.replay[0]:g} {args.replay[1]:g}: give an iteration "
                     f"from 1 to {MAX_ITERATION} and a ratio between 0 and 1")
    _, scene, settings = build(parser, args, group=args.group)
    rows = record_attempts(scene)
    histories, lasts = record_residuals(scene)
    if args.keep_jacobians:
        keep_jacobians(scene, settings, rows)
    clock = time.process_time()
    try:
        finished = bool(scene.mbs.SolveDynamic(settings, storeSolver=True))
    except RuntimeError as error:  # Exudyn's SolverError: the step cut reached its minimum
        print(f"the solve stopped: {error}")
        finished = False
    cpu = time.process_time() - clock
    close_residuals(scene, histories, lasts)
    statistics = solver_statistics(scene.mbs, scene.line_search)
    _, failed, jacobians, iterations = attempt_costs(
        rows, statistics.jacobian_updates, statistics.newton_iterations, finished)
    print(f"CPU {cpu:.1f} s, {statistics}")
    for label, count, spent in by_iterations(failed, jacobians, iterations):
        print(f"  {label:34s}: {count:6d} attempts, {spent:7d} Jacobians "
              f"({100.0 * spent / max(jacobians.sum(), 1):.0f} %)")
    if len(histories) != len(failed):
        raise SystemExit(f"{len(histories)} residual histories for {len(failed)} attempts")
    for label, chosen in (("failed", failed), ("accepted", ~failed)):
        ends = [last / history[0] for history, last, pick
                in zip(histories, lasts, chosen, strict=True) if pick and history]
        if ends:
            print(f"{label} attempts, last residual over the first: quantiles 10/50/90 % "
                  + " ".join(f"{q:.2g}" for q in np.quantile(ends, [0.1, 0.5, 0.9])))
    if args.replay:
        saved, stopped = replay(histories, failed, int(args.replay[0]), args.replay[1])
        print(f"give-up rule {args.replay[0]:g}, {args.replay[1]:g}: failed attempts save "
              f"{saved} of {int(iterations[failed].sum())} iterations; {stopped} of "
              f"{int((~failed).sum())} accepted attempts stopped")


if __name__ == "__main__":
    main()
