"""The stick/slip law as Exudyn runs it (exubrush.contact.exudyn_contact with
``contact.friction_model = "stick-slip"``): both user functions give the law, the hook sees
the angles the law sees, and a pressed sphere sticks, breaks away and slides, or rolls, as
Coulomb's law and rigid-body mechanics say in closed form."""

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest
from exudyn.rigidBodyUtilities import InertiaSphere, RotXYZ2RotationMatrix

from exubrush.contact.exudyn_contact import (
    add_tip_contact,
    contact_user_function,
    initial_offset,
    stick_slip_hook,
)
from exubrush.contact.stick_slip import stick_slip_plane_force
from exubrush.models.assembly import rigid_marker
from exubrush.parameters.case import ContactLaw

LAW = ContactLaw(friction_model="stick-slip")
RADIUS = 0.4  # mm
MASS = 1e-6  # t (1 g)
PRESS = 0.1  # N, the dead load pressing the sphere on the plane
DEPTH = (PRESS / LAW.stiffness) ** (1.0 / LAW.stiffness_exponent)  # its static indentation


def _sphere(mbs, centre, angles=(0.0, 0.0, 0.0), velocity=(0.0, 0.0, 0.0),
            omega=(0.0, 0.0, 0.0)):
    """A solid sphere of MASS and RADIUS (its body's item dict); ``omega`` in the plane's
    frame."""
    return mbs.CreateRigidBody(referencePosition=list(centre), initialVelocity=list(velocity),
                               initialAngularVelocity=list(omega),
                               referenceRotationMatrix=RotXYZ2RotationMatrix(list(angles)),
                               inertia=InertiaSphere(MASS, RADIUS), gravity=[0, 0, 0],
                               show=False, returnDict=True)


def _contact(mbs, body, law, offset=None):
    plane = rigid_marker(mbs, mbs.AddObject(eii.ObjectGround()), [0.0, 0.0, 0.0])
    function = contact_user_function(mbs, law, RADIUS)
    connector = add_tip_contact(mbs, plane, body["bodyNumber"], function,
                                initial_offset(law, False) if offset is None else offset)
    return connector, function


STATES = [  # centre [mm], Tait-Bryan angles [rad], velocity [mm/s], state (offset)
    ((0.1, 0.2, 0.39), (0.3, -0.2, 0.1), (1.0, -0.5, -2.0),
     [0.1003, 0.1995, -0.38, 0.11, -0.08, 1.0]),  # sticks
    ((0.0, 0.0, 0.395), (1.1, 0.4, -0.3), (20.0, 0.0, 0.0),
     [-0.05, 0.5, -0.2, 0.3, 0.15, 0.95]),  # slides
]


@pytest.mark.parametrize("state", STATES)
def test_symbolic_and_python_laws_are_the_pure_law(state):
    centre, angles, velocity, offset = state
    omega = (3.0, -2.0, 1.0)  # rad/s
    expected = -np.array(stick_slip_plane_force(LAW, RADIUS, centre, angles, velocity, omega,
                                                offset))
    assert np.hypot(*expected[:2]) > 0.0
    for backend in ("paper-symbolic", "paper-python"):
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        body = _sphere(mbs, centre, angles, velocity, omega)
        connector, _ = _contact(mbs, body, LAW.replace(backend=backend), offset)
        mbs.Assemble()
        load = np.concatenate([
            mbs.GetObjectOutput(connector, exu.OutputVariableType.ForceLocal),
            mbs.GetObjectOutput(connector, exu.OutputVariableType.TorqueLocal)])
        # the same double-precision operations in C++ and Python: round-off
        np.testing.assert_allclose(load, expected, rtol=1e-12, atol=1e-15)


def test_the_hook_reads_the_angles_the_law_is_given():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    body = _sphere(mbs, (0.0, 0.0, 0.39), (0.7, -0.4, 0.25))
    seen = []
    law = contact_user_function(mbs, LAW.replace(backend="paper-python"), RADIUS)

    def recorded(mbs, t, item, displacement, rotation, *rest):
        seen.append(list(rotation))
        return law(mbs, t, item, displacement, rotation, *rest)

    plane = rigid_marker(mbs, mbs.AddObject(eii.ObjectGround()), [0.0, 0.0, 0.0])
    connector = add_tip_contact(mbs, plane, body["bodyNumber"], recorded,
                                initial_offset(LAW, False))
    mbs.Assemble()
    mbs.GetObjectOutput(connector, exu.OutputVariableType.ForceLocal)  # calls the law
    output = mbs.GetObjectOutput(connector, exu.OutputVariableType.Rotation)
    assert seen and np.allclose(seen[-1], output, atol=1e-14)
    assert np.allclose(output, (0.7, -0.4, 0.25), atol=1e-12)


