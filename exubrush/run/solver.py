"""The one place where Exudyn's SimulationSettings are filled."""

from __future__ import annotations

import exudyn as exu

from exubrush.parameters.settings import Solver


def quiet(settings: exu.SimulationSettings) -> exu.SimulationSettings:
    """Switch off Exudyn's console output, solution files and graphics."""
    settings.timeIntegration.verboseMode = 0
    settings.staticSolver.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = 1e30
    settings.show.computationTime = False
    settings.show.statistics = False
    return settings


def dynamic_settings(solver: Solver, end_time: float, output_interval: float,
                     touching: bool = False, force_tolerance: float = 0.0):
    """Implicit generalized-α settings for a brushing run.

    Choices (each measured on this problem, docs/decisions/0002 and 0016): spectral
    radius 0 by default,
    modified Newton, automatic step reduction down to ``minimum_step_size`` (snap-through
    at stroke reversals needs tiny steps), a failed step cut by ``step_cut`` (0.25) and
    allowed to double again after ``step_recovery_steps`` (4) good steps: Exudyn's 10 kept
    the step tiny through stick-slip chatter before the friction drop was lagged, 2 (0.4.0
    to 0.8.0) let it grow back into a snap-through and fail again; ``adaptInitialResidual``
    off (with it on, a diverged first iteration resets the reference residual and a wrong
    step can pass), no
    solution-norm bound (a small one caused false failures at snap-through), and
    ``newton_iterations`` (12) Newton iterations per try: a step that has not converged by
    then is cut at once instead of after Exudyn's 25 full-Newton iterations, each with a
    fresh Jacobian (on five DFM bristles: 17 % less wall time, 24 % fewer Jacobians).
    ``touching``: the system holds bristles that touch each other (exubrush.contact.
    exudyn_between): a sparse solver, and the sparsity pattern is analysed anew at every
    factorisation, as contacts come and go; a fresh Jacobian at the start of every step
    (with the last step's, the contacts had moved enough that Newton stalled until a new one
    was made, 5 iterations a step instead of 2) and ``solver.touching_relative_tolerance``
    (touching filaments leave a residual floor near 1e-5 of a step's initial residual that
    Newton could not pass at any step size). On a 7-filament tuft, approach and 0.1 period,
    the two together: 37-39 s -> 7.6 s (seed 1), 28-74 s -> 19 s (seed 2); each alone
    gained little or nothing (docs/decisions/0011).
    ``force_tolerance`` [N]: Newton also accepts a step whose residual is below it
    (:meth:`exubrush.run.prepared.PreparedCase.newton_force_tolerance`; docs/model.md, "Newton's
    tolerance"); Exudyn's absolute tolerance is the larger of it and
    ``solver.absolute_tolerance``.
    """
    settings = quiet(exu.SimulationSettings())
    ti = settings.timeIntegration
    ti.endTime = end_time
    ti.numberOfSteps = max(1, round(end_time / solver.step_size))
    ti.minimumStepSize = solver.minimum_step_size
    ti.automaticStepSize = True
    ti.adaptiveStep = True
    ti.adaptiveStepRecoverySteps = solver.step_recovery_steps
    ti.adaptiveStepDecrease = solver.step_cut
    ti.generalizedAlpha.spectralRadius = solver.spectral_radius
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.newton.useModifiedNewton = solver.modified_newton
    ti.newton.modifiedNewtonContractivity = solver.newton_contractivity
    ti.newton.modifiedNewtonJacUpdatePerStep = touching
    ti.newton.relativeTolerance = (solver.touching_relative_tolerance if touching
                                   else solver.relative_tolerance)
    ti.newton.absoluteTolerance = max(solver.absolute_tolerance, force_tolerance)
    ti.newton.adaptInitialResidual = False
    ti.newton.maxIterations = solver.newton_iterations
    settings.solution.sensors.writePeriod = output_interval
    settings.linearSolver.solverType = getattr(exu.LinearSolverType,
                                               linear_solver(solver, touching))
    # without contacts between bristles, a coupled head's sparsity pattern never changes
    settings.linearSolver.reuseAnalyzedPattern = not touching
    settings.parallel.numberOfThreads = solver.threads
    return settings


def linear_solver(solver: Solver, touching: bool = False) -> str:
    """Name of the Exudyn linear solver for ``solver.linear_solver``.

    "auto": a whole head ("coupled") or a group of bristles that touch each other
    (``touching``) has thousands of coordinates with a block-sparse Jacobian, so
    EigenSparse; one bristle has a few dozen, so a dense LU. EigenDense (partial
    pivoting) solved five DFM bristles 20 % faster than EXUdense, with 0.4 % more steps and
    mean forces within 0.01 %; like EXUdense, it lets Exudyn cut the step where the Jacobian
    turns singular (a PRB link swinging round at a reversal, where the Stribeck friction's
    negative slope cancels the inertia); EigenSparse stops the run there.
    """
    if solver.linear_solver != "auto":
        return solver.linear_solver
    return "EigenSparse" if solver.partition == "coupled" or touching else "EigenDense"


