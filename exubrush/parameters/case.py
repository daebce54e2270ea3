"""The parameters of a brushing case: head, contact, model, motion, solver, output.

Frames. The head frame has X along the head's long axis, Y across it and Z along the
surface normal, pointing from the surface to the head.
The surface's highest point lies at Z = 0 (see :class:`Surface`).
A bristle's own frame has x from root to tip, y along the head's long axis (the section
width) and z = x × y (the section height, across the head).

Defaults are the paper's silicone brush (E, tip radius, d, contact law) and, where the
paper is silent, exubrush's documented choices (layout, section, length, ν, ρ, damping,
perturbation, approach): see docs/model.md, "Default head".
The built-in cases made from these sections are in :mod:`exubrush.parameters.catalogue`.

Every section derives from :class:`~exubrush.parameters.fields.Parameters`, so
``case.replace(...)`` and ``case.solver.replace(...)`` give validated copies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from exubrush.parameters.choices import CONTACT_BACKENDS, MESH_UNITS, POSE_AXES, SECTION_SHAPES
from exubrush.parameters.fields import Parameters, param
from exubrush.parameters.surface_kinds import MESH, PLANE, SURFACE_KINDS, TOOTH_ROW


@dataclass(frozen=True)
class Material(Parameters):
    """Linear elastic bristle material."""

    youngs_modulus: float = param(7.5, "Young's modulus E (paper: silicone)", "MPa", above=0.0)
    poisson_ratio: float = param(0.48, "Poisson ratio (silicone, nearly incompressible)",
                                 minimum=0.0, below=0.5)
    density: float = param(1.1e-9, "density (silicone rubber)", "t/mm^3", "kg/m^3", above=0.0)
    damping_time: float = param(
        5e-5, "stiffness-proportional damping: C = damping_time * K", "s", minimum=0.0
    )

    @property
    def shear_modulus(self) -> float:
        """G = E / (2(1 + ν)) [MPa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class BristleShape(Parameters):
    """Geometry of one straight bristle."""

    length: float = param(5.0, "free length, root to tip-sphere centre", "mm", above=0.0)
    section: str = param("rectangle", "cross-section shape", "text", choices=SECTION_SHAPES)
    width: float = param(0.6, "section width along the head's long axis", "mm", above=0.0)
    height: float = param(0.9, "section height across the head", "mm", above=0.0)
    tip_radius: float = param(0.4, "radius of the tip sphere (paper)", "mm", above=0.0)

    def check(self) -> None:
        """A circle needs equal width and height."""
        if self.section == "circle" and not math.isclose(self.width, self.height):
            raise ValueError("a circle section needs width == height (the diameter)")


@dataclass(frozen=True)
class BristleEntry(Parameters):
    """One bristle of an explicit list layout (head.layout = "list")."""

    x: float = param(0.0, "root position along the head's long axis", "mm")
    y: float = param(0.0, "root position across the head", "mm")
    tilt_x: float = param(0.0, "root tilt about the head's long axis", "rad", "deg")
    tilt_y: float = param(0.0, "root tilt about the across axis", "rad", "deg")
    length: float = param(5.0, "free length, root to tip-sphere centre", "mm", above=0.0)
    section: str = param("rectangle", "cross-section shape", "text", choices=SECTION_SHAPES)
    width: float = param(0.6, "section width along the head's long axis", "mm", above=0.0)
    height: float = param(0.9, "section height across the head", "mm", above=0.0)
    tip_radius: float = param(0.4, "radius of the tip sphere", "mm", above=0.0)


@dataclass(frozen=True)
class NamedMaterial(Material):
    """A material a tuft refers to by ``name`` (``[[head.materials]]``); its fields are
    those of :class:`Material`, with the silicone defaults where a field is not given."""

    name: str = param("", "name the tufts' material field refers to", "text")

    def check(self) -> None:
        """A name that is not one of the built-in materials' (those cannot be redefined)."""
        if not self.name.strip():
            raise ValueError("a material needs a name")
        if self.name in BUILT_IN_MATERIALS:
            raise ValueError(f"material {self.name!r} is built in; give yours another name")


# Typical filament materials (docs/tufts.md, "Materials", for where the values come from and
# how uncertain they are). The damping time is exubrush's numerical choice, as for silicone.
BUILT_IN_MATERIALS = {
    "silicone": Material(),
    "nylon": Material(youngs_modulus=2000.0, poisson_ratio=0.40, density=1.06e-9),
    "pbt": Material(youngs_modulus=2500.0, poisson_ratio=0.40, density=1.31e-9),
}
TUFT_PACKINGS = ("hexagonal", "random")


@dataclass(frozen=True)
class Tuft(Parameters):
    """One tuft of the head (head.layout = "tufts"): ``filaments`` equal straight filaments
    packed inside a circle of ``diameter`` around (x, y), all parallel to the tuft's axis.
    A single blade is a tuft of one filament with a rectangle section."""

    name: str = param("", "name used in messages and tables (default: tufts[i])", "text")
    x: float = param(0.0, "tuft centre along the head's long axis", "mm")
    y: float = param(0.0, "tuft centre across the head", "mm")
    diameter: float = param(1.6, "diameter of the tuft's hole in the head", "mm", above=0.0)
    filaments: int = param(37, "number of filaments in the tuft", above=0)
    packing: str = param(
        "hexagonal", "filament roots: hexagonal (touching, centre outwards) or random "
        "(seeded, non-overlapping, inside the tuft circle)", "text", choices=TUFT_PACKINGS)
    section: str = param("circle", "filament cross-section shape", "text",
                         choices=SECTION_SHAPES)
    width: float = param(0.2, "filament section width along the head's long axis (a "
                              "circle's diameter)", "mm", above=0.0)
    height: float = param(0.2, "filament section height across the head (a circle's "
                               "diameter)", "mm", above=0.0)
    length: float = param(10.4, "free length, root to tip-sphere centre (10.5 mm trim "
                                "length less the tip radius)", "mm", above=0.0)
    tip_radius: float = param(0.1, "radius of the filament's rounded tip", "mm", above=0.0)
    tilt_x: float = param(0.0, "tuft tilt about the head's long axis", "rad", "deg",
                          minimum=-math.radians(60.0), below=math.radians(60.0))
    tilt_y: float = param(0.0, "tuft tilt about the across axis", "rad", "deg",
                          minimum=-math.radians(60.0), below=math.radians(60.0))
    material: str = param("nylon", "filament material: silicone, nylon, pbt or the name of "
                                   "a [[head.materials]] entry", "text")

    def check(self) -> None:
        """A circle needs equal width and height."""
        if self.section == "circle" and not math.isclose(self.width, self.height):
            raise ValueError(f"a circle section needs width == height (the diameter), got "
                             f"{self.width:g} mm and {self.height:g} mm")

    @property
    def filament_diameter(self) -> float:
        """Diameter of the circle around a filament's section [mm] (the packing pitch)."""
        return math.hypot(self.width, self.height) if self.section == "rectangle" else max(
            self.width, self.height)


@dataclass(frozen=True)
class Head(Parameters):
    """Bristle layout of the head.

    ``layout = "grid"`` places ``rows x columns`` copies of ``bristle`` on a regular grid
    centred on the head; ``layout = "list"`` uses the ``bristles`` entries instead;
    ``layout = "tufts"`` builds the head from ``tufts`` (or from the CSV ``tuft_table``,
    read into ``tufts`` when the case is loaded: exubrush.parameters.tuft_table).
    """

    layout: str = param("grid", "bristle layout", "text", choices=("grid", "list", "tufts"))
    rows: int = param(4, "grid: bristles across the head", above=0)
    columns: int = param(12, "grid: bristles along the head's long axis", above=0)
    pitch_along: float = param(1.8, "grid: pitch along the long axis", "mm", above=0.0)
    pitch_across: float = param(1.8, "grid: pitch across the head", "mm", above=0.0)
    root_tilt: float = param(
        math.radians(0.5),
        "symmetry breaking: each root is tilted by this angle in a seeded random direction",
        "rad", "deg", minimum=0.0, below=math.radians(30.0),
    )
    tilt_pattern: str = param(
        "random", "direction of each root's tilt (root_tilt): random = a seeded random "
                  "direction per bristle, shared by a tuft's filaments; radial = away from "
                  "the head's centre, the section turned with the root's polar angle (a "
                  "root at the centre: a seeded random direction), so that a head "
                  "symmetric under turns about its centre stays so",
        "text", choices=("random", "radial"))
    seed: int = param(1, "seed of the root-tilt directions and of random tuft packings",
                      minimum=0)
    tuft_table: str = param("", "tufts: CSV table of the tufts, one row per tuft, units in "
                                "the header (relative to the case file)", "text")
    material: Material = field(default_factory=Material)
    bristle: BristleShape = field(default_factory=BristleShape)
    bristles: tuple[BristleEntry, ...] = ()
    tufts: tuple[Tuft, ...] = ()
    materials: tuple[NamedMaterial, ...] = ()

    @property
    def count(self) -> int:
        """Number of bristles, known before any is built (a tuft table must have been
        read: exubrush.parameters.io.load_case)."""
        if self.layout == "tufts":
            return sum(tuft.filaments for tuft in self.tufts)
        return len(self.bristles) if self.layout == "list" else self.rows * self.columns

    def tuft_names(self) -> list[str]:
        """Each tuft as messages name it: ``tuft 'NAME'`` with its own name, or ``tufts[i]``
        (a tuft table's rows are named after their file and line)."""
        return [f"tuft {tuft.name!r}" if tuft.name else f"tufts[{i}]"
                for i, tuft in enumerate(self.tufts)]

    def tuft_material(self, tuft: Tuft) -> Material:
        """The material a tuft names (a [[head.materials]] entry or a built-in one)."""
        for entry in self.materials:
            if entry.name == tuft.material:
                return entry
        return BUILT_IN_MATERIALS[tuft.material]

    def check(self) -> None:
        """A list layout needs entries, each at its own root; a tuft layout needs tufts
        that name known materials and do not overlap."""
        if self.layout == "list" and not self.bristles:
            raise ValueError("layout 'list' needs at least one [[head.bristles]] entry")
        roots: dict[tuple[float, float], int] = {}
        for index, entry in enumerate(self.bristles):
            first = roots.setdefault((entry.x, entry.y), index)
            if first != index:
                raise ValueError(f"bristles[{index}] has the same root (x, y) as "
                                 f"bristles[{first}]: give each bristle its own position")
        if self.layout == "tufts":
            self._check_tufts()
        elif self.tuft_table:
            raise ValueError(f"tuft_table is read for layout 'tufts' only (layout is "
                             f"'{self.layout}'): set head.layout = 'tufts'")

    def _check_tufts(self) -> None:
        if self.tuft_table and self.tufts:
            raise ValueError("give the tufts either as [[head.tufts]] or in tuft_table, not "
                             "both")
        if not self.tufts and not self.tuft_table:
            raise ValueError("layout 'tufts' needs [[head.tufts]] entries or a tuft_table")
        names = self.tuft_names()
        known = set(BUILT_IN_MATERIALS) | {entry.name for entry in self.materials}
        for name, tuft in zip(names, self.tufts, strict=True):
            if tuft.material not in known:
                raise ValueError(f"{name}: material {tuft.material!r} is not defined; use "
                                 f"one of {', '.join(sorted(known))} or add a "
                                 "[[head.materials]] entry of that name")
        if len(self.tufts) < 2:
            return
        centres = [(tuft.x, tuft.y) for tuft in self.tufts]
        radii = [0.5 * tuft.diameter for tuft in self.tufts]
        # candidate pairs from a k-d tree (a head may have thousands of tufts), then exact;
        # NumPy and SciPy are imported only where tufts are read
        from exubrush.util.pair_search import pairs_within

        # sorted: the first overlapping pair named is the same whatever the tree's order
        for i, j in sorted(pairs_within(centres, 2.0 * max(radii)).tolist()):
            gap = math.dist(centres[i], centres[j]) - radii[i] - radii[j]
            if gap < 0.0:
                raise ValueError(
                    f"{names[i]} and {names[j]} overlap by {-gap:.3g} mm (their circles "
                    "of diameter share area): move them apart or make them narrower")


@dataclass(frozen=True)
class BristleContactLaw(Parameters):
    """Contact between bristles (contact.between_bristles): a linear penalty along the
    normal of the touching surfaces with damping, and Coulomb friction regularised below a
    sliding speed (docs/tufts.md, "Contact between bristles")."""

    # a numerical choice (docs/tufts.md): the deepest overlap in a 7-filament tuft over a
    # period was 3.8 % of the diameter at 50 N/mm, 5.6 % at 25; 100 N/mm doubled the run time
    stiffness: float = param(50.0, "penalty stiffness per contact", "N/mm", above=0.0)
    # about critical damping 2√(k m) of one DFM segment of a nylon filament (1e-4) or of a
    # silicone blade (3e-4)
    damping: float = param(2e-4, "damping per contact", "N*s/mm", minimum=0.0)
    friction: float = param(0.2, "Coulomb friction coefficient between bristles (nylon on "
                                 "nylon)", minimum=0.0)
    friction_velocity: float = param(
        1.0, "sliding speed of the friction's regularisation: mu f_n v/sqrt(v^2 + v_r^2), "
             "linear from zero below it", "mm/s",
        above=0.0)


@dataclass(frozen=True)
class ContactLaw(Parameters):
    """Tip-surface contact: the paper's normal and friction laws (mm-N-s units; defaults:
    the paper's table 2) and how they are computed (``backend``).

    k and c are the coefficients of the law evaluated in mm, N and s. Their units are
    written for the paper's exponents (N/mm^1.3 for m1 = 1.3; N·s/mm³ for m2 = 1, m3 = 2);
    with other exponents the number is still read in mm-N-s, whatever the unit says.
    The law itself is :mod:`exubrush.contact.laws`.
    """

    stiffness: float = param(100.0, "penalty stiffness k", "N/mm^1.3", above=0.0)
    stiffness_exponent: float = param(1.3, "stiffness exponent m1", above=0.0)
    damping: float = param(0.2, "Flores damping coefficient c", "N*s/mm^3", minimum=0.0)
    damping_rate_exponent: float = param(1.0, "damping rate exponent m2", above=0.0)
    damping_depth_exponent: float = param(2.0, "indentation exponent m3", minimum=0.0)
    static_friction: float = param(0.8, "static friction coefficient mu_s", minimum=0.0)
    dynamic_friction: float = param(0.76, "dynamic friction coefficient mu_d", minimum=0.0)
    static_velocity: float = param(1.2, "static velocity tolerance v_s", "mm/s", above=0.0)
    dynamic_velocity: float = param(1.5, "dynamic velocity tolerance v_d", "mm/s", above=0.0)
    backend: str = param(
        "paper-symbolic",
        "how the contact is computed: paper-symbolic = the paper's law compiled by Exudyn "
        "(C++); paper-python = the same law in Python (slower, same forces); paper-compiled = "
        "the same law compiled with numba with a Jacobian of its own where it is built (tips "
        "on Euler-parameter nodes, as DFM's, over a cylinder, sphere or tooth row; faster: "
        "docs/decisions/0018), else paper-symbolic; exudyn-builtin = "
        "Exudyn's own sphere-triangle contact with the nearest parameters (one friction "
        "coefficient, linear damping: an approximation, see docs/model.md)",
        "text", choices=CONTACT_BACKENDS,
    )
    between_bristles: bool = param(
        False, "bristles touch each other (groups that can touch are solved together)")
    bristles: BristleContactLaw = field(default_factory=BristleContactLaw)

    def check(self) -> None:
        """Cross-field rules: v_s < v_d."""
        if not self.static_velocity < self.dynamic_velocity:
            raise ValueError(
                f"static_velocity ({self.static_velocity:g} mm/s) must be below "
                f"dynamic_velocity ({self.dynamic_velocity:g} mm/s)"
            )


@dataclass(frozen=True)
class Surface(Parameters):
    """The rigid surface the tips brush (exubrush.world.surfaces).

    Each kind is defined in its own frame, whose origin is the surface's highest point (top)
    and whose z is the head frame's Z: ``plane`` is z = 0; ``cylinder`` has its axis along
    y at depth ``radius`` (a tooth crown); ``sphere`` its centre at depth ``radius``;
    ``tooth-row`` is a row of flat-topped teeth of width ``tooth_width`` along x, separated
    by interdental gaps ``gap_width`` wide and ``gap_depth`` deep, the tooth's top edges
    rounded with ``edge_radius``, the profile extruded along y; ``mesh`` is the triangle
    mesh of ``mesh_file`` (STL or OBJ, in ``mesh_unit``), its highest vertex moved to z = 0
    (exubrush.world.mesh). ``x``, ``y`` and ``yaw``
    place that frame in the head frame (the head's position at the slide's centre); the
    top stays at Z = 0, so ``motion.interaction_distance`` is measured to it.
    """

    kind: str = param(PLANE, "surface shape", "text", choices=SURFACE_KINDS)
    # below 1 km: the distance √(x² + (z+R)²) − R keeps the µm of a contact's depth (its
    # rounding, R · 2e-16, grows with R; at R = 1e12 mm a run failed on it): use a plane
    radius: float = param(4.0, "cylinder, sphere: radius", "mm", above=0.0, below=1e6)
    tooth_width: float = param(7.0, "tooth-row: width of a tooth's crown along the row", "mm",
                               above=0.0)
    gap_width: float = param(1.0, "tooth-row: width of an interdental gap", "mm", above=0.0)
    gap_depth: float = param(2.0, "tooth-row: depth of a gap below the tooth tops", "mm",
                             above=0.0)
    edge_radius: float = param(0.5, "tooth-row: radius of the rounded top edges of a tooth",
                               "mm", minimum=0.0)
    mesh_file: str = param("", "mesh: STL or OBJ file of the surface (relative to the case "
                                "file)", "text")
    mesh_unit: str = param("mm", "mesh: unit of the file's coordinates", "text",
                           choices=tuple(MESH_UNITS))
    x: float = param(0.0, "position of the surface's top along the head's long axis", "mm")
    y: float = param(0.0, "position of the surface's top across the head", "mm")
    yaw: float = param(0.0, "rotation of the surface about Z (0: its x along the head's "
                            "long axis)", "rad", "deg", minimum=-2 * math.pi,
                       below=2 * math.pi)

    def check(self) -> None:
        """A tooth's rounded edges fit in its crown and its gap; a mesh needs a file."""
        if self.kind == MESH and not self.mesh_file:
            raise ValueError("kind 'mesh' needs mesh_file (an STL or OBJ file)")
        if self.kind == TOOTH_ROW:
            if not self.edge_radius < 0.5 * self.tooth_width:
                raise ValueError(f"edge_radius ({self.edge_radius:g} mm) must be below half "
                                 f"the tooth_width ({self.tooth_width:g} mm)")
            if not self.edge_radius <= self.gap_depth:
                raise ValueError(f"edge_radius ({self.edge_radius:g} mm) must not exceed "
                                 f"gap_depth ({self.gap_depth:g} mm)")


@dataclass(frozen=True)
class Model(Parameters):
    """Bristle model and its discretisation."""

    kind: str = param("dfm", "bristle model", "text", choices=("dfm", "prb"))
    segments: int = param(6, "DFM: rigid bodies per bristle", above=0)
    rotation: str = param(
        "auto",
        "rotation coordinates of the bristle bodies: euler-parameters (4 per node and a "
        "constraint), rotation-vector (Exudyn's Lie-group node, 3 per node) or auto (the "
        "faster one for the model: euler-parameters for DFM, rotation-vector for PRB; "
        "docs/decisions/0015)",
        "text", choices=("auto", "euler-parameters", "rotation-vector"),
    )
    prb_link: str = param(
        "buckling",
        "PRB: 'buckling' lets the link shorten along its axis against the bristle's axial "
        "stiffness, which gives way at the clamped-pinned buckling load (exubrush.models."
        "buckling), so a pushed bristle snaps through; 'rigid' is the paper's link",
        "text", choices=("buckling", "rigid"),
    )
    prb_pivot: str = param(
        "spring",
        "PRB, buckling link: what holds the link's axis on the pivot: 'spring' (a stiff "
        "lateral spring, exubrush.models.prb.PIVOT_STIFFNESS_FACTOR times the bristle's "
        "axial stiffness, acting where the link passes the pivot; Newton needs fewer "
        "iterations) or 'joint' (Exudyn's constraint, exact)",
        "text", choices=("spring", "joint"),
    )
    prb_parameters: str = param(
        "howell-table",
        "PRB: 'howell-table' interpolates gamma, K_theta in Howell's table at n; 'fitted' "
        "fits them to the exact elastica at n (exubrush.reference.howell_fit); 'explicit' "
        "uses prb_gamma and prb_stiffness_coefficient",
        "text", choices=("howell-table", "fitted", "explicit"),
    )
    prb_load_ratio: str = param(
        "1/mu_d", "PRB: load ratio n = axial / transverse tip force: '1/mu_d' (a tip sliding "
        "with Coulomb friction) or a number", "text",
    )
    prb_gamma: float = param(0.8329, "PRB: characteristic radius factor gamma (explicit)",
                             above=0.0, below=1.0)
    prb_stiffness_coefficient: float = param(
        2.6001, "PRB: stiffness coefficient K_theta (explicit)", above=0.0
    )

    @property
    def node_rotation(self) -> str:
        """The rotation coordinates the bodies get, ``rotation`` with "auto" resolved: a PRB
        link on Euler parameters took 3.5-5.2 Newton iterations a step and 5.5 times the
        Jacobians, on a rotation vector 2.6-3.8 (docs/decisions/0015); DFM chains are faster on
        Euler parameters."""
        if self.rotation != "auto":
            return self.rotation
        return "rotation-vector" if self.kind == "prb" else "euler-parameters"

    @property
    def shape_nodes(self) -> int:
        """Nodes of a bristle the solve stores in its shapes, the root not counted: the
        DFM's ``segments`` bodies, the PRB link [-]."""
        return self.segments if self.kind == "dfm" else 1

    @property
    def bristle_coordinates(self) -> int:
        """ODE2 coordinates of one bristle in its Exudyn system, as a run keeps them for
        the viewer (output.solution_file): per node 3 of position and 4 Euler parameters
        or 3 rotation-vector components (:attr:`node_rotation`) [-]."""
        return self.shape_nodes * (7 if self.node_rotation == "euler-parameters" else 6)


@dataclass(frozen=True)
class SineMotion(Parameters):
    """A sine on one coordinate of the head's pose, added to the approach and the slide
    (``[[motion.sine]]``; exubrush.world.pose.SineTerm, docs/motion.md).

    value = e(t) a sin(2π f (t - t₀) + φ) from t₀ = the slide's start + ``start`` for
    ``duration`` (0: to the run's end), e(t) rising from 0 to 1 over ``ramp_cycles``
    cycles and falling again before a finite end, so the head never jerks.
    """

    axis: str = param("y", "pose coordinate: x, y, z [mm] along the head's axes, or rx, ry, "
                           "rz [deg] about them (about motion.pivot)", "text", choices=POSE_AXES)
    amplitude: float = param(0.0, "x, y, z: amplitude of the translation", "mm", minimum=0.0)
    angle: float = param(0.0, "rx, ry, rz: amplitude of the rotation", "rad", "deg",
                         minimum=0.0, below=math.pi)
    frequency: float = param(260.0, "frequency", "Hz", above=0.0)
    phase: float = param(0.0, "phase at the term's start", "rad", "deg")
    start: float = param(0.0, "start after the slide's start (the end of the hold)", "s",
                         minimum=0.0)
    duration: float = param(0.0, "how long the term acts (0: to the end of the run)", "s",
                            minimum=0.0)
    ramp_cycles: float = param(2.0, "cycles over which the amplitude rises from 0 (and "
                                    "falls before a finite end); 0: none, the head jerks",
                               minimum=0.0)

    @property
    def rotation(self) -> bool:
        """Whether the term turns the head (rx, ry, rz) rather than moving it."""
        return self.axis.startswith("r")

    @property
    def size(self) -> float:
        """The amplitude in the internal unit of its axis (mm or rad)."""
        return self.angle if self.rotation else self.amplitude

    def check(self) -> None:
        """The amplitude that fits the axis, none of the other; a finite term's ramps fit."""
        given, other = ("angle", "amplitude") if self.rotation else ("amplitude", "angle")
        if getattr(self, other) != 0.0:
            raise ValueError(f"axis {self.axis!r} takes {given}, not {other}")
        if self.size == 0.0:
            raise ValueError(f"axis {self.axis!r} needs a {given} above 0")
        ramp = self.ramp_cycles / self.frequency
        if self.duration and 2.0 * ramp > self.duration:
            raise ValueError(f"duration {self.duration:g} s is shorter than the rise and fall "
                             f"of ramp_cycles = {self.ramp_cycles:g} (2 x {ramp:.4g} s)")


@dataclass(frozen=True)
class Motion(Parameters):
    """Approach, hold and slide of the head, and any sine or tabulated pose terms on top
    (see exubrush.world.motion, exubrush.world.pose and docs/motion.md)."""

    direction: str = param(
        "orthogonal", "slide axis: across the long axis (orthogonal) or along it (parallel)",
        "text", choices=("orthogonal", "parallel"),
    )
    profile: str = param("sine", "slide profile (none: the head does not slide; the run "
                                 "still lasts periods x period after the hold)", "text",
                         choices=("sine", "csv", "none"))
    amplitude: float = param(15.0, "sine: slide amplitude", "mm", above=0.0)
    period: float = param(12.0, "sine: slide period", "s", above=0.0)
    periods: float = param(2.0, "sine: number of slide periods simulated", above=0.0)
    csv_file: str = param("", "csv: slide profile file (time [s], slider_position [mm])", "text")
    interaction_distance: float = param(
        4.2, "distance d from the bristle roots' surface to the plane (paper)", "mm", above=0.0
    )
    approach_clearance: float = param(
        0.3, "gap between the lowest tip sphere and the plane at t = 0", "mm", minimum=0.0
    )
    approach_duration: float = param(1.0, "time to move from clearance to d", "s", above=0.0)
    hold_duration: float = param(0.2, "rest at d before sliding", "s", minimum=0.0)
    approach_friction: str = param(
        "auto",
        "friction while approaching: on; off (blended in during the hold); auto = on for "
        "DFM, off for PRB (a rigid PRB link with a sticking tip jams; with the buckling "
        "link a sticking tip leaves PRB two strokes longer off DFM's forces)",
        "text", choices=("auto", "on", "off"),
    )

    pivot: tuple[float, ...] = param(
        (0.0, 0.0, 0.0), "point the head turns about, in the head frame (origin: the "
                         "roots' surface at the head's centre)", "mm")
    sine: tuple[SineMotion, ...] = ()
    pose_csv: str = param("", "pose table added to the motion: time and any of x, y, z, rx, "
                              "ry, rz, units in the header (docs/motion.md)", "text")
    pose_csv_start: float = param(0.0, "when the pose table's first row applies, after the "
                                       "slide's start", "s", minimum=0.0)

    def check(self) -> None:
        """A CSV profile needs a file; the pivot is a point."""
        if self.profile == "csv" and not self.csv_file:
            raise ValueError("profile 'csv' needs csv_file")
        if len(self.pivot) != 3:
            raise ValueError(f"pivot needs 3 coordinates (x, y, z), got {len(self.pivot)}")

    @property
    def posed(self) -> bool:
        """Whether any pose term (motion.sine, motion.pose_csv) moves the head beyond the
        approach and the slide."""
        return bool(self.sine or self.pose_csv)


@dataclass(frozen=True)
class Solver(Parameters):
    """Exudyn implicit solver settings (generalized-alpha with automatic step reduction).

    The defaults are the ``balanced`` preset (exubrush.presets); why each is what it is,
    with measurements, is in the decision records docs/decisions/ (index in
    validation/benchmarks/README.md).
    """

    RENAMED = {
        "user_functions": "renamed contact.backend: 'symbolic' is now 'paper-symbolic', "
                          "'python' 'paper-python', 'builtin' 'exudyn-builtin'",
    }

    step_size: float = param(2e-3, "largest time step (the step is cut where Newton fails)",
                             "s", "ms", above=0.0)
    sliding_step_factor: float = param(
        5.0, "while the head slides at sliding_speed_fraction of its peak speed or faster "
             "over a plane, cylinder or sphere (a tooth row: with every tip over a flat top), "
             "the step may grow to this multiple of step_size, at most output.interval (1: "
             "step_size throughout; docs/model.md, 'Steps in the middle of a stroke')",
        minimum=1.0, below=100.0,
    )
    sliding_speed_fraction: float = param(
        0.3, "the head slides 'in the middle of a stroke' (sliding_step_factor) at this "
             "fraction of its peak speed or faster, and at 1.5 contact.dynamic_velocity or "
             "faster", above=0.0, below=1.0,
    )
    friction_drop: str = param(
        "lagged",
        "how a step takes the friction law's fall from mu_s to mu_d: lagged = at the slip "
        "speed of the step's start, the rise to mu_s within Newton; implicit = all within "
        "Newton (Newton fails where the falling friction outweighs a small tip's inertia; "
        "docs/model.md, 'The friction drop, one step behind')",
        "text", choices=("lagged", "implicit"),
    )
    step_cut: float = param(
        0.25, "factor by which a step is cut after Newton fails (Exudyn's "
              "adaptiveStepDecrease; Exudyn's default 0.5): a snapping tip's microsecond "
              "steps are reached in fewer failed tries (docs/decisions/0016)",
        above=0.0, below=1.0,
    )
    minimum_step_size: float = param(1e-9, "smallest step of the automatic step reduction",
                                     "s", above=0.0)
    spectral_radius: float = param(
        0.0, "generalized-alpha spectral radius at infinity (0 = most damping)", minimum=0.0
    )
    # below 1: at 1 or more Newton takes a step's first guess as converged, and the run
    # failed later with a misleading cause
    relative_tolerance: float = param(1e-6, "Newton relative tolerance", above=0.0, below=1.0)
    touching_relative_tolerance: float = param(
        1e-5, "Newton relative tolerance of a group of bristles that touch each other "
              "(contact.between_bristles)", above=0.0, below=1.0,
    )
    absolute_tolerance: float = param(1e-10, "Newton absolute tolerance (residual)", above=0.0)
    # below 1e-2: at 2.5e-3 the flat-zone forces already moved by 0.3 %, and a tolerance
    # near the buckling load itself accepts any first guess (a run "completes" with wrong
    # forces)
    force_tolerance: float = param(
        5e-4, "Newton also accepts a step whose residual is below this fraction of the Euler "
              "buckling load of the weakest bristle solved with it (0: off; "
              "docs/model.md, 'Newton's tolerance')", minimum=0.0, below=1e-2,
    )
    modified_newton: bool = param(True, "reuse the Jacobian between Newton iterations and "
                                        "steps (false: a fresh Jacobian every iteration)")
    newton_contractivity: float = param(
        0.5, "modified Newton makes a new Jacobian when an iteration shrinks the residual by "
             "less than this factor (Exudyn's modifiedNewtonContractivity); 1 was faster on "
             "the interdental case but moved the forces (docs/decisions/0018)",
        above=0.0, below=10.0,
    )
    # below 10, one-bristle solves failed at a reversal (docs/decisions/0002, 0007)
    newton_iterations: int = param(
        12, "Newton iterations before a step is given up and cut", minimum=10,
    )
    line_search: str = param(
        "auto",
        "shorten Newton's updates until the residual falls (a backtracking line search): "
        "always = at every iteration, after-cut = while the step is below its largest after "
        "a cut, off = Exudyn's full updates, auto = always in a group of touching bristles, "
        "off elsewhere and on rotation-vector nodes (docs/decisions/"
        "0001-newton-line-search.md)",
        "text", choices=("auto", "always", "after-cut", "off"),
    )
    linear_solver: str = param(
        "auto",
        "linear solver of Newton's steps: auto = EigenDense for one bristle, EigenSparse for "
        "a coupled head",
        "text", choices=("auto", "EigenDense", "EXUdense", "EigenSparse"),
    )
    steps_per_cycle: int = param(
        160, "while a [[motion.sine]] term acts, the step is at most its cycle over this: "
             "20 resolve the drive, 160 what a stuck tip and the head's moment do under a "
             "turn (docs/motion.md, 'How many steps a cycle')", minimum=4,
    )
    step_recovery_steps: int = param(
        4, "successful steps after a step reduction before the step may grow again (Exudyn's "
           "default 10; docs/decisions/0016)",
        minimum=1,
    )
    partition: str = param(
        "per-bristle",
        "per-bristle: each bristle its own system, solved in parallel processes (bristles do "
        "not touch each other); coupled: the whole head as one system",
        "text", choices=("per-bristle", "coupled"),
    )
    share_identical: bool = param(
        True, "solve once the bristles that differ only by where their roots sit, on a plane "
              "and a head that does not turn, without contact between bristles (a tuft's "
              "filaments; exubrush.run.twins)")
    threads: int = param(
        1, "Exudyn threads for a coupled head (needs contact.backend exudyn-builtin)",
        minimum=1,
    )

    def check(self) -> None:
        """Spectral radius within [0, 1]; minimum step below the step; threads only for a
        coupled head."""
        if self.spectral_radius > 1.0:
            raise ValueError(f"spectral_radius {self.spectral_radius:g} must be <= 1")
        if self.minimum_step_size > self.step_size:
            raise ValueError("minimum_step_size must not exceed step_size")
        if self.threads > 1 and self.partition != "coupled":
            raise ValueError(
                f"threads = {self.threads} needs partition 'coupled': per-bristle already "
                "solves one bristle per process on every core"
            )


@dataclass(frozen=True)
class Output(Parameters):
    """What is recorded."""

    interval: float = param(0.01, "force output interval", "s", above=0.0)
    shape_interval: float = param(0.1, "bristle shape output interval", "s", above=0.0)
    solution_file: bool = param(
        False, "also keep every node's coordinates at shape_interval, for Exudyn's "
        "SolutionViewer (exubrush view)")

    @property
    def shape_stride(self) -> int:
        """Force samples per shape sample: shapes are every this many force samples from
        the first [-]."""
        return max(1, round(self.shape_interval / self.interval))

    def shape_samples(self, samples: int) -> int:
        """Shape samples among ``samples`` force samples: every :attr:`shape_stride`-th
        from the first [-]."""
        return -(-samples // self.shape_stride)

    def check(self) -> None:
        """Shapes are sampled from the force output, so not more often than it."""
        if self.shape_interval < self.interval:
            raise ValueError(f"shape_interval ({self.shape_interval:g} s) must not be shorter "
                             f"than interval ({self.interval:g} s)")


@dataclass(frozen=True)
class Limits(Parameters):
    """Bounds on the work a run may take on, checked before anything is built
    (exubrush.run.budget). Generous for real studies; raise them to run bigger ones. They do
    not change results, so a run that only raises a limit resumes its checkpoint."""

    bristles: int = param(10_000, "most bristles in a head", above=0)
    segments: int = param(200, "most DFM bodies per bristle", above=0)
    steps: int = param(
        20_000_000, "most time steps per solved system at solver.step_size (end time / step)",
        above=0)
    memory: float = param(8e9, "most memory the recorded results may take (estimate)", "B",
                          "GB", above=0.0)
    term_evaluations: float = param(
        1e7, "most evaluations of the pose terms per solved system: (motion.sine terms + a "
             "pose table) x time steps; each is evaluated in Python at every step (its cost: "
             "docs/runs.md)", above=0.0)


@dataclass(frozen=True)
class Case(Parameters):
    """A complete brushing case."""

    name: str = param("orthogonal", "case name", "text")
    head: Head = field(default_factory=Head)
    contact: ContactLaw = field(default_factory=ContactLaw)
    surface: Surface = field(default_factory=Surface)
    model: Model = field(default_factory=Model)
    motion: Motion = field(default_factory=Motion)
    solver: Solver = field(default_factory=Solver)
    output: Output = field(default_factory=Output)
    limits: Limits = field(default_factory=Limits)

    def load_ratio(self) -> float:
        """The PRB load ratio n (model.prb_load_ratio; '1/mu_d' from the contact law)."""
        text = self.model.prb_load_ratio.strip()
        if text == "1/mu_d":
            if self.contact.dynamic_friction <= 0:
                raise ValueError("model.prb_load_ratio '1/mu_d' is infinite for "
                                 "contact.dynamic_friction = 0; set model.prb_load_ratio to a "
                                 "number or model.prb_parameters = 'explicit'")
            return 1.0 / self.contact.dynamic_friction
        try:
            return float(text)
        except ValueError:
            raise ValueError(f"model.prb_load_ratio {text!r} is neither '1/mu_d' nor a "
                             "number") from None

    def check(self) -> None:
        """Rules that tie sections together (PRB parameters, threads, friction blending),
        and a name that can label files and plots."""
        if not self.name.isprintable() or not 0 < len(self.name) <= 100:
            raise ValueError(f"name {self.name!r} must be 1 to 100 printable characters")
        prb = self.model.kind == "prb"
        source = self.model.prb_parameters
        if prb and source != "explicit":
            n = self.load_ratio()
            low = 0.0 if source == "howell-table" else -1.0
            if not low <= n <= 10.0:
                raise ValueError(f"PRB load ratio n = {n:.4g} is outside [{low:g}, 10] of "
                                 f"model.prb_parameters '{source}'; set the PRB parameters "
                                 "explicitly")
        if self.solver.threads > 1 and self.contact.backend != "exudyn-builtin":
            raise ValueError(
                f"solver.threads = {self.solver.threads} needs contact.backend "
                f"'exudyn-builtin': with the {self.contact.backend} law Exudyn's threads broke "
                "Newton or hung; use solver.threads = 1 or the built-in contact"
            )
        if self.contact.backend == "exudyn-builtin" and self.surface.kind != PLANE:
            raise ValueError(
                f"contact.backend 'exudyn-builtin' brushes a plane only; surface.kind "
                f"'{self.surface.kind}' needs contact.backend 'paper-symbolic' (or 'paper-python')"
            )
        if (self.solver.line_search in ("always", "after-cut")
                and self.model.node_rotation == "rotation-vector"):
            raise ValueError(
                f"solver.line_search '{self.solver.line_search}' needs model.rotation "
                "'euler-parameters': Exudyn updates rotation vectors on the Lie group, where a "
                "shortened update is not what it continues from; set solver.line_search = "
                "'auto' or 'off'")
        blended = self.motion.approach_friction == "off" or (
            prb and self.motion.approach_friction == "auto")
        if blended and self.motion.hold_duration <= 0.0:
            raise ValueError("motion.approach_friction off (or auto with PRB) blends friction "
                             "in during the hold: set motion.hold_duration > 0")
