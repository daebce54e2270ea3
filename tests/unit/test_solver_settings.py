"""Solver parameters reach Exudyn's SimulationSettings (exubrush.run.solver)."""

import math
from types import SimpleNamespace

import exudyn as exu
import pytest

from exubrush.parameters.io import load_case
from exubrush.parameters.settings import Solver
from exubrush.run.prepared import prepare
from exubrush.run.solver import (
    dynamic_settings,
    fresh_jacobian_after_step_change,
    fresh_jacobian_while,
    step_cap,
)


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


def test_the_step_control_reaches_exudyn():
    default = dynamic_settings(Solver(), 1.0, 0.01).timeIntegration
    assert (default.adaptiveStepDecrease, default.adaptiveStepRecoverySteps) == (0.25, 4)
    chosen = dynamic_settings(Solver(step_cut=0.1, step_recovery_steps=7), 1.0, 0.01)
    assert chosen.timeIntegration.adaptiveStepDecrease == 0.1
    assert chosen.timeIntegration.adaptiveStepRecoverySteps == 7


def test_newtons_contractivity_reaches_exudyn():
    default = dynamic_settings(Solver(), 1.0, 0.01).timeIntegration.newton
    assert default.modifiedNewtonContractivity == 0.5  # Exudyn's own default
    chosen = dynamic_settings(Solver(newton_contractivity=1.0), 1.0, 0.01)
    assert chosen.timeIntegration.newton.modifiedNewtonContractivity == 1.0


def test_a_touching_group_gets_a_jacobian_every_step_and_its_own_tolerance():
    solver = Solver(relative_tolerance=1e-7, touching_relative_tolerance=3e-5)
    touching = dynamic_settings(solver, end_time=1.0, output_interval=0.01, touching=True)
    apart = dynamic_settings(solver, end_time=1.0, output_interval=0.01)
    assert touching.timeIntegration.newton.modifiedNewtonJacUpdatePerStep
    assert touching.timeIntegration.newton.relativeTolerance == 3e-5
    assert touching.linearSolver.solverType == exu.LinearSolverType.EigenSparse
    assert not apart.timeIntegration.newton.modifiedNewtonJacUpdatePerStep
    assert apart.timeIntegration.newton.relativeTolerance == 1e-7


class _System:
    """What fresh_jacobian_after_step_change reads and sets of a MainSystem."""

    def __init__(self):
        self.start = 0.0
        self.solverSignalJacobianUpdate = False
        self.systemData = self

    def GetTime(self, configuration):  # noqa: N802 (Exudyn's name)
        assert configuration == exu.ConfigurationType.StartOfStep
        return self.start


def test_a_new_jacobian_is_asked_for_exactly_when_the_step_size_changes():
    hook, system = fresh_jacobian_after_step_change(), _System()
    asked = []
    # (start of the step, end of the step): equal steps, a retry at half the size from the
    # same start, steps of that size (rounding in t - start), a larger one again
    for start, end in [(0.0, 2e-3), (2e-3, 4e-3), (4e-3, 6e-3), (4e-3, 5e-3),
                       (5e-3, 6e-3), (0.1 + 6e-3, 0.1 + 7e-3), (7e-3, 9e-3)]:
        system.start, system.solverSignalJacobianUpdate = start, False
        hook(system, end)
        asked.append(system.solverSignalJacobianUpdate)
    assert asked == [False, False, False, True, False, False, True]


def test_a_new_jacobian_is_asked_for_at_every_step_while_a_sine_term_acts(tmp_path):
    # the hook the scene adds for sine pose terms: their windows, look-ahead included
    # (exubrush.run.step_policy.term_step_cap), here 0.1-0.2 s
    from exubrush.run.scene import build_scene

    text = "[head]\nrows = 1\ncolumns = 1\n[motion]\nprofile = 'none'\nperiod = '0.2 s'\n" \
           "periods = 1\napproach_duration = '0.1 s'\nhold_duration = '0.01 s'\n" \
           "[[motion.sine]]\naxis = 'y'\namplitude = '0.1 mm'\nfrequency = '200 Hz'\n" \
           "start = '0.05 s'\nduration = '0.05 s'\n"
    hook = fresh_jacobian_while(lambda t: 0.1 <= t <= 0.2)
    asked = []
    for t in (0.05, 0.1, 0.15, 0.2, 0.25):
        system = _System()
        hook(system, t)
        asked.append(system.solverSignalJacobianUpdate)
    assert asked == [False, True, True, True, False]
    path = tmp_path / "shaken.toml"
    path.write_text(text)
    scene = build_scene(prepare(load_case(str(path))))
    start = 0.11 + 0.05  # the slide's start (approach and hold), then the term's start
    ahead = 6 * 2e-3  # (step_recovery_steps + 2) steps of step_size before it
    flags = []
    for t in (start - ahead - 1e-3, start - ahead + 1e-3, start + 0.05 - 1e-3,
              start + 0.05 + 1e-3):
        system = _System()
        system.start = t - 1e-4
        for step_hook in scene.step_hooks:
            if step_hook.__qualname__.startswith("fresh_jacobian_while"):
                step_hook(system, t)
        flags.append(system.solverSignalJacobianUpdate)
    assert flags == [False, True, True, False]