def fresh_jacobian_after_step_change():
    """Pre-step hook (mbs, t) that asks Exudyn for a new Newton Jacobian whenever the step
    size differs from the last attempt's.

    Exudyn's modified Newton keeps its factorised Jacobian across steps, and a step retried
    with a smaller size starts from it too. Where that factorisation had failed (a singular
    Jacobian), the retry solves with a matrix that was never factorised: the checked core
    stops the run ("matrix is not factorized"), the fast core crashed (SIGSEGV after 21
    minutes of a 19-filament tuft with contact between bristles). EigenSparse is exposed to
    this, the dense solvers are not. A Jacobian made for another step size is also wrong in
    its mass term (1/(β h²)), so a retry starts better with a new one: on a 7-filament tuft
    (approach and 0.1 period) the run took 12,224 Jacobians and 107 s against 11,569 and
    104 s without the hook. Groups of touching bristles do not need it: their settings
    (``dynamic_settings(touching=True)``) renew the Jacobian at every step attempt, retries
    included; a coupled head without contact between bristles does.
    """
    last = [None]
    start = exu.ConfigurationType.StartOfStep

    def refresh(mbs, t):
        step = t - mbs.systemData.GetTime(start)
        # t and the step's start differ by rounding for one step size: a relative margin
        if last[0] is not None and abs(step - last[0]) > 1e-9 * last[0]:
            mbs.solverSignalJacobianUpdate = True
        last[0] = step

    return refresh


def fresh_jacobian_while(acting):
    """Pre-step hook (mbs, t) that asks Exudyn for a new Newton Jacobian at every step
    attempt while ``acting(t)``: a head driven by a sine pose term moves its handle so far
    in a step (a sonic head accelerates it at 4e6 mm/s²) that the last step's Jacobian left
    Newton on a stale matrix for half its iterations. On one filament of the `sonic` case
    (0.05 s of swing) its steps went from 991 to 865, its Newton iterations from 8,839 to
    6,267, its Jacobians from 2,733 to 2,173 (docs/motion.md)."""

    def refresh(mbs, t):
        if acting(t):
            mbs.solverSignalJacobianUpdate = True

    return refresh


def step_cap(largest):
    """Pre-step hook (mbs, t) that sets Exudyn's largest step to ``largest(mbs, t)`` [s].

    Exudyn calls the hook with t at the end of the step it is about to try, whose size is
    fixed by then. Exudyn applies the cap when it next tries to grow the step, which it
    does every ``solver.step_recovery_steps`` good steps (counting on while the step is at
    the cap): a larger cap lets the step double towards it there, and a smaller one takes
    the step down to it there (or at the next failed try, which cuts it by
    ``solver.step_cut``). So the step the hook sees and up to ``step_recovery_steps`` − 1
    after it may still be large, and ``largest`` should look that far ahead. A good
    step is one that converged within Exudyn's ``adaptiveStepRecoveryIterations`` (7)
    Newton iterations: large steps that each take more but converge would keep the step
    large for longer; in the middle of a stroke they take one or two.
    """

    last = [None, None]  # the solver and the cap last set on it

    def cap(mbs, t):
        solver = mbs.sys.get("dynamicSolver")
        if solver is not None:
            value = largest(mbs, t)
            # Exudyn sets maxStepSize only when a solve starts: an unchanged cap is not set
            # again (~0.6 µs a step)
            if solver is not last[0] or value != last[1]:
                solver.it.maxStepSize = value
                last[:] = [solver, value]

    return cap


def record_coordinates(settings: exu.SimulationSettings, path: str, period: float) -> None:
    """Let the solver write the ODE2 coordinates (no velocities, accelerations, algebraic or
    data coordinates) to the text solution file ``path`` every ``period`` [s]: the format
    Exudyn's SolutionViewer reads (exubrush.output.viewer)."""
    file = settings.solution.file
    file.write = True
    file.name = path
    file.binary = False
    file.writePeriod = period
    file.writeInitialValues = True
    export = file.export
    export.velocities = False
    export.accelerations = False
    export.algebraicCoordinates = False
    export.dataCoordinates = False
    export.ODE1Velocities = False


def static_settings(load_steps: int, linear_solver: str = "EXUdense") -> exu.SimulationSettings:
    """Static Newton settings for the convergence references (exubrush.statics,
    exubrush.shear_beam): the load in ``load_steps`` equal increments with
    adaptive steps, Newton tolerances 1e-8 relative and 1e-10 absolute (tighter ones make
    Exudyn's static Newton solve fail, measured on the shear-beam reference), at most 50
    iterations per increment."""
    settings = quiet(exu.SimulationSettings())
    static = settings.staticSolver
    static.numberOfLoadSteps = load_steps
    static.adaptiveStep = True
    static.newton.relativeTolerance = 1e-8
    static.newton.absoluteTolerance = 1e-10
    static.newton.maxIterations = 50
    settings.linearSolver.solverType = getattr(exu.LinearSolverType, linear_solver)
    return settings
