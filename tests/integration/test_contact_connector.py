"""The contact law inside Exudyn: back ends agree and the sign convention holds."""

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest
from exudyn.rigidBodyUtilities import InertiaSphere

from exubrush.contact.exudyn_contact import add_tip_contact, contact_user_function
from exubrush.contact.laws import ContactLaw, sphere_plane_force

LAW = ContactLaw()
RADIUS = 0.4
STATES = [  # centre [mm], velocity [mm/s], angular velocity [rad/s]
    ([0.1, 0.2, 0.35], [1.0, -0.5, -2.0], [0.3, 0.1, 0.0]),
    ([0.0, 0.0, 0.39], [0.1, 0.05, 0.3], [0.0, 0.0, 0.0]),
    ([0.0, 0.0, 0.30], [5.0, 0.0, 0.0], [0.0, 2.0, 0.0]),
    ([0.0, 0.0, 0.50], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]),
]


def _connector_load(backend, centre, velocity, omega):
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    body = mbs.CreateRigidBody(referencePosition=centre, initialVelocity=velocity,
                               initialAngularVelocity=omega, inertia=InertiaSphere(1e-9, RADIUS),
                               gravity=[0, 0, 0], show=False, returnDict=True)
    plane = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
    function = contact_user_function(mbs, LAW, RADIUS, backend)
    connector = add_tip_contact(mbs, plane, body["bodyNumber"], function)
    mbs.Assemble()
    force = mbs.GetObjectOutput(connector, exu.OutputVariableType.ForceLocal)
    torque = mbs.GetObjectOutput(connector, exu.OutputVariableType.TorqueLocal)
    return np.concatenate([force, torque])


@pytest.mark.parametrize("state", STATES)
def test_symbolic_and_python_user_functions_agree(state):
    symbolic = _connector_load("symbolic", *state)
    python = _connector_load("python", *state)
    # same double-precision operations in C++ and Python: agreement to round-off
    np.testing.assert_allclose(symbolic, python, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("state", STATES)
def test_connector_load_is_minus_the_law(state):
    # Exudyn applies minus the returned load to the tip body (spring convention), so the
    # connector's output is minus the force the plane puts on the sphere
    expected = -np.array(sphere_plane_force(LAW, RADIUS, *state))
    np.testing.assert_allclose(_connector_load("symbolic", *state), expected, rtol=1e-12,
                               atol=1e-15)


def test_penetrating_sphere_is_pushed_up():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    body = mbs.CreateRigidBody(referencePosition=[0, 0, 0.39], inertia=InertiaSphere(1e-9, RADIUS),
                               gravity=[0, 0, 0], show=False, returnDict=True)
    plane = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
    add_tip_contact(mbs, plane, body["bodyNumber"], contact_user_function(mbs, LAW, RADIUS))
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.timeIntegration.endTime = 1e-4
    settings.timeIntegration.numberOfSteps = 10
    mbs.SolveDynamic(settings)
    velocity = mbs.GetNodeOutput(body["nodeNumber"], exu.OutputVariableType.Velocity)
    assert velocity[2] > 0


def test_friction_window_blends_friction_in():
    function = contact_user_function(None, LAW, RADIUS, "python", friction_window=(1.0, 1.2))
    state = dict(displacement=[0, 0, 0.38], rotation=[0, 0, 0], velocity=[3.0, 0, 0],
                 angularVelocity=[0, 0, 0], stiffness=0, damping=0, rotJ0=0, rotJ1=0, offset=0)
    before, during, after = (function(None, t, 0, **state) for t in (0.5, 1.1, 2.0))
    assert before[0] == 0.0 and before[2] == after[2] != 0.0
    assert after[0] > during[0] > 0.0  # connector load is minus the friction force (+x)
