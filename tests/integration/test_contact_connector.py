"""The contact law inside Exudyn: back ends agree and the sign convention holds; Exudyn's
built-in contact with the fitted parameters is the law where the fit says it is."""

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest
from exudyn.rigidBodyUtilities import InertiaSphere, RigidBodyInertia

from exubrush.contact.exudyn_contact import (
    add_builtin_tip_contact,
    add_tip_contact,
    builtin_friction_blend,
    contact_user_function,
    initial_offset,
    lagged_drop_hook,
    surface_marker,
)
from exubrush.contact.laws import (
    builtin_contact_parameters,
    drop_ratios,
    friction_drop,
    sphere_plane_force,
    sphere_surface_force,
)
from exubrush.parameters.case import ContactLaw, Surface
from exubrush.world.surfaces import features, orientation, to_surface_frame

LAW = ContactLaw()
RADIUS = 0.4
STATES = [  # centre [mm], velocity [mm/s], angular velocity [rad/s]
    ([0.1, 0.2, 0.35], [1.0, -0.5, -2.0], [0.3, 0.1, 0.0]),
    ([0.0, 0.0, 0.39], [0.1, 0.05, 0.3], [0.0, 0.0, 0.0]),
    ([0.0, 0.0, 0.30], [5.0, 0.0, 0.0], [0.0, 2.0, 0.0]),
    ([0.0, 0.0, 0.50], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]),
]


