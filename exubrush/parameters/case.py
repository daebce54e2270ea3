"""The parameters of a brushing case: contact, surface, model, motion, and the case that
composes them with the head (exubrush.parameters.head) and the numerical settings
(exubrush.parameters.settings).

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

from exubrush.parameters.choices import (
    CONTACT_BACKENDS,
    EXUDYN_BUILTIN,
    FRICTION_MODELS,
    MESH_UNITS,
    PAPER_COMPILED,
    PAPER_FRICTION,
    POSE_AXES,
    STICK_SLIP,
)
from exubrush.parameters.fields import Parameters, param
from exubrush.parameters.head import Head
from exubrush.parameters.settings import Limits, Output, Solver
from exubrush.parameters.surface_kinds import MESH, PLANE, SURFACE_KINDS, TOOTH_ROW


@dataclass(frozen=True)
class BristleContactLaw(Parameters):
    """Contact between bristles (contact.between_bristles): a linear penalty along the
    normal of the touching surfaces with damping, and Coulomb friction regularised below a
    sliding speed (docs/tufts.md, "Contact between bristles")."""

    # a numerical choice between the filaments' overlap and the run time (docs/tufts.md,
    # docs/decisions/0011)
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
    friction_model: str = param(
        PAPER_FRICTION,
        "the tip's friction: paper = the paper's regularised law (mu rises from 0 at zero "
        "slip to mu_s at v_s: a loaded tip creeps); stick-slip = its Coulomb limit, a tip "
        "held by a stiff tangential spring until F_t = mu_s F_n, then sliding at mu(v) "
        "(docs/model.md, 'Friction without creep')",
        "text", choices=FRICTION_MODELS,
    )
    stick_stretch: float = param(
        0.001, "stick-slip: the elastic slip of a sticking tip at F_t = mu_s F_n", "mm", "um",
        above=0.0, below=0.1,
    )
    stick_damping_time: float = param(
        1e-5, "stick-slip: time constant of the damper beside the sticking tip's spring "
              "(its force at slip speed v is that of the spring stretched by this time v)",
        "s", "us", minimum=0.0, below=1.0,
    )
    between_bristles: bool = param(
        False, "bristles touch each other (groups that can touch are solved together)")
    bristles: BristleContactLaw = field(default_factory=BristleContactLaw)

    def check(self) -> None:
        """Cross-field rules: v_s < v_d; the stick/slip law's needs."""
        if not self.static_velocity < self.dynamic_velocity:
            raise ValueError(
                f"static_velocity ({self.static_velocity:g} mm/s) must be below "
                f"dynamic_velocity ({self.dynamic_velocity:g} mm/s)"
            )
        if self.friction_model == STICK_SLIP:
            if self.static_friction <= 0.0:
                raise ValueError("friction_model 'stick-slip' needs static_friction above 0 "
                                 "(a tip with mu_s = 0 cannot stick; set friction_model "
                                 "'paper' for frictionless contact)")
            if self.backend in (EXUDYN_BUILTIN, PAPER_COMPILED):
                raise ValueError(f"friction_model 'stick-slip' is written for the user-function "
                                 f"back ends; contact.backend {self.backend!r} has its own "
                                 "friction: set contact.backend 'paper-symbolic' or "
                                 "'paper-python'")


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
        """The rotation coordinates the bodies get, ``rotation`` with "auto" resolved: the
        one on which the model's Newton iterations converge faster, a rotation vector for a
        PRB link, Euler parameters for DFM chains (docs/decisions/0015)."""
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
        if self.solver.threads > 1 and self.contact.backend != EXUDYN_BUILTIN:
            raise ValueError(
                f"solver.threads = {self.solver.threads} needs contact.backend "
                f"'exudyn-builtin': with the {self.contact.backend} law Exudyn's threads broke "
                "Newton or hung; use solver.threads = 1 or the built-in contact"
            )
        if self.contact.backend == EXUDYN_BUILTIN and self.surface.kind != PLANE:
            raise ValueError(
                f"contact.backend 'exudyn-builtin' brushes a plane only; surface.kind "
                f"'{self.surface.kind}' needs contact.backend 'paper-symbolic' (or 'paper-python')"
            )
        if self.contact.friction_model == STICK_SLIP and self.surface.kind != PLANE:
            raise ValueError(
                f"contact.friction_model 'stick-slip' is written for the plane (its anchor "
                f"lives in the plane's frame); surface.kind '{self.surface.kind}' needs "
                "contact.friction_model 'paper'")
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
