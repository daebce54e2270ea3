"""Solver parameters reach Exudyn's SimulationSettings (exubrush.solver)."""

import exudyn as exu

from exubrush.parameters.case import Solver
from exubrush.solver import dynamic_settings


def test_threads_and_linear_solver_reach_exudyn():
    solver = Solver(partition="coupled", threads=2)
    settings = dynamic_settings(solver, end_time=1.0, output_interval=0.01)
    assert settings.parallel.numberOfThreads == 2
    # auto: a coupled head is sparse
    assert settings.linearSolver.solverType == exu.LinearSolverType.EigenSparse


def test_defaults_solve_one_bristle_dense_on_one_thread():
    settings = dynamic_settings(Solver(), end_time=1.0, output_interval=0.01)
    assert settings.parallel.numberOfThreads == 1
    assert settings.linearSolver.solverType == exu.LinearSolverType.EigenDense
    assert settings.timeIntegration.newton.maxIterations == 12
