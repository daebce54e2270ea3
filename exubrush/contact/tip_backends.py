"""The tip's contact with the surface, one back end per value of ``contact.backend``: the
paper's law as an Exudyn symbolic user function, as a plain Python one, compiled with its
own Jacobian (exubrush.contact.surface_kernel), or Exudyn's built-in contact.

Each back end says where it applies beside how it is built, which sensor records its
force, and which step hook its friction needs; the scene (exubrush.run.scene) asks
:func:`tip_backend` for a tip's back end and no longer tests the backend's name. A new back
end is one class here, one entry in :data:`BACKENDS` and its name in
exubrush.parameters.choices.CONTACT_BACKENDS.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from exubrush.contact.exudyn_contact import (
    add_builtin_tip_contact,
    add_compiled_tip_contact,
    add_tip_contact,
    builtin_friction_blend,
    contact_user_function,
    initial_offset,
    lagged_drop_hook,
    stick_slip_hook,
)
from exubrush.contact.laws import builtin_contact_parameters, drop_can_lag
from exubrush.models.assembly import rigid_marker
from exubrush.models.geometry import BristleGeometry
from exubrush.models.stiffness import buckling_load
from exubrush.parameters.choices import (
    EXUDYN_BUILTIN,
    PAPER_COMPILED,
    PAPER_PYTHON,
    PAPER_SYMBOLIC,
    STICK_SLIP,
)
from exubrush.parameters.surface_kinds import MESH, PLANE, SURFACE_KIND, SurfaceKind

# where a mesh's contact frame starts: far below, until the first step puts it on the
# tangent plane [mm]
PARKED_FRAME = (0.0, 0.0, -1e3)


class TipSite(NamedTuple):
    """Where a tip contact is made: the system, its ground, the marker of the surface frame
    (exubrush.contact.exudyn_contact.surface_marker), the tip's body and node (the
    sphere's centre) and its bristle."""

    mbs: Any
    ground: int
    surface_marker: int
    tip_body: int
    tip_node: int
    bristle: BristleGeometry


class CompiledLaw(NamedTuple):
    """The compiled law of a tip contact (exubrush.contact.exudyn_contact.
    add_compiled_tip_contact)."""

    item: int  # its ObjectGenericODE2
    drops: np.ndarray  # the drop ratios that object reads
    functions: tuple  # its user functions, kept alive with it


class TipContact(NamedTuple):
    """A tip's contact as a back end made it."""

    connector: int  # the contact's Exudyn object (a connector, or the built-in contact)
    node: int  # the tip node
    radius: float  # the tip sphere's radius [mm]
    frame_marker: int | None  # the marker of a frame moved onto a mesh's tangent plane
    lagged: bool  # it reads a lagged friction drop (lagged_drop_hook)
    compiled: CompiledLaw | None  # the compiled law that carries it, where one does


def law_surface(case):
    """The surface the tip law is written for: None for the plane law, which a plane and a
    mesh (in a frame on its tangent plane, moved before every step) both use, else the
    case's analytic surface (exubrush.world.surfaces.features)."""
    return None if SURFACE_KIND[case.surface.kind].plane_law else case.surface


def _sensor(item, output, body: bool = False):
    """A sensor item recording ``output`` of the object ``item`` (a body's: ``body``)."""
    if body:
        return eii.SensorBody(bodyNumber=item, storeInternal=True, writeToFile=False,
                              outputVariableType=output)
    return eii.SensorObject(objectNumber=item, storeInternal=True, writeToFile=False,
                            outputVariableType=output)


class UserFunctionContact:
    """The paper's law as the user function of a connector (exubrush.contact.exudyn_contact.
    contact_user_function): recorded as a symbolic (C++) expression, or plain Python.
    Applies everywhere; on a mesh in a frame moved onto its tangent plane. Its sensor
    records the connector's ForceLocal (surface frame, minus the force on the tip)."""

    lags = True  # the law's friction falls with slip: its drop can be taken a step behind
    otherwise = None  # applies everywhere

    def __init__(self, name: str):
        self.name = name

    def applies(self, kind: SurfaceKind, site: TipSite) -> bool:
        """Every surface kind, every tip."""
        return True

    def add(self, site: TipSite, case, window, laws: dict) -> TipContact:
        """Connect the tip to the surface through the law's user function, one per tip
        radius (cached in ``laws``); ``window``: the friction's blend window [s] or None."""
        marker, frame = site.surface_marker, None
        if case.surface.kind == MESH:
            marker = frame = rigid_marker(site.mbs, site.ground, list(PARKED_FRAME))
        radius = site.bristle.tip_radius
        lagged = lags_friction_drop(case)
        if radius not in laws:
            laws[radius] = contact_user_function(site.mbs, case.contact, radius, window,
                                                 law_surface(case), lagged)
        connector = add_tip_contact(site.mbs, marker, site.tip_body, laws[radius],
                                    initial_offset(case.contact, lagged))
        return TipContact(connector, site.tip_node, radius, frame, lagged, None)

    def force_sensor(self, contact: TipContact):
        """The connector's ForceLocal."""
        return _sensor(contact.connector, exu.OutputVariableType.ForceLocal)

    def friction_hook(self, contacts: list[TipContact], case, window):
        """The hook that commits the stick/slip law's states before a step
        (exubrush.contact.exudyn_contact.stick_slip_hook), or else sets the lagged contacts'
        drop ratios (lagged_drop_hook); None where none lags."""
        if case.contact.friction_model == STICK_SLIP:
            return stick_slip_hook([(c.connector, c.radius) for c in contacts], case.contact)
        lagged = [(c.connector, c.radius) for c in contacts if c.lagged]
        if not lagged:
            return None
        drops = {c.connector: c.compiled.drops for c in contacts if c.compiled is not None}
        return lagged_drop_hook(lagged, case.contact, law_surface(case), drops)