def _sphere_above_plane(centre, velocity=None, omega=None, inertia=None):
    """A free rigid sphere and a marker on the plane z = 0: (system container, system,
    the body's item dict, plane marker); keep the container alive while the system runs.
    At rest and a 1e-9 t tip sphere unless told otherwise."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    body = mbs.CreateRigidBody(referencePosition=centre, initialVelocity=velocity or [0, 0, 0],
                               initialAngularVelocity=omega or [0, 0, 0],
                               inertia=inertia or InertiaSphere(1e-9, RADIUS),
                               gravity=[0, 0, 0], show=False, returnDict=True)
    plane = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
    return SC, mbs, body, plane


def _solve(mbs, end_time, steps):
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.timeIntegration.endTime = end_time
    settings.timeIntegration.numberOfSteps = steps
    mbs.SolveDynamic(settings)


def _connector_load(backend, centre, velocity, omega):
    SC, mbs, body, plane = _sphere_above_plane(centre, velocity, omega)
    function = contact_user_function(mbs, LAW.replace(backend=backend), RADIUS)
    connector = add_tip_contact(mbs, plane, body["bodyNumber"], function)
    mbs.Assemble()
    force = mbs.GetObjectOutput(connector, exu.OutputVariableType.ForceLocal)
    torque = mbs.GetObjectOutput(connector, exu.OutputVariableType.TorqueLocal)
    return np.concatenate([force, torque])


@pytest.mark.parametrize("state", STATES)
def test_symbolic_and_python_user_functions_agree(state):
    symbolic = _connector_load("paper-symbolic", *state)
    python = _connector_load("paper-python", *state)
    # same double-precision operations in C++ and Python: agreement to round-off
    np.testing.assert_allclose(symbolic, python, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("state", STATES)
def test_connector_load_is_minus_the_law(state):
    # Exudyn applies minus the returned load to the tip body (spring convention), so the
    # connector's output is minus the force the plane puts on the sphere
    expected = -np.array(sphere_plane_force(LAW, RADIUS, *state))
    np.testing.assert_allclose(_connector_load("paper-symbolic", *state), expected, rtol=1e-12,
                               atol=1e-15)


def test_penetrating_sphere_is_pushed_up():
    SC, mbs, body, plane = _sphere_above_plane([0, 0, 0.39])
    add_tip_contact(mbs, plane, body["bodyNumber"], contact_user_function(mbs, LAW, RADIUS))
    _solve(mbs, end_time=1e-4, steps=10)
    velocity = mbs.GetNodeOutput(body["nodeNumber"], exu.OutputVariableType.Velocity)
    assert velocity[2] > 0


def test_friction_window_blends_friction_in():
    function = contact_user_function(None, LAW.replace(backend="paper-python"), RADIUS,
                                     friction_window=(1.0, 1.2))
    state = dict(displacement=[0, 0, 0.38], rotation=[0, 0, 0], velocity=[3.0, 0, 0],
                 angularVelocity=[0, 0, 0], stiffness=0, damping=0, rotJ0=0, rotJ1=0, offset=0)
    before, during, after = (function(None, t, 0, **state) for t in (0.5, 1.1, 2.0))
    assert before[0] == 0.0 and before[2] == after[2] != 0.0
    assert after[0] > during[0] > 0.0  # connector load is minus the friction force (+x)


def _builtin_load(centre, velocity, omega):
    """Force and moment [N, N·mm] of the built-in contact on a free sphere of mass 1 t and
    inertia 1 t·mm², read as its accelerations after one 1 ns step (the state barely moves;
    the contact's gap and slip state are settled by Exudyn's discontinuous iteration)."""
    SC, mbs, body, plane = _sphere_above_plane(centre, velocity, omega,
                                               RigidBodyInertia(1.0, np.eye(3)))
    add_builtin_tip_contact(mbs, plane, body["bodyNumber"], RADIUS,
                            builtin_contact_parameters(LAW, reference_force=0.05))
    _solve(mbs, end_time=1e-9, steps=1)
    node = body["nodeNumber"]
    return np.concatenate([
        mbs.GetNodeOutput(node, exu.OutputVariableType.Acceleration),
        mbs.GetNodeOutput(node, exu.OutputVariableType.AngularAcceleration),
    ])


def test_builtin_contact_normal_force_is_the_laws_elastic_force():
    load = _builtin_load([0.0, 0.0, 0.39], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    expected = sphere_plane_force(LAW, RADIUS, [0, 0, 0.39], [0, 0, 0], [0, 0, 0])
    # at rest no damping: the same k δ^m1, to the solver's 1 ns of motion
    np.testing.assert_allclose(load, expected, rtol=1e-6, atol=1e-12)


def test_builtin_contact_friction_in_full_slip_is_the_dynamic_coefficient():
    load = _builtin_load([0.0, 0.0, 0.39], [5.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    law = sphere_plane_force(LAW, RADIUS, [0, 0, 0.39], [5.0, 0, 0], [0, 0, 0])
    assert load[2] == pytest.approx(law[2], rel=1e-6)
    assert load[0] == pytest.approx(-LAW.dynamic_friction * law[2], rel=1e-6)
    # Exudyn's friction moment arm is the centre's height above the plane (0.39 mm), the
    # law's is the radius (0.4 mm): 2.5 % apart, within the approximation
    assert load[4] == pytest.approx(law[4], rel=0.03)


def test_builtin_contact_friction_at_small_slip_follows_the_laws_slope():
    # slip 0.3 mm/s, a quarter of v_s: both are ~linear in the slip with the same slope at
    # zero; the law's cubic step has bent 2 % below its tangent there
    load = _builtin_load([0.0, 0.0, 0.39], [0.3, 0.0, 0.0], [0.0, 0.0, 0.0])
    law = sphere_plane_force(LAW, RADIUS, [0, 0, 0.39], [0.3, 0, 0], [0, 0, 0])
    assert load[0] == pytest.approx(law[0], rel=0.03)


def test_builtin_friction_blend_raises_the_coefficient_over_the_window():
    SC, mbs, body, plane = _sphere_above_plane([0, 0, 1.0])
    contact = add_builtin_tip_contact(mbs, plane, body["bodyNumber"], RADIUS,
                                      {"dynamicFriction": 0.0, "contactStiffness": 1.0})
    blend = builtin_friction_blend([contact], 0.76, (1.0, 1.2))
    seen = []
    for t in (0.5, 1.1, 1.2, 0.5):  # once at full friction, the hook leaves μ alone
        blend(mbs, t)
        seen.append(mbs.GetObjectParameter(contact, "dynamicFriction"))
    assert seen[0] == 0.0 and 0.0 < seen[1] < 0.76
    assert seen[2] == pytest.approx(0.76) and seen[3] == seen[2]


PLACED = [  # (surface, centre of a sphere touching it [mm], head frame)
    (Surface(kind="cylinder", radius=4.0, x=0.5, y=-1.0, yaw=np.radians(30.0)),
     [0.5 + 1.5 * np.cos(np.radians(30.0)), -1.0 + 1.5 * np.sin(np.radians(30.0)),
      np.sqrt(4.37**2 - 1.5**2) - 4.0]),
    (Surface(kind="sphere", radius=3.0, x=-0.2), [0.8, 0.9, np.sqrt(3.38**2 - 1.81) - 3.0]),
    # on the rounding of a tooth's edge, and in a gap narrower than the sphere (two walls)
    (Surface(kind="tooth-row", yaw=np.radians(90.0)), [0.1, 3.4, -0.15]),
    (Surface(kind="tooth-row", gap_width=0.7, yaw=np.radians(-45.0)),
     [3.82 * np.sqrt(0.5), -3.82 * np.sqrt(0.5), -1.0]),
]


def _applied_load(surface, backend, centre, velocity, omega, lagged=False):
    """Force and moment [N, N·mm] that the contact applies to a free sphere of mass 1 t and
    inertia 1 t·mm², head frame, read as its accelerations after one 1 ns step; with
    ``lagged``, also the drop ratios the step hook put into the connector's offset."""
    SC, mbs, body, _ = _sphere_above_plane(list(centre), list(velocity), list(omega),
                                           RigidBodyInertia(1.0, np.eye(3)))
    ground = mbs.AddObject(eii.ObjectGround())
    law = LAW.replace(backend=backend)
    law_surface = None if surface.kind == "plane" else surface
    function = contact_user_function(mbs, law, RADIUS, surface=law_surface, lagged=lagged)
    contact = add_tip_contact(mbs, surface_marker(mbs, ground, surface), body["bodyNumber"],
                              function, initial_offset(law, lagged))
    if lagged:
        hook = lagged_drop_hook([(contact, RADIUS)], law, law_surface)
        mbs.SetPreStepUserFunction(lambda mbs, t: hook(mbs, t) or True)
    _solve(mbs, end_time=1e-9, steps=1)
    node = body["nodeNumber"]
    load = np.concatenate([
        mbs.GetNodeOutput(node, exu.OutputVariableType.Acceleration),
        mbs.GetNodeOutput(node, exu.OutputVariableType.AngularAcceleration),
    ])
    return (load, list(mbs.GetObjectParameter(contact, "offset"))) if lagged else load


