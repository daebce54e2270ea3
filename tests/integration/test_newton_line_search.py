"""Newton's line search in Exudyn (exubrush.run.newton.LineSearch): it changes Newton's path,
not the solution a step converges to, and shortens updates that overshoot."""

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.newton import LineSearch
from exubrush.run.prepared import prepare
from exubrush.run.scene import build_scene
from exubrush.run.solver import quiet
from exubrush.simulation import simulate


def _arctan_spring(search, start, force, step, end, tolerance=1e-8, minimum_step=None):
    """A unit mass on a spring pulling with force·arctan(x) [N] from x = ``start``, at rest,
    stepped with full Newton, at fixed steps or (``minimum_step``) cut after a failed
    attempt down to that; returns (x over the recorded steps, Newton iterations). Newton on
    arctan overshoots from far out: the slope there is small."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    node = mbs.AddNode(eii.NodePoint(referenceCoordinates=[0.0, 0.0, 0.0],
                                     initialCoordinates=[start, 0.0, 0.0]))
    mbs.AddObject(eii.MassPoint(mass=1.0, nodeNumber=node))
    anchor = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=mbs.AddNode(
        eii.NodePointGround()), coordinate=0))
    mass = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=node, coordinate=0))
    mbs.AddObject(eii.ObjectConnectorCoordinateSpringDamper(
        markerNumbers=[anchor, mass],
        springForceUserFunction=lambda mbs, t, item, u, v, k, d, offset: force * np.arctan(u)))
    sensor = mbs.AddSensor(eii.SensorNode(nodeNumber=node, storeInternal=True,
                                          outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    settings = quiet(exu.SimulationSettings())
    ti = settings.timeIntegration
    ti.endTime, ti.numberOfSteps = end, round(end / step)
    ti.automaticStepSize = minimum_step is not None
    if minimum_step is not None:
        ti.minimumStepSize = minimum_step
        ti.adaptiveStepDecrease = 0.25
    ti.generalizedAlpha.spectralRadius = 0.0
    ti.newton.useModifiedNewton = False
    ti.newton.adaptInitialResidual = False
    ti.newton.relativeTolerance = tolerance
    ti.newton.maxIterations = 25
    settings.solution.sensors.writePeriod = step
    if search is not None:
        mbs.SetPreNewtonResidualUserFunction(search)
    assert mbs.SolveDynamic(settings, storeSolver=True)
    return (np.asarray(mbs.GetSensorStoredData(sensor))[:, 1],
            mbs.sys["dynamicSolver"].it.newtonStepsCount)


def test_overshooting_updates_are_shortened_and_the_equilibrium_is_reached():
    # 1e6 N·arctan(x) from x = 10 at 0.1 s steps: the spring's slope at the start is 1e4
    # N/mm, at the solution 1e6, and the mass term 1/(β h²) about 200, so Newton's full
    # update from the start overshoots far past 0
    search = LineSearch()
    plain, plain_iterations = _arctan_spring(None, 10.0, 1e6, 0.1, 2.0)
    searched, searched_iterations = _arctan_spring(search, 10.0, 1e6, 0.1, 2.0)
    assert search.counts.shortened > 0
    # measured: 224 iterations without, 44 with
    assert searched_iterations < plain_iterations / 3
    # the spring's equilibrium is x = 0; with spectral radius 0, generalized-alpha damps a
    # mode with h·ω = 100 out within a step or two, so 20 steps end there (to the tolerance)
    assert abs(plain[-1]) < 1e-9 and abs(searched[-1]) < 1e-9


def test_where_the_update_does_not_overshoot_the_solution_is_the_same():
    # a resolved oscillation (ω = 100 rad/s, h ω = 0.5): every step converges to the same
    # state whatever path Newton takes; they differ by Newton's tolerance (1e-10 of the
    # residual, amplified by the 100 steps)
    plain, _ = _arctan_spring(None, 0.5, 1e4, 0.005, 0.5, tolerance=1e-10)
    searched, _ = _arctan_spring(LineSearch(), 0.5, 1e4, 0.005, 0.5, tolerance=1e-10)
    assert np.max(np.abs(searched - plain)) < 1e-7 * 0.5


def test_a_hopeless_attempt_is_given_up_and_its_step_cut():
    # the overshooting spring above, its steps cut where Newton fails: the first attempts'
    # residuals are still above a tenth of their first after two (shortened) updates, so
    # with give_up they are abandoned at the third iteration and their steps cut. Here the
    # search alone would have converged (44 iterations in all against 183 given up and cut):
    # the rule pays only where such attempts mostly fail (docs/decisions/0026)
    kept = LineSearch()
    given = LineSearch(give_up=0.1)
    x_kept, iterations_kept = _arctan_spring(kept, 10.0, 1e6, 0.1, 2.0, minimum_step=1e-6)
    x_given, iterations_given = _arctan_spring(given, 10.0, 1e6, 0.1, 2.0, minimum_step=1e-6)
    assert kept.counts.given_up == 0 and given.counts.given_up > 0
    # Exudyn stopped those attempts and cut their steps: Newton took another path (were
    # the stop ignored, it would run the same iterations as without the rule)
    assert iterations_given != iterations_kept
    # the equilibrium is reached all the same (spectral radius 0 damps the mode out)
    assert abs(x_kept[-1]) < 1e-9 and abs(x_given[-1]) < 1e-9


def test_an_attempt_at_the_minimum_step_is_not_given_up():
    # a step that cannot be cut (the minimum step is the step): giving up would stop the
    # run, so the search lets Newton run to its iterations as without the rule
    given = LineSearch(give_up=0.1)
    x_given, iterations_given = _arctan_spring(given, 10.0, 1e6, 0.1, 2.0, minimum_step=0.1)
    x_plain, iterations_plain = _arctan_spring(LineSearch(), 10.0, 1e6, 0.1, 2.0,
                                               minimum_step=0.1)
    assert given.counts.given_up == 0
    assert iterations_given == iterations_plain
    assert np.array_equal(x_given, x_plain)


SMALL = ["head.rows=1", "head.columns=1", "motion.periods=0.05"]


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_bristle_on_euler_parameters_gives_the_same_forces_with_and_without():
    # Euler parameters bring algebraic coordinates (their normalisation): the blend of
    # states must keep them consistent. Fixed 0.5 ms steps (no cut, so both runs take the
    # same steps; with cuts, the step sequences differ and so do the forces at an event, by
    # the time discretisation's error), tight Newton tolerances: the forces differ by the
    # tolerance (measured 2e-11 N with 53 updates shortened)
    fixed = ["solver.step_size='0.5 ms'", "solver.minimum_step_size='0.5 ms'",
             "solver.sliding_step_factor=1", "solver.relative_tolerance=1e-10",
             "solver.force_tolerance=0"]
    runs = [simulate(load_case("orthogonal", [*SMALL, *fixed, f"solver.line_search='{mode}'"]),
                     progress=False, workers=1) for mode in ("off", "always")]
    assert all(run.metadata["completed"] for run in runs)
    assert runs[1].metadata["solver_statistics"]["shortened_updates"] > 0
    peak = np.max(np.abs(runs[0].normal_force))
    assert np.max(np.abs(runs[1].normal_force - runs[0].normal_force)) < 1e-8 * peak


@pytest.mark.parametrize(("case", "overrides", "expected"), [
    ("orthogonal", [], None),  # one DFM bristle on the plane: auto leaves it off
    ("interdental", [], None),  # on a tooth row too
    ("interdental", ["solver.line_search='after-cut'"], "after-cut"),
    ("interdental", ["solver.line_search='off'"], None),
    ("orthogonal", ["solver.line_search='always'"], "always"),
    ("orthogonal", ["solver.line_search='after-cut'"], "after-cut"),
    ("interdental", ["model.kind='prb'"], None),  # rotation vectors: auto leaves it off
])
def test_auto_runs_the_search_where_it_applies(case, overrides, expected):
    scene = build_scene(prepare(load_case(case, [*SMALL, *overrides])), (0,))
    assert (scene.line_search is not None) == (expected is not None)
    # "always" sets Exudyn's function now, "after-cut" from a step hook when a step is cut
    assert (scene.mbs.GetPreNewtonResidualUserFunction() != 0) == (expected == "always")


def test_a_touching_group_searches_at_every_iteration():
    case = load_case("validation/benchmarks/tuft7.toml", ["motion.periods=0.05"])
    prepared = prepare(case)
    scene = build_scene(prepared, prepared.groups[0])
    assert scene.line_search is not None
    assert scene.mbs.GetPreNewtonResidualUserFunction() != 0
    # and gives up hopeless attempts as solver.touching_give_up says
    assert scene.line_search.give_up == case.solver.touching_give_up > 0.0


def test_one_bristle_never_gives_up_an_attempt():
    # touching_give_up is about groups of touching bristles: a lone bristle's search
    # (asked for with "always") lets Newton run to its iterations
    scene = build_scene(prepare(load_case("orthogonal", [*SMALL, "solver.line_search='always'"])),
                        (0,))
    assert scene.line_search.give_up == 0.0


def test_a_search_on_rotation_vectors_is_refused_in_one_line():
    with pytest.raises(ParameterError, match="needs model.rotation 'euler-parameters'"):
        load_case("orthogonal", ["model.kind='prb'", "solver.line_search='always'"])