class CompiledContact(UserFunctionContact):
    """The paper's law compiled with its own Jacobian on the tip node
    (exubrush.contact.surface_kernel), its symbolic connector switched off and kept for its
    outputs. Applies over a curved analytic surface to a tip with Euler parameters (DFM's);
    elsewhere the symbolic law stands in. Its sensor records the object's Force."""

    otherwise = PAPER_SYMBOLIC

    def applies(self, kind: SurfaceKind, site: TipSite) -> bool:
        """A compiled kind (SurfaceKind.compiled) and a tip node with Euler parameters."""
        return kind.compiled and site.mbs.GetNode(site.tip_node)["nodeType"] == "RigidBodyEP"

    def add(self, site: TipSite, case, window, laws: dict) -> TipContact:
        """The symbolic connector (for its outputs), switched off, and the compiled law on
        the tip node."""
        contact = super().add(site, case, window, laws)
        item, drops, functions = add_compiled_tip_contact(
            site.mbs, contact.connector, site.tip_node, case.surface, case.contact,
            contact.radius, window, contact.lagged)
        return contact._replace(compiled=CompiledLaw(item, drops, functions))

    def force_sensor(self, contact: TipContact):
        """The compiled object's Force (an object, not a connector)."""
        return _sensor(contact.compiled.item, exu.OutputVariableType.Force, body=True)


class BuiltinContact:
    """Exudyn's built-in sphere-triangle contact with the law's nearest parameters
    (exubrush.contact.laws.builtin_contact_parameters). Applies to a plane only (the case
    refuses others: exubrush.parameters.case). Its sensor records the contact's Force (on
    the tip, head frame)."""

    name = EXUDYN_BUILTIN
    lags = False  # no Stribeck law to lag
    otherwise = None

    def applies(self, kind: SurfaceKind, site: TipSite) -> bool:
        """The plane."""
        return kind.name == PLANE

    def add(self, site: TipSite, case, window, laws: dict) -> TipContact:
        """The built-in contact between the tip sphere and the plane; friction from the
        start, or blended in over ``window`` [s] by :meth:`friction_hook`'s hook."""
        bristle = site.bristle
        parameters = builtin_contact_parameters(
            case.contact,
            buckling_load(bristle.section, bristle.material.youngs_modulus, bristle.length),
        )
        if window is not None:
            parameters["dynamicFriction"] = 0.0  # blended in by a step hook
        connector = add_builtin_tip_contact(site.mbs, site.surface_marker, site.tip_body,
                                            bristle.tip_radius, parameters)
        return TipContact(connector, site.tip_node, bristle.tip_radius, None, False, None)

    def force_sensor(self, contact: TipContact):
        """The contact's Force."""
        return _sensor(contact.connector, exu.OutputVariableType.Force)

    def friction_hook(self, contacts: list[TipContact], case, window):
        """The hook that blends μ in over the friction window, None without one."""
        if window is None or not contacts:
            return None
        return builtin_friction_blend([c.connector for c in contacts],
                                      case.contact.dynamic_friction, window)


BACKENDS = {backend.name: backend for backend in (
    UserFunctionContact(PAPER_SYMBOLIC),
    UserFunctionContact(PAPER_PYTHON),
    CompiledContact(PAPER_COMPILED),
    BuiltinContact(),
)}  # contact.backend -> its back end


def tip_backend(case, site: TipSite):
    """The back end of the tip at ``site``: the case's ``contact.backend`` where it applies,
    else the one it names in its stead."""
    chosen = BACKENDS[case.contact.backend]
    if chosen.applies(SURFACE_KIND[case.surface.kind], site):
        return chosen
    if chosen.otherwise is None:
        raise ValueError(f"contact.backend {chosen.name!r} does not apply to surface.kind "
                         f"{case.surface.kind!r}")
    return BACKENDS[chosen.otherwise]


def lags_friction_drop(case) -> bool:
    """Whether the tip contacts take the friction's drop one step behind
    (``solver.friction_drop = "lagged"``): with a back end whose law lags (the paper's law),
    and only where the law's friction falls (μ_s > μ_d)."""
    return (case.solver.friction_drop == "lagged" and BACKENDS[case.contact.backend].lags
            and drop_can_lag(case.contact) and case.contact.friction_model != STICK_SLIP)
