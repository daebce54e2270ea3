"""Tip-sphere contact with the plane Z = 0 as an Exudyn connector with a user function.

Each tip gets an ``ObjectConnectorRigidBodySpringDamper`` from a ground marker on the plane
(frame = head/world frame, normal +Z) to the tip body's node at the sphere centre, in the
non-intrinsic formulation: Exudyn then hands the user function the centre's position,
velocity and angular velocity in the plane frame, applies the returned force at the sphere
centre and the returned torque to the tip body, both with a minus sign (a spring's
restoring convention, checked in tests/integration/test_contact_connector.py). The law is
:func:`exubrush.contact.laws.sphere_plane_force`, recorded as an Exudyn symbolic (C++) user
function by default, or called as plain Python.
"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
from exudyn.advancedUtilities import CreateSymbolicUserFunction

from exubrush.contact.laws import FLOAT_MATH, ContactLaw, cubic_step, sphere_plane_force

CONNECTOR_TYPE = "ObjectConnectorRigidBodySpringDamper"
USER_FUNCTION_NAME = "springForceTorqueUserFunction"


def contact_user_function(
    mbs, law: ContactLaw, radius: float, backend: str = "symbolic", friction_window=None
):
    """Return an Exudyn spring-force-torque user function for one sphere radius.

    Parameters
    ----------
    backend : {"symbolic", "python"}
        ``"symbolic"`` records the law into a C++ expression tree (keep the returned object
        alive as long as ``mbs`` runs); ``"python"`` returns the plain Python function.
    friction_window : (float, float), optional
        Times [s] between which friction is blended in (cubic step from 0 to 1); ``None``
        means friction acts from the start.
    """
    math_backend = exu.symbolic if backend == "symbolic" else FLOAT_MATH

    def contact_force(mbs, t, itemNumber, displacement, rotation, velocity, angularVelocity,
                      stiffness, damping, rotJ0, rotJ1, offset):
        scale = 1.0
        if friction_window is not None:
            scale = cubic_step(t, friction_window[0], 0.0, friction_window[1], 1.0, math_backend)
        load = sphere_plane_force(law, radius, displacement, velocity, angularVelocity,
                                  math_backend, scale)
        return [-component for component in load]

    if backend == "python":
        return contact_force
    if backend != "symbolic":
        raise ValueError(f"unknown user-function back end {backend!r}; use symbolic or python")
    return CreateSymbolicUserFunction(
        mbs, contact_force, USER_FUNCTION_NAME, itemTypeName=CONNECTOR_TYPE
    )


def add_tip_contact(mbs, plane_marker, tip_body, user_function):
    """Connect the tip body's node (sphere centre) to the plane through ``user_function``."""
    tip_marker = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=tip_body, localPosition=[0, 0, 0]))
    return mbs.AddObject(
        eii.ObjectConnectorRigidBodySpringDamper(
            markerNumbers=[plane_marker, tip_marker],
            useIntrinsicFormulation=False,
            springForceTorqueUserFunction=user_function,
            visualization=eii.VObjectConnectorRigidBodySpringDamper(show=False),
        )
    )