@pytest.mark.parametrize("backend", ["paper-symbolic", "paper-python"])
@pytest.mark.parametrize("placed", PLACED, ids=["cylinder", "sphere", "tooth-edge", "narrow-gap"])
def test_placed_surface_pushes_as_the_law_in_its_frame(placed, backend):
    surface, centre = placed
    velocity, omega = np.array([1.0, -2.0, -0.3]), np.array([0.2, -0.1, 0.4])
    turn = orientation(surface)
    local = to_surface_frame(surface, centre)
    law = sphere_surface_force(LAW, RADIUS, features(surface, local, RADIUS),
                               (turn.T @ velocity).tolist(), (turn.T @ omega).tolist())
    expected = np.concatenate([turn @ law[:3], turn @ law[3:]])
    assert np.linalg.norm(expected[:3]) > 0.05  # the sphere is pressed in
    # 1 ns of motion at these speeds changes the load by far less than 1e-6 of it
    np.testing.assert_allclose(_applied_load(surface, backend, centre, velocity, omega),
                               expected, rtol=1e-6, atol=1e-9)


def test_a_sphere_pressed_on_a_turned_cylinder_sinks_by_the_laws_depth():
    # statics: only the elastic term balances P, δ = (P/k)^(1/m1) on any curvature; the
    # geometry (placement, turn, normal) decides where the sphere ends (the notebook
    # validation/surfaces.ipynb does the same for every kind and load)
    from exubrush.statics import sphere_pressed_on_surface

    surface = Surface(kind="cylinder", radius=4.0, x=0.3, yaw=np.radians(30.0))
    turn = orientation(surface)
    normal = turn @ [np.sin(0.5), 0.0, np.cos(0.5)]
    anchor = np.array([0.3, 0.0, 0.0]) + turn @ [0.0, 0.0, -4.0] + 4.0 * normal
    centre = sphere_pressed_on_surface(surface, LAW, RADIUS, anchor, normal, 0.1)
    depth = RADIUS - (centre - anchor) @ normal
    # Newton's tolerance leaves ~1e-13 of δ; a wrong normal or placement misses by > 1e-3
    assert depth == pytest.approx((0.1 / LAW.stiffness) ** (1 / LAW.stiffness_exponent),
                                  rel=1e-9)