def test_newton_accepts_a_residual_below_the_force_tolerance_or_the_absolute_one():
    solver = Solver(absolute_tolerance=1e-10)
    assert dynamic_settings(solver, 1.0, 0.01, force_tolerance=6e-6) \
        .timeIntegration.newton.absoluteTolerance == 6e-6
    # off (0) or below the absolute tolerance: the absolute tolerance stays
    assert dynamic_settings(solver, 1.0, 0.01).timeIntegration.newton.absoluteTolerance == 1e-10
    assert dynamic_settings(Solver(absolute_tolerance=1e-4), 1.0, 0.01, force_tolerance=6e-6) \
        .timeIntegration.newton.absoluteTolerance == 1e-4


def test_the_force_tolerance_follows_the_weakest_bristle_of_a_group():
    case = load_case("orthogonal", ["head.rows=1", "head.columns=2",
                                    "solver.force_tolerance=1e-3"])
    prepared = prepare(case)
    shape, material = case.head.bristle, case.head.material
    # Euler load of a clamped-free rectangular column, pi^2 E I_min / (4 l^2), I_min = b h^3/12
    thin = min(shape.width, shape.height)
    thick = max(shape.width, shape.height)
    euler = math.pi**2 * material.youngs_modulus * thick * thin**3 / 12 / (4 * shape.length**2)
    assert prepared.newton_force_tolerance((0, 1)) == pytest.approx(1e-3 * euler, rel=1e-12)


def test_the_step_cap_follows_the_condition_once_the_solver_exists():
    hook = step_cap(lambda mbs, t: 5e-3 if 1.0 <= t < 2.0 else 2e-3)
    iteration = SimpleNamespace(maxStepSize=2e-3)
    system = SimpleNamespace(sys={})
    hook(system, 1.5)  # before Exudyn stored its solver: nothing to set, no error
    system.sys["dynamicSolver"] = SimpleNamespace(it=iteration)
    caps = []
    for t in (0.5, 1.0, 1.5, 2.0):
        hook(system, t)
        caps.append(iteration.maxStepSize)
    assert caps == [2e-3, 5e-3, 5e-3, 2e-3]


# the benchmark harness starts every variant from fixed older settings (its BASELINE) and
# applies a preset on top: a preset must set each of them, or its rows measure the old one
OLDER_SETTINGS = ["solver.step_size='1 ms'", "solver.relative_tolerance=1e-8",
                  "solver.force_tolerance=0", "solver.sliding_step_factor=1",
                  "solver.friction_drop='implicit'", "solver.step_cut=0.5",
                  "solver.step_recovery_steps=2", "model.segments=8"]


@pytest.mark.parametrize("name", ["fast", "balanced", "accurate"])
def test_a_preset_sets_every_setting_it_stands_for(name):
    from exubrush.presets import preset_overrides

    over_older = load_case("orthogonal", [*OLDER_SETTINGS, *preset_overrides(name)])
    alone = load_case("orthogonal", preset_overrides(name))
    assert over_older.solver == alone.solver and over_older.model == alone.model


@pytest.mark.parametrize("case_name", ["orthogonal", "parallel", "tuft", "interdental"])
def test_the_balanced_preset_is_the_case_defaults(case_name):
    from exubrush.presets import preset_overrides

    default = load_case(case_name)
    balanced = load_case(case_name, preset_overrides("balanced"))
    assert balanced.solver == default.solver and balanced.model == default.model
