"""Tip-sphere contact with the surface as an Exudyn connector with a user function.

Each tip gets an ``ObjectConnectorRigidBodySpringDamper`` from a ground marker in the
surface frame (at its top, turned by ``surface.yaw``; :func:`surface_marker`) to the tip body's
node at the sphere centre, in the non-intrinsic formulation: Exudyn then hands the user
function the centre's position, velocity and angular velocity in the surface frame, applies
the returned force at the sphere centre and the returned torque to the tip body, both with
a minus sign (a spring's restoring convention, checked in
tests/integration/test_contact_connector.py). The law is
:func:`exubrush.contact.laws.sphere_plane_force` on a plane and
:func:`exubrush.contact.laws.sphere_surface_force` over the surface's features
(exubrush.world.surfaces) on any other surface, recorded as an Exudyn symbolic (C++) user
function by default (``contact.backend = "paper-symbolic"``), or called as plain Python
(``"paper-python"``). With ``"paper-compiled"`` the connector is made as for the symbolic
law and switched off, kept for its outputs (the tip's state in the surface frame), and
:func:`add_compiled_tip_contact` computes the contact on a curved analytic surface.

The approximate fast path (``"exudyn-builtin"``) uses Exudyn's own ``ObjectContactSphereTriangle``
against one triangle covering the plane, with the law's nearest parameters
(:func:`exubrush.contact.laws.builtin_contact_parameters`).
"""

from __future__ import annotations

from types import SimpleNamespace

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
from exudyn.advancedUtilities import CreateSymbolicUserFunction

from exubrush.contact.laws import (
    cubic_step,
    drop_ratios,
    sphere_plane_force,
    sphere_surface_force,
)
from exubrush.contact.stick_slip import STATE_SIZE, committed_state, stick_slip_plane_force
from exubrush.models.assembly import rigid_marker
from exubrush.parameters.case import ContactLaw, Surface
from exubrush.parameters.choices import STICK_SLIP
from exubrush.parameters.surface_kinds import PLANE
from exubrush.util.float_math import FLOAT_MATH
from exubrush.world.surfaces import features, orientation

# half the side of the square of the plane z = 0 that the built-in contact's triangle
# covers [mm]: far beyond any head and stroke
BUILTIN_PLANE_HALF_SIZE = 1e4

def _symbolic_if(condition, if_true, if_false):
    """Exudyn's symbolic IfThenElse, also for plain numbers as branches (it takes only
    expressions)."""
    real = exu.symbolic.Real
    return exu.symbolic.IfThenElse(
        condition, *(b if isinstance(b, real) else real(float(b)) for b in (if_true, if_false)))


SYMBOLIC_MATH = SimpleNamespace(
    **{name: getattr(exu.symbolic, name) for name in ("sqrt", "abs", "sign", "min", "max",
                                                      "floor")},
    # x**2 evaluates x once in Exudyn's expression tree, x * x twice
    square=lambda x: x**2,
    IfThenElse=_symbolic_if,
)
"""The math back end (exubrush.util.float_math) that records Exudyn symbolic expressions."""

CONNECTOR_TYPE = "ObjectConnectorRigidBodySpringDamper"
# the connector's offset vector, which carries the lagged drop ratios (one per feature)
OFFSET_SIZE = 6
USER_FUNCTION_NAME = "springForceTorqueUserFunction"