@pytest.mark.parametrize("backend", ["paper-symbolic", "paper-python"])
@pytest.mark.parametrize("placed", [(Surface(yaw=np.radians(40.0)), [0.3, -0.2, 0.37]),
                                    *PLACED],
                         ids=["plane", "cylinder", "sphere", "tooth-edge", "narrow-gap"])
def test_lagged_drop_reads_the_slip_the_law_sees(placed, backend):
    # the step hook reads the connector's local state: the ratios it sets are those of the
    # state turned into the surface frame by hand, and a step that starts there pushes as
    # the implicit law (the lag is zero at the step's start); slip speeds of 0.8-1.6 mm/s
    # put some features inside the Stribeck band
    surface, centre = placed
    velocity, omega = np.array([0.9, -0.6, -0.3]), np.array([0.2, -0.1, 0.4])
    turn = orientation(surface)
    local = (to_surface_frame(surface, centre), turn.T @ velocity, turn.T @ omega)
    law_surface = None if surface.kind == "plane" else surface
    expected_ratios = drop_ratios(LAW, RADIUS, law_surface, *(v.tolist() for v in local))
    load, offset = _applied_load(surface, backend, centre, velocity, omega, lagged=True)
    np.testing.assert_allclose(offset[:len(expected_ratios)], expected_ratios, rtol=1e-12)
    assert offset[len(expected_ratios):] == [1.0] * (6 - len(expected_ratios))
    if surface.kind == "plane":
        implicit = sphere_plane_force(LAW, RADIUS, *(v.tolist() for v in local))
    else:
        implicit = sphere_surface_force(LAW, RADIUS, features(surface, local[0], RADIUS),
                                        local[1].tolist(), local[2].tolist())
    expected = np.concatenate([turn @ implicit[:3], turn @ implicit[3:]])
    np.testing.assert_allclose(load, expected, rtol=1e-6, atol=1e-9)


def test_a_lagged_contact_uses_the_ratio_it_was_given():
    # the user function takes the drop ratio from the offset, not from the current slip:
    # at full slip (r(5 mm/s) = μ_d/μ_s) a given r = 1 pushes with μ_s
    function = contact_user_function(None, LAW.replace(backend="paper-python"), RADIUS,
                                     lagged=True)
    state = dict(displacement=[0, 0, 0.38], rotation=[0, 0, 0], velocity=[5.0, 0, 0],
                 angularVelocity=[0, 0, 0], stiffness=0, damping=0, rotJ0=0, rotJ1=0)
    held = function(None, 1.0, 0, offset=[1.0] * 6, **state)
    dropped = function(None, 1.0, 0, offset=[friction_drop(LAW, 5.0)] + [1.0] * 5, **state)
    # (the connector's load is minus the law's, normal and friction alike)
    assert held[0] == pytest.approx(-LAW.static_friction * held[2], rel=1e-12)
    assert dropped[0] == pytest.approx(-LAW.dynamic_friction * dropped[2], rel=1e-12)
