"""The surface kinds a case can name (``surface.kind``) and what the layers above ask of
each: the one list of kinds.

Adding a kind starts with an entry here; the modules that then implement it are listed in
docs/architecture.md, "Adding a surface kind". Pure: imports nothing of exubrush.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SurfaceKind:
    """A surface kind and the properties that decide how the layers treat it.

    Attributes
    ----------
    name : str
        The value of ``surface.kind``.
    plane_law : bool
        The tip law is the plane's (exubrush.contact.laws.sphere_plane_force): on the plane
        itself, and on a mesh in a contact frame moved onto its tangent plane before every
        step (exubrush.contact.tip_backends.law_surface); else the law over the kind's
        analytic features (exubrush.world.surfaces.features).
    compiled : bool
        A curved analytic surface, over which contact.backend "paper-compiled" computes
        the tip law compiled (exubrush.contact.surface_kernel) on tips with Euler
        parameters (DFM's); elsewhere that backend is the symbolic law
        (exubrush.contact.tip_backends.CompiledContact.applies).
    larger_steps : bool
        The step may grow in the middle of a stroke, which is steady sliding
        (exubrush.run.step_policy): on a tooth row only while every tip is over a tooth's flat
        top, as tips snap off its edges into the gaps; a mesh (which may be a tooth row)
        keeps ``solver.step_size``.
    """

    name: str
    plane_law: bool
    compiled: bool
    larger_steps: bool


# the kinds' names, which the modules that implement a kind compare with (a misspelt name
# fails at import, a misspelt string never matches)
PLANE, CYLINDER, SPHERE, TOOTH_ROW, MESH = "plane", "cylinder", "sphere", "tooth-row", "mesh"
KINDS = (
    SurfaceKind(PLANE, plane_law=True, compiled=False, larger_steps=True),
    SurfaceKind(CYLINDER, plane_law=False, compiled=True, larger_steps=True),
    SurfaceKind(SPHERE, plane_law=False, compiled=True, larger_steps=True),
    SurfaceKind(TOOTH_ROW, plane_law=False, compiled=True, larger_steps=True),
    SurfaceKind(MESH, plane_law=True, compiled=False, larger_steps=False),
)
SURFACE_KIND = {kind.name: kind for kind in KINDS}  # name -> SurfaceKind
SURFACE_KINDS = tuple(SURFACE_KIND)  # the names, in the order of KINDS