def contact_user_function(
    mbs, law: ContactLaw, radius: float, friction_window=None, surface: Surface | None = None,
    lagged: bool = False,
):
    """Return an Exudyn spring-force-torque user function for one sphere radius and
    ``surface`` (default: the plane).

    ``law.backend`` chooses how: ``"paper-symbolic"`` (and ``"paper-compiled"``, whose
    connector is switched off and kept for its outputs) records the law into a C++
    expression tree (keep the returned object alive as long as ``mbs`` runs);
    ``"paper-python"`` returns the plain Python function.

    Parameters
    ----------
    friction_window : (float, float), optional
        Times [s] between which friction is blended in (cubic step from 0 to 1); ``None``
        means friction acts from the start.
    lagged : bool
        Read the friction's drop ratio of each surface feature from the connector's
        ``offset`` (set before every step by :func:`lagged_drop_hook`) instead of
        evaluating it at the current slip.

    With ``law.friction_model = "stick-slip"`` the law is
    exubrush.contact.stick_slip.stick_slip_plane_force, its state the connector's offset
    (set before every step by :func:`stick_slip_hook`).
    """
    backend = law.backend
    if backend not in ("paper-symbolic", "paper-python", "paper-compiled"):
        raise ValueError(f"contact.backend {backend!r} has no user function; use "
                         "paper-symbolic, paper-python or paper-compiled")
    math_backend = FLOAT_MATH if backend == "paper-python" else SYMBOLIC_MATH

    def contact_force(mbs, t, itemNumber, displacement, rotation, velocity, angularVelocity,
                      stiffness, damping, rotJ0, rotJ1, offset):
        scale = 1.0
        if friction_window is not None:
            scale = cubic_step(t, friction_window[0], 0.0, friction_window[1], 1.0, math_backend)
        if law.friction_model == STICK_SLIP:  # the plane only (exubrush.parameters.case)
            load = stick_slip_plane_force(law, radius, displacement, rotation, velocity,
                                          angularVelocity,
                                          [offset[k] for k in range(STATE_SIZE)],
                                          math_backend, scale)
        elif surface is None or surface.kind == PLANE:
            load = sphere_plane_force(law, radius, displacement, velocity, angularVelocity,
                                      math_backend, scale, offset[0] if lagged else None)
        else:
            found = features(surface, displacement, radius, math_backend)
            drops = [offset[k] for k in range(len(found))] if lagged else None
            load = sphere_surface_force(law, radius, found, velocity, angularVelocity,
                                        math_backend, scale, drops)
        return [-component for component in load]

    if backend == "paper-python":
        return contact_force
    return CreateSymbolicUserFunction(
        mbs, contact_force, USER_FUNCTION_NAME, itemTypeName=CONNECTOR_TYPE
    )


def surface_marker(mbs, ground, surface: Surface | None):
    """A marker on ``ground`` in the surface frame (the plane's: the head frame); a
    connector from it sees the tip in that frame."""
    if surface is None:
        return rigid_marker(mbs, ground, [0.0, 0.0, 0.0])
    return rigid_marker(mbs, ground, [surface.x, surface.y, 0.0], orientation(surface))


def add_tip_contact(mbs, surface_marker_number, tip_body, user_function,
                    offset=(0.0,) * OFFSET_SIZE):
    """Connect the tip body's node (sphere centre) to the surface through ``user_function``;
    the connector's frame is that of the surface marker. ``offset``: the 6 numbers the user
    function reads (:func:`initial_offset`; zeros where it reads none)."""
    tip_marker = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=tip_body, localPosition=[0, 0, 0]))
    return mbs.AddObject(
        eii.ObjectConnectorRigidBodySpringDamper(
            markerNumbers=[surface_marker_number, tip_marker],
            useIntrinsicFormulation=False,
            springForceTorqueUserFunction=user_function,
            offset=list(offset),
            visualization=eii.VObjectConnectorRigidBodySpringDamper(show=False),
        )
    )


def initial_offset(law: ContactLaw, lagged: bool) -> list[float]:
    """The connector's offset before the first step: the stick/slip law's state (a drop
    ratio of 1; the rest is set by :func:`stick_slip_hook` before the first step); the
    lagged drop ratios at 1 (no drop: the tip at rest); else zeros, unread."""
    if law.friction_model == STICK_SLIP:
        return [0.0] * (STATE_SIZE - 1) + [1.0]
    return [1.0] * OFFSET_SIZE if lagged else [0.0] * OFFSET_SIZE


