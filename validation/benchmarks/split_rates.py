"""Could a touching group be split into one system per filament? The coupling's rates.

    python validation/benchmarks/split_rates.py [--case tuft] [--periods 0.1]
        [--bristle 0] [--at T ...] [--set KEY=VALUE ...]

A split solves each filament as its own system, its neighbours held where the last sweep
left them, and sweeps until the filaments agree (block Jacobi: all at once, in parallel;
block Gauss-Seidel: one after the other, each with its neighbours' newest positions). How
many sweeps that takes is a property of the group's Newton matrix: this script solves the
group that holds ``--bristle`` as a run does (contact.between_bristles must be on), takes
Exudyn's Newton Jacobian at the first step attempt at or after each time ``--at`` [s],
and splits it into the filaments' blocks: each filament's ODE2 coordinates with the
algebraic equations that involve only them (its Euler parameters' norms); the handle's
coordinates and its drive's equations are left out, as a split would prescribe the
handle. It prints, per time, the spectral radius of block Jacobi's and block
Gauss-Seidel's iteration matrices (the filaments in index order), the sweeps each needs
to shrink an error a thousand- and a million-fold, the iterations of block-Jacobi sweeps
accelerated by a Krylov method (GMRES, the best any method can do from the same sweeps,
as an interface quasi-Newton does), and the coordinates coupled between filaments (the
size of the problem a split solved in the space of contact forces would couple). What it
found: docs/decisions/0023.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import scipy.linalg
import scipy.sparse.linalg
from one_bristle import add_arguments, build

DEFAULT_TIMES = (0.25, 0.45, 0.65, 0.85, 0.99)  # shares of the run's end time (no --at)


def block_rates(matrix: np.ndarray, owner: np.ndarray) -> tuple[float, float, int]:
    """(block Jacobi's spectral radius, block Gauss-Seidel's, coordinates coupled between
    blocks) of the linear system ``matrix`` x = b, whose row and column i belong to block
    ``owner[i]`` (blocks in increasing ``owner`` order for Gauss-Seidel).

    Block Jacobi's iteration matrix is I − D⁻¹A (D the block diagonal of A); block
    Gauss-Seidel's is −(D + L)⁻¹U (L and U the parts of A below and above the block
    diagonal). An error shrinks by the spectral radius per sweep.
    """
    a, o = matrix, np.asarray(owner)
    same = o[:, None] == o[None, :]
    diagonal = np.where(same, a, 0.0)
    lower = np.where(~same & (o[:, None] > o[None, :]), a, 0.0)
    upper = a - diagonal - lower
    jacobi = np.max(np.abs(1.0 - np.linalg.eigvals(np.linalg.solve(diagonal, a))))
    gauss_seidel = np.max(np.abs(np.linalg.eigvals(np.linalg.solve(diagonal + lower, -upper))))
    coupled = int(np.count_nonzero(np.any((a != 0.0) & ~same, axis=0)))
    return float(jacobi), float(gauss_seidel), coupled


def accelerated_sweeps(matrix: np.ndarray, owner: np.ndarray, reduction: float,
                       seed: int = 0) -> int:
    """GMRES iterations, preconditioned by the blocks of ``owner`` (block Jacobi), for the
    residual of ``matrix`` x = b to shrink by ``reduction``; b random (``seed``), x0 = 0.
    Each iteration is one block-Jacobi sweep plus the Krylov method's own work."""
    o = np.asarray(owner)
    factors = scipy.linalg.lu_factor(np.where(o[:, None] == o[None, :], matrix, 0.0))
    preconditioner = scipy.sparse.linalg.LinearOperator(
        matrix.shape, matvec=lambda v: scipy.linalg.lu_solve(factors, v))
    right = np.random.default_rng(seed).normal(size=len(matrix))
    residuals: list[float] = []
    scipy.sparse.linalg.gmres(matrix, right, M=preconditioner, rtol=reduction,
                              restart=len(matrix), maxiter=1,
                              callback=residuals.append, callback_type="pr_norm")
    return len(residuals)


def sweeps(radius: float, reduction: float) -> float:
    """Sweeps for an error to shrink by ``reduction`` at ``radius`` per sweep (inf if it
    does not shrink)."""
    if radius >= 1.0:
        return math.inf
    if radius <= 0.0:
        return 1.0
    return math.ceil(math.log(reduction) / math.log(radius))


