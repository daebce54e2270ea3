"""The fixed lists a case chooses from, each defined once: the parameters offer them
(exubrush.parameters.case) and the layers that implement them import them from here
(section shapes: exubrush.models.sections; mesh units: exubrush.world.mesh; pose axes:
exubrush.world.pose). The surface kinds have their own registry
(exubrush.parameters.surface_kinds). Pure: imports nothing of exubrush.
"""

from __future__ import annotations

# bristle cross-sections (head.section, a tuft's section; exubrush.models.sections)
SECTION_SHAPES = ("rectangle", "ellipse", "circle")

# units a mesh file can be written in (surface.mesh_unit), and millimetres per unit
# (exubrush.world.mesh.read_mesh)
MESH_UNITS = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "um": 1e-3, "in": 25.4}

# the head pose's six coordinates in order (a pose term's axis, a pose CSV's columns;
# exubrush.world.pose): translation x, y, z [mm], then Tait-Bryan angles rx, ry, rz [rad]
POSE_AXES = ("x", "y", "z", "rx", "ry", "rz")

# how the tip's contact is computed (contact.backend; each a back end in
# exubrush.contact.tip_backends)
PAPER_SYMBOLIC, PAPER_PYTHON, PAPER_COMPILED, EXUDYN_BUILTIN = (
    "paper-symbolic", "paper-python", "paper-compiled", "exudyn-builtin")
CONTACT_BACKENDS = (PAPER_SYMBOLIC, PAPER_PYTHON, PAPER_COMPILED, EXUDYN_BUILTIN)

# the tip's friction law (contact.friction_model): the paper's regularised law
# (exubrush.contact.laws) or its Coulomb limit with a stick state (exubrush.contact.stick_slip)
PAPER_FRICTION, STICK_SLIP = "paper", "stick-slip"
FRICTION_MODELS = (PAPER_FRICTION, STICK_SLIP)