def stick_slip_hook(contacts: list, law: ContactLaw):
    """A step hook ``(mbs, t)`` that commits each stick/slip contact's state
    (exubrush.contact.stick_slip.committed_state) from the state the step starts at, and
    writes it into the connector's offset where it changed.

    ``contacts``: (connector, tip radius [mm]) of tip contacts whose user function is the
    stick/slip law. Exudyn calls the pre-step function before every step attempt, after a
    failed attempt with the state reset to the step's start, where committing again
    changes nothing. The connector's local displacement, rotation, velocity and angular
    velocity are its user function's arguments
    (tests/integration/test_stick_slip_contact.py)."""
    outputs = (exu.OutputVariableType.DisplacementLocal, exu.OutputVariableType.Rotation,
               exu.OutputVariableType.VelocityLocal,
               exu.OutputVariableType.AngularVelocityLocal)
    states = [initial_offset(law, False) for _ in contacts]

    def commit(mbs, t):
        for k, (contact, radius) in enumerate(contacts):
            tip = [mbs.GetObjectOutput(contact, output) for output in outputs]
            state = committed_state(law, radius, *tip, states[k])
            if state != states[k]:
                states[k] = state
                mbs.SetObjectParameter(contact, "offset", state)

    return commit


def add_compiled_tip_contact(mbs, connector, tip_node, surface: Surface, law: ContactLaw,
                             radius: float, friction_window=None, lagged: bool = False):
    """Let an ``ObjectGenericODE2`` on the tip node (Euler parameters) carry the contact
    with the compiled law and its own Jacobian (exubrush.contact.surface_kernel), and
    switch ``connector`` (the symbolic law's, made by :func:`add_tip_contact`) off: it stays
    for its outputs (the tip's state in the surface frame, which the lagged drop reads and
    Exudyn still evaluates); the contact force is the object's (its Force output, minus
    the generalized force).

    Returns (the object, the drop ratios it reads: 1 to start with where ``lagged``, which
    :func:`lagged_drop_hook` keeps up to date; else −1, the implicit law; the user
    functions to keep alive)."""
    from exubrush.contact.surface_kernel import (
        MAX_FEATURES,
        law_numbers,
        node_jacobian,
        node_load,
        surface_numbers,
    )

    kind, params = surface_numbers(surface)
    numbers = law_numbers(law)
    turn = np.ascontiguousarray(orientation(surface))
    origin = np.array([surface.x, surface.y, 0.0])
    reference = np.array(mbs.GetNode(tip_node)["referenceCoordinates"], float)
    drops = np.full(MAX_FEATURES, 1.0 if lagged else -1.0)
    out, local, triplets = np.zeros(7), np.zeros(6), np.zeros((49, 3))

    def scale(t):
        if friction_window is None:
            return 1.0
        return cubic_step(t, friction_window[0], 0.0, friction_window[1], 1.0)

    def force(mbs, t, itemNumber, q, q_t):
        node_load(np.asarray(q), np.asarray(q_t), reference, turn, origin, kind, params,
                  numbers, radius, scale(t), drops, out, local)
        return out

    def jacobian(mbs, t, itemNumber, q, q_t, f_position, f_velocity):
        node_jacobian(np.asarray(q), np.asarray(q_t), reference, turn, origin, kind, params,
                      numbers, radius, scale(t), drops, f_position, f_velocity, triplets)
        matrix = exu.MatrixContainer()
        matrix.SetWithSparseMatrix(triplets, 7, 7)
        return matrix

    mbs.SetObjectParameter(connector, "activeConnector", False)
    empty = exu.MatrixContainer()
    empty.SetWithSparseMatrix(np.zeros((0, 3)), 7, 7)
    item = mbs.AddObject(eii.ObjectGenericODE2(
        nodeNumbers=[tip_node], massMatrix=empty, forceVector=[0.0] * 7,
        forceUserFunction=force, jacobianUserFunction=jacobian,
        visualization=eii.VObjectGenericODE2(show=False)))
    return item, drops, (force, jacobian)