def filament_owner(scene, matrix: np.ndarray) -> np.ndarray:
    """Per row of the Newton matrix of ``scene``'s system: the index of the filament it
    belongs to, or −1 (the handle, the drive). ODE2 rows by their node; algebraic rows by
    the ODE2 columns they touch (a row touching one filament only is that filament's)."""
    import exudyn as exu  # here: exubrush, imported first, chooses Exudyn's core

    mbs = scene.mbs
    ode2 = mbs.systemData.ODE2Size()
    owner = np.full(matrix.shape[0], -1)
    for filament, sensors in enumerate(scene.node_sensors):
        for sensor in sensors:
            node = mbs.GetSensor(sensor)["nodeNumber"]
            start = mbs.GetNodeODE2Index(node)
            count = len(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates))
            owner[start:start + count] = filament
    for row in range(ode2, matrix.shape[0]):
        touched = set(owner[np.nonzero(matrix[row, :ode2])[0]].tolist()) - {-1}
        if len(touched) == 1:
            owner[row] = touched.pop()
    return owner


def capture_jacobians(scene, times: list[float]) -> list:
    """Set ``scene``'s pre-step function: its step hooks, and at the first step attempt at
    or after each of ``times`` [s] a copy of the solver's last Newton Jacobian (the one
    that step starts from: touching groups make one per attempt); the solve stops after
    the last. Returns the list it fills with (t, step size [s], Jacobian)."""
    captured: list = []
    waiting = sorted(times)

    def capture(mbs, t):
        scene.run_step_hooks(mbs, t)
        if waiting and t >= waiting[0]:
            waiting.pop(0)
            solver = mbs.sys["dynamicSolver"]
            captured.append((t, solver.it.currentStepSize,
                             np.array(solver.GetSystemJacobian())))
        return bool(waiting)

    scene.mbs.SetPreStepUserFunction(capture)
    return captured


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser, case="tuft", bristle=0)
    parser.add_argument("--at", type=float, nargs="+", metavar="T",
                        help="times [s] of the Jacobians (default: 25, 45, 65, 85 and "
                             "99 %% of the run)")
    args = parser.parse_args()
    prepared, scene, settings = build(parser, args, group=True)
    if scene.bristle_contact is None:
        parser.error("the bristle is solved alone: no group of touching bristles to split "
                     "(set contact.between_bristles=true, on a head whose bristles touch)")
    end = prepared.motion.end_time
    times = args.at or [share * end for share in DEFAULT_TIMES]
    if not all(0.0 < t <= end for t in times):
        parser.error(f"--at: give times within the run, above 0 s and up to {end:g} s")
    captured = capture_jacobians(scene, times)
    clock = time.perf_counter()
    try:
        scene.mbs.SolveDynamic(settings, storeSolver=True)
    except RuntimeError as error:  # Exudyn's SolverError: the step cut reached its minimum
        print(f"the solve stopped: {error}")
    reached = captured[-1][0] if captured else 0.0
    print(f"{len(scene.node_sensors)} filaments, solved to t = {reached:.4g} s in "
          f"{time.perf_counter() - clock:.1f} s")
    print("| t [s] | step [s] | coordinates | coupled | block Jacobi | sweeps 1e-3 / 1e-6 "
          "| block Gauss-Seidel | sweeps 1e-3 / 1e-6 | GMRES on block Jacobi 1e-3 / 1e-6 |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for t, step, jacobian in captured:
        owner = filament_owner(scene, jacobian)
        kept = np.nonzero(owner >= 0)[0]
        matrix, blocks = jacobian[np.ix_(kept, kept)], owner[kept]
        jacobi, gauss_seidel, coupled = block_rates(matrix, blocks)
        krylov = [accelerated_sweeps(matrix, blocks, r) for r in (1e-3, 1e-6)]
        print(f"| {t:.3f} | {step:.2e} | {len(kept)} | {coupled} | {jacobi:.6f} | "
              f"{sweeps(jacobi, 1e-3):g} / {sweeps(jacobi, 1e-6):g} | {gauss_seidel:.6f} | "
              f"{sweeps(gauss_seidel, 1e-3):g} / {sweeps(gauss_seidel, 1e-6):g} | "
              f"{krylov[0]} / {krylov[1]} |")


if __name__ == "__main__":
    main()
