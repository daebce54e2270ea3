"""The head's parameters: bristle materials, shapes and entries, tufts, and the head's
layout (a section of :class:`exubrush.parameters.case.Case`).

A bristle's own frame has x from root to tip, y along the head's long axis (the section
width) and z = x × y (the section height, across the head); the head frame is described in
:mod:`exubrush.parameters.case`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from exubrush.parameters.choices import SECTION_SHAPES
from exubrush.parameters.fields import Parameters, param


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
# the imperfections' ranges (docs/model.md, "Imperfections of a real head"): a tilt spread or
# misalignment beyond this is no small error but another head; a length spread of half
# the length or more would trim some bristles to stubs; a root jitter beyond 1 mm moves a
# root by more than a blade's width (and a bristle with no neighbour, whose jitter no
# neighbour bounds, anywhere): another layout, not a placement error [mm]
IMPERFECT_TILT_LIMIT = math.radians(10.0)
LENGTH_SPREAD_LIMIT = 0.5
ROOT_JITTER_LIMIT = 1.0


def section_diameter(section: str, width: float, height: float) -> float:
    """Diameter of the circle around a section [mm]: a rectangle's diagonal, a circle's
    diameter (the larger extent)."""
    return math.hypot(width, height) if section == "rectangle" else max(width, height)


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
        return section_diameter(self.section, self.width, self.height)


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
    seed: int = param(1, "seed of the root-tilt directions, of random tuft packings and of "
                         "the imperfect head's draws", minimum=0)
    tilt_spread_x: float = param(
        0.0, "imperfect head: half-width of the uniform spread of each root's tilt about the "
             "head's long axis x (tips scatter across the head: in the slide's plane for "
             "orthogonal brushing, out of it for parallel), drawn per bristle (per tuft) "
             "from head.seed", "rad", "deg", minimum=0.0, below=IMPERFECT_TILT_LIMIT)
    tilt_spread_y: float = param(
        0.0, "imperfect head: half-width of the uniform spread of each root's tilt about the "
             "across axis y (tips scatter along the head: in the slide's plane for parallel "
             "brushing, out of it for orthogonal), drawn per bristle (per tuft)", "rad",
        "deg", minimum=0.0, below=IMPERFECT_TILT_LIMIT)
    length_spread: float = param(
        0.0, "imperfect head: half-width of the uniform spread of each free length, a "
             "fraction of it (0.03 or \"3 %\": lengths within ±3 %), drawn per bristle",
        minimum=0.0, below=LENGTH_SPREAD_LIMIT)
    root_jitter: float = param(
        0.0, "imperfect head: half-width of the uniform spread of each root's x and y, "
             "drawn per bristle (grid and list layouts)", "mm", minimum=0.0,
        below=ROOT_JITTER_LIMIT)
    misalign_x: float = param(
        0.0, "imperfect head: tilt of the whole head about its long axis x through its "
             "centre on the roots' surface (roots and bristles turned)", "rad", "deg",
        minimum=-IMPERFECT_TILT_LIMIT, below=IMPERFECT_TILT_LIMIT)
    misalign_y: float = param(
        0.0, "imperfect head: tilt of the whole head about its across axis y through its "
             "centre, after misalign_x", "rad", "deg", minimum=-IMPERFECT_TILT_LIMIT,
        below=IMPERFECT_TILT_LIMIT)
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

    @property
    def imperfect(self) -> bool:
        """Whether any imperfection of a real head is switched on (tilt, length or root
        spreads, misalignment); all zero is the ideal head."""
        return any((self.tilt_spread_x, self.tilt_spread_y, self.length_spread,
                    self.root_jitter, self.misalign_x, self.misalign_y))

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
        that name known materials and do not overlap; a root jitter must keep the roots
        apart (grid and list layouts only)."""
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
            if self.root_jitter > 0.0:
                raise ValueError("root_jitter is for grid and list layouts: a tuft's "
                                 "filaments are packed touching (packing = 'random' draws "
                                 "their roots); set head.root_jitter = 0")
            return
        if self.tuft_table:
            raise ValueError(f"tuft_table is read for layout 'tufts' only (layout is "
                             f"'{self.layout}'): set head.layout = 'tufts'")
        if self.root_jitter > 0.0:
            self._check_jitter()

    def _check_jitter(self) -> None:
        """Jittered roots stay apart: each root moves at most √2 root_jitter (its x and y
        each by up to root_jitter), so a pair of roots a distance D apart comes at most
        2√2 root_jitter closer; the circles around their sections (section_diameter) must
        still not overlap (a bound for any seed, so a sweep over seeds is refused or run
        whole)."""
        if self.layout == "grid":
            pitches = ([self.pitch_along] if self.columns > 1 else []) + (
                [self.pitch_across] if self.rows > 1 else [])
            shape = self.bristle
            pairs = [(pitch - section_diameter(shape.section, shape.width, shape.height),
                      "neighbouring roots of the grid") for pitch in pitches]
        else:
            pairs = self._list_root_gaps()
        if not pairs:
            return
        gap, which = min(pairs)
        largest = max(gap, 0.0) / (2.0 * math.sqrt(2.0))
        if self.root_jitter > largest:
            # shown rounded down to 4 significant digits: a value as shown is allowed
            scale = 10.0 ** (3 - math.floor(math.log10(largest))) if largest else 1.0
            shown = math.floor(largest * scale) / scale
            raise ValueError(
                f"root_jitter {self.root_jitter:g} mm could push {which} into each other "
                f"(their sections' circles {gap:.4g} mm apart close by up to 2√2 x "
                f"root_jitter): keep it at most {shown:.4g} mm")

    def _list_root_gaps(self) -> list[tuple[float, str]]:
        """(gap between the circles around the two sections [mm], the pair's names) of
        each pair of list entries near enough to matter."""
        from exubrush.util.pair_search import pairs_within

        roots = [(entry.x, entry.y) for entry in self.bristles]
        sizes = [section_diameter(e.section, e.width, e.height) for e in self.bristles]
        reach = max(sizes) + 2.0 * math.sqrt(2.0) * self.root_jitter
        gaps = []
        for i, j in pairs_within(roots, reach).tolist():
            gap = math.dist(roots[i], roots[j]) - 0.5 * (sizes[i] + sizes[j])
            gaps.append((gap, f"the roots of bristles[{min(i, j)}] and "
                              f"bristles[{max(i, j)}]"))
        return gaps

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