def lagged_drop_hook(contacts: list, law: ContactLaw, surface: Surface | None,
                     compiled: dict | None = None):
    """A step hook ``(mbs, t)`` that puts into each tip contact's offset the drop ratios
    (exubrush.contact.laws.drop_ratios) at the state the step starts from.

    ``contacts``: (connector, tip radius [mm]) of tip contacts made with ``lagged=True``;
    ``surface``: the law's surface (None: the plane law, also in a mesh's tangent frame,
    so a mesh's frame must be placed before this hook runs). Exudyn calls the pre-step
    function before every step attempt, after a failed attempt with the state reset to the
    step's start; the connector's local displacement, velocity and angular velocity are
    the user function's arguments (tests/integration/test_contact_connector.py). The offset is
    only written when a ratio changes (it stays at 1 or μ_d/μ_s through a stick or a
    slide). ``compiled``: connector -> the drop-ratio array a compiled contact reads
    (:func:`add_compiled_tip_contact`), written instead of the offset.
    """
    compiled = compiled or {}
    velocity_output = exu.OutputVariableType.VelocityLocal
    omega_output = exu.OutputVariableType.AngularVelocityLocal
    # the plane's slip does not depend on where the sphere is (an output call saved, ~3 µs)
    centre_output = None if surface is None else exu.OutputVariableType.DisplacementLocal
    last = [None] * len(contacts)

    def set_drops(mbs, t):
        for k, (contact, radius) in enumerate(contacts):
            centre = None if centre_output is None else mbs.GetObjectOutput(contact,
                                                                            centre_output)
            ratios = drop_ratios(law, radius, surface, centre,
                                 mbs.GetObjectOutput(contact, velocity_output),
                                 mbs.GetObjectOutput(contact, omega_output))
            if ratios != last[k]:
                last[k] = ratios
                if contact in compiled:  # its connector is switched off: nothing reads it
                    compiled[contact][:len(ratios)] = ratios
                else:
                    padded = ratios + [1.0] * (OFFSET_SIZE - len(ratios))
                    mbs.SetObjectParameter(contact, "offset", padded)

    return set_drops


def add_builtin_tip_contact(mbs, plane_marker, tip_body, radius: float, parameters: dict):
    """Exudyn's built-in sphere-triangle contact between the tip sphere and the plane z = 0.

    ``parameters``: keyword arguments of ``ObjectContactSphereTriangle`` (stiffness, damping,
    friction; from :func:`exubrush.contact.laws.builtin_contact_parameters`). The triangle,
    counter-clockwise seen from +z (normal +z), covers the square |x|, |y| <= 1e4 mm; its
    edges are never reached, so edge contact is off. The contact's state (gap, slip) lives
    in a data node that Exudyn updates between Newton solves; it starts "apart".
    """
    tip_marker = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=tip_body, localPosition=[0, 0, 0]))
    state = mbs.AddNode(eii.NodeGenericData(numberOfDataCoordinates=4,
                                            initialCoordinates=[1.0, 0.0, 0.0, 0.0]))
    size = BUILTIN_PLANE_HALF_SIZE
    return mbs.AddObject(
        eii.ObjectContactSphereTriangle(
            markerNumbers=[tip_marker, plane_marker],
            nodeNumber=state,
            sphereRadius=radius,
            trianglePoints=exu.Vector3DList([[-size, -size, 0.0], [3 * size, -size, 0.0],
                                             [-size, 3 * size, 0.0]]),
            includeEdges=0,
            **parameters,
            visualization=eii.VObjectContactSphereTriangle(show=False),
        )
    )


def builtin_friction_blend(contacts: list, friction: float, window: tuple[float, float]):
    """A per-step hook ``(mbs, t)`` that blends the built-in contacts' μ from 0 to ``friction``
    over ``window`` [s] (the cubic step of the user-function law's friction window)."""

    blended = [False]

    def set_friction(mbs, t):
        if blended[0]:
            return
        scale = cubic_step(t, window[0], 0.0, window[1], 1.0)
        for contact in contacts:
            mbs.SetObjectParameter(contact, "dynamicFriction", friction * scale)
        blended[0] = scale >= 1.0

    return set_friction