def _pressed_sphere(pull, locked: bool, end_time: float, steps: int):
    """A sphere pressed on the plane by PRESS and pulled along x at its centre by
    ``pull(t)`` [N]; rotations locked (pure sliding) or free (it may roll). Returns the
    record (t, x [mm], friction force along x [N], angle about y [rad]) at each step's
    start."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    body = _sphere(mbs, (0.0, 0.0, RADIUS - DEPTH))
    connector, _ = _contact(mbs, body, LAW)
    if locked:
        ground = mbs.AddObject(eii.ObjectGround())
        mbs.AddObject(eii.ObjectJointGeneric(
            markerNumbers=[rigid_marker(mbs, ground, [0.0, 0.0, 0.0]),
                           rigid_marker(mbs, body["bodyNumber"], [0.0, 0.0, 0.0])],
            constrainedAxes=[0, 0, 0, 1, 1, 1]))
    centre = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=body["bodyNumber"],
                                                  localPosition=[0, 0, 0]))
    mbs.AddLoad(eii.LoadForceVector(markerNumber=centre, loadVector=[0, 0, -PRESS]))
    mbs.AddLoad(eii.LoadForceVector(markerNumber=centre, loadVector=[0, 0, 0],
                                    loadVectorUserFunction=lambda mbs, t, load: [pull(t), 0, 0]))
    commit = stick_slip_hook([(connector, RADIUS)], LAW)
    record = []

    def before_step(mbs, t):
        commit(mbs, t)
        # t is the time the step goes to; the state is the step's start, a step before
        output = exu.OutputVariableType
        record.append((t - end_time / steps,
                       mbs.GetObjectOutput(connector, output.Displacement)[0],
                       mbs.GetObjectOutput(connector, output.ForceLocal)[0],
                       mbs.GetObjectOutput(connector, output.Rotation)[1]))
        return True

    mbs.SetPreStepUserFunction(before_step)
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.timeIntegration.endTime = end_time
    settings.timeIntegration.numberOfSteps = steps
    settings.timeIntegration.generalizedAlpha.spectralRadius = 0.0
    mbs.SolveDynamic(settings)
    return np.array(record)


def test_a_pressed_sphere_holds_until_mu_s_then_slides_at_mu_d():
    rate = 0.1  # N/s: the pull reaches mu_s PRESS = 0.08 N at t = 0.8 s
    record = _pressed_sphere(lambda t: rate * t, locked=True, end_time=1.0, steps=2000)
    time, x, friction = record[:, 0], record[:, 1], record[:, 2]
    breakaway = 0.8 * PRESS / rate
    held = time < 0.98 * breakaway
    # held: the sphere moves only by the spring's elastic slip, s_e F / (mu_s F_n), and,
    # once the ring of the pull's start has died out (10 ms), the friction balances the
    # slow pull (its inertia m a is ~0)
    assert np.max(np.abs(x[held])) <= 1.001 * LAW.stick_stretch
    settled = held & (time > 0.01)
    np.testing.assert_allclose(friction[settled], rate * time[settled], rtol=1e-6)
    # it breaks away when the pull reaches mu_s F_n: until the slip exceeds v_s, mu_s
    # holds it back and only the ramp's excess c (t - t*) drives it, so one more um of
    # travel takes (6 m um / c)^(1/3) = 4 ms
    moved = time[np.argmax(x > 2 * LAW.stick_stretch)]
    assert breakaway < moved < breakaway + 0.006
    # once sliding beyond v_d, mu_d PRESS, opposing the slide (connector load: minus it)
    sliding = time > breakaway + 0.05
    assert np.all(np.diff(x[sliding]) > 0.0)
    np.testing.assert_allclose(friction[sliding], 0.76 * PRESS, rtol=1e-6)


def test_a_sphere_pulled_gently_rolls_without_slipping():
    pull = 0.01  # N: rolling needs a friction of 2/7 of it, far below mu_s PRESS
    record = _pressed_sphere(lambda t: pull, locked=False, end_time=0.008, steps=800)
    time, x, friction, angle = record.T
    # a solid sphere rolling: m a = F - f, (2/5) m r^2 alpha = f r, a = alpha r
    # -> f = 2 F / 7 and x = (5/7) (F/m) t^2 / 2
    # after the stick spring's first ring has died out (its damper: tau = 10 us)
    np.testing.assert_allclose(friction[time > 6e-3], 2.0 * pull / 7.0, rtol=1e-3)
    assert x[-1] == pytest.approx(5.0 / 7.0 * pull / MASS * time[-1] ** 2 / 2.0, rel=1e-2)
    # it rolls: the centre advances r per radian (to the stick's micrometre)
    assert x[-1] > 0.1
    assert x[-1] == pytest.approx(RADIUS * angle[-1], abs=2 * LAW.stick_stretch)


def _one_bristle(*overrides):
    """The paper's orthogonal case on one bristle, one period: (flat-zone mean F_n of its
    whole strokes [N], the largest F_n in each reversal zone [N]), as the reversal-peak
    study measures them (exubrush.output.reversal.reversal_metrics)."""
    from exubrush.output.experiment import ForceSeries
    from exubrush.output.reversal import reversal_metrics
    from exubrush.parameters.io import load_case
    from exubrush.simulation import simulate

    case = load_case("orthogonal", ["head.rows=1", "head.columns=1", "motion.periods=1",
                                    *overrides])
    results = simulate(case, progress=False)
    assert results.metadata["status"] == "completed", results.metadata["message"]
    metrics = reversal_metrics(ForceSeries.from_results(results))
    return metrics["flat_normal"], np.array(metrics["peaks"])


def test_a_bristle_of_the_papers_head_gets_the_papers_law_without_its_creep():
    # the paper's law with its band 100x narrower has converged (docs/model.md, 'The
    # friction band's sensitivity'); at its own band (1.2 mm/s) the tip creeps and the
    # second peak is a third lower
    stick_slip = _one_bristle("contact.friction_model='stick-slip'")
    narrow = _one_bristle("contact.static_velocity='0.012 mm/s'",
                          "contact.dynamic_velocity='0.015 mm/s'")
    paper = _one_bristle()
    # measured: flat 16.07 against 16.08 mN, peaks within 0.9 %; the bounds leave room
    # for the narrow band's own residual creep, not for the paper band's 7 % and 35 %
    assert stick_slip[0] == pytest.approx(narrow[0], rel=0.01)
    np.testing.assert_allclose(stick_slip[1], narrow[1], rtol=0.03)
    assert paper[0] < 0.95 * stick_slip[0]
    assert paper[1][1] < 0.8 * stick_slip[1][1]
