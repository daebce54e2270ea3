"""Where each bristle of a head sits and how it is oriented (pure, mm units).

Symmetry breaking (docs/model.md; measured in docs/decisions/0004): a perfectly
straight, perfectly aligned bristle pressed onto a plane cannot choose a side to escape to
at a stroke reversal, and the solver jams. Each root is therefore tilted by
``Head.root_tilt`` (default 0.5°) about a horizontal axis whose direction is drawn from a
seeded uniform distribution, so two runs with the same seed are identical and
``root_tilt = 0`` restores the ideal head. The filaments of a tuft share one direction, so
that filaments packed side by side start parallel instead of leaning into each other.
``Head.tilt_pattern = "radial"`` tilts every root away from the head's centre instead: a
round head then stays symmetric under its turns, and filaments the same distance from
the centre are twins under them (exubrush.run.twins).

Imperfections of a real head (docs/model.md, "Imperfections of a real head"; all zero by
default, the ideal head): each bristle's tilts about x and y, free length and root x, y
deviate by a uniform draw within ``head.tilt_spread_x``, ``tilt_spread_y``,
``length_spread`` (a fraction of the length) and ``root_jitter``, and the whole head is
turned by ``head.misalign_x`` then ``misalign_y`` about its centre on the roots' surface.
Each quantity has its own stream of unit draws u in [-1, 1) from ``head.seed`` (apart from
the root tilts' and the packings' streams), scaled by its half-width: switching one on
leaves the others' draws and the root-tilt directions as they were, and the same seed at
twice the spread gives twice the deviations.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from exubrush.models.packing import PackingError, filament_offsets
from exubrush.models.sections import SectionProperties, section_properties
from exubrush.parameters.head import BristleEntry, Head, Material, section_diameter
from exubrush.util.pair_search import pairs_within

# a root this close to the head's centre [mm] has no direction away from it (tilt_pattern
# "radial"): it tilts in its random direction
RADIAL_CENTRE = 1e-9
# bristle frame (x root->tip, y along the head, z = x × y) in the head frame, untilted
UPRIGHT_FRAME = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])


def rotation_about(axis: ArrayLike, angle: float) -> np.ndarray:
    """Rotation matrix for ``angle`` [rad] about unit vector ``axis`` (Rodrigues)."""
    u = np.asarray(axis, dtype=float)
    u = u / np.linalg.norm(u)
    skew = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    return np.eye(3) + np.sin(angle) * skew + (1.0 - np.cos(angle)) * skew @ skew


@dataclass(frozen=True)
class BristleGeometry:
    """One bristle, resolved.

    Attributes
    ----------
    root : ndarray (3,)
        Root position in the head frame, on the roots' surface Z = 0 of the handle [mm]
        (off it by the misalignment of an imperfect head).
    frame : ndarray (3, 3)
        Columns: the bristle's x (root to tip), y and z axes in the head frame.
    length, tip_radius : float
        Free length to the tip-sphere centre and sphere radius [mm].
    section : SectionProperties
        Section of the bristle.
    width, height : float
        Section extents along the bristle's y and z [mm] (for inertia and drawing).
    shape : str
        Section shape name.
    material : Material
        The bristle's material (the head's, or its tuft's).
    tuft : int or None
        Index of the tuft in ``head.tufts`` the bristle is a filament of (None outside a
        tuft layout).
    """

    root: np.ndarray
    frame: np.ndarray
    length: float
    tip_radius: float
    section: SectionProperties
    width: float
    height: float
    shape: str
    material: Material = Material()
    tuft: int | None = None

    def point(self, s: float) -> np.ndarray:
        """Head-frame position of the undeformed centreline at arc length ``s`` [mm]."""
        return self.root + s * self.frame[:, 0]

    @property
    def outer_radius(self) -> float:
        """Radius of the smallest cylinder around the bristle's section and tip sphere [mm]."""
        return max(0.5 * section_diameter(self.shape, self.width, self.height),
                   self.tip_radius)

    @property
    def lowest_reach(self) -> float:
        """Z of the tip sphere's lowest point relative to the roots' surface, upright [mm]."""
        return float(self.point(self.length)[2] - self.tip_radius)


@dataclass(frozen=True)
class Imperfections:
    """The deviations drawn for an imperfect head (module docstring), per bristle.

    Attributes
    ----------
    tilt_x, tilt_y : ndarray (n,)
        Added to the bristle's tilt about the head's x and y axes [rad] (a tuft's
        filaments share their tuft's).
    length_factor : ndarray (n,)
        The free length's factor 1 + length_spread u [-].
    offset : ndarray (n, 2)
        Added to the root's x and y [mm].
    """

    tilt_x: np.ndarray
    tilt_y: np.ndarray
    length_factor: np.ndarray
    offset: np.ndarray


def imperfections(head: Head, tufts: list[int | None]) -> Imperfections:
    """The deviations of a head whose bristles belong to ``tufts`` (each bristle's tuft
    index, None outside a tuft layout): zeros, and factors of exactly 1, for zero spreads."""
    count = len(tufts)

    def unit_draws(stream: int, size: int) -> np.ndarray:
        return np.random.default_rng([head.seed, 2, stream]).uniform(-1.0, 1.0, size)

    if head.layout == "tufts":  # a tuft tilts as one: its filaments start parallel
        index = np.array(tufts, dtype=int)
        tilt_x = unit_draws(0, len(head.tufts))[index]
        tilt_y = unit_draws(1, len(head.tufts))[index]
    else:
        tilt_x, tilt_y = unit_draws(0, count), unit_draws(1, count)
    return Imperfections(
        tilt_x=head.tilt_spread_x * tilt_x,
        tilt_y=head.tilt_spread_y * tilt_y,
        length_factor=1.0 + head.length_spread * unit_draws(2, count),
        offset=head.root_jitter * np.column_stack([unit_draws(3, count),
                                                   unit_draws(4, count)]),
    )


def misalignment(head: Head) -> np.ndarray | None:
    """The whole head's turn (3, 3): about x by ``misalign_x``, then about y by
    ``misalign_y``, in the head frame; None for an aligned head."""
    if head.misalign_x == 0.0 and head.misalign_y == 0.0:
        return None
    return (rotation_about([1.0, 0.0, 0.0], head.misalign_x)
            @ rotation_about([0.0, 1.0, 0.0], head.misalign_y))


def can_reach(bristle: BristleGeometry, interaction_distance: float) -> bool:
    """Coarse reach test: a tip touches the plane only if d < l + r (any tilt) [mm]."""
    return interaction_distance < bristle.length + bristle.tip_radius


def touching_groups(bristles: list[BristleGeometry]) -> tuple[tuple[int, ...], ...]:
    """Bristles that can touch each other, directly or through others: the connected
    components of the graph whose edges join bristles closer at the root than their
    lengths and outer radii together (a bristle never leaves the ball of its length around
    its root, so no pair outside it can ever touch, whatever the motion). Each group's
    indices ascend; groups are ordered by their first index."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    roots = np.array([b.root for b in bristles])
    reach = np.array([b.length + b.outer_radius for b in bristles])
    pairs = pairs_within(roots, 2.0 * reach.max())
    if len(pairs):
        gaps = np.linalg.norm(roots[pairs[:, 0]] - roots[pairs[:, 1]], axis=1)
        pairs = pairs[gaps < reach[pairs[:, 0]] + reach[pairs[:, 1]]]
    count = len(bristles)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])) if len(pairs)
                       else (np.zeros(0), (np.zeros(0, int), np.zeros(0, int))),
                       shape=(count, count))
    _, labels = connected_components(graph, directed=False)
    groups: dict[int, list[int]] = {}
    for index, label in enumerate(labels):
        groups.setdefault(int(label), []).append(index)
    return tuple(sorted((tuple(g) for g in groups.values()), key=lambda g: g[0]))


def _entries(head: Head) -> list[tuple[BristleEntry, Material, int | None]]:
    """(entry, material, tuft index) of every bristle, in order."""
    if head.layout == "tufts":
        return _filaments(head)
    if head.layout == "list":
        return [(entry, head.material, None) for entry in head.bristles]
    shape = head.bristle
    entries: list[tuple[BristleEntry, Material, int | None]] = []
    for i in range(head.rows):
        for j in range(head.columns):
            entries.append((
                BristleEntry(
                    x=(j - (head.columns - 1) / 2.0) * head.pitch_along,
                    y=(i - (head.rows - 1) / 2.0) * head.pitch_across,
                    length=shape.length,
                    section=shape.section,
                    width=shape.width,
                    height=shape.height,
                    tip_radius=shape.tip_radius,
                ), head.material, None))
    return entries


def _filaments(head: Head) -> list[tuple[BristleEntry, Material, int | None]]:
    """Every filament of every tuft, its root from exubrush.models.packing.

    Raises
    ------
    ValueError
        Naming the tuft whose filaments do not fit in it.
    """
    rng = np.random.default_rng([head.seed, 1])  # apart from the root tilts' stream
    entries: list[tuple[BristleEntry, Material, int | None]] = []
    for index, (name, tuft) in enumerate(zip(head.tuft_names(), head.tufts, strict=True)):
        try:
            offsets = filament_offsets(tuft.filaments, tuft.filament_diameter, tuft.diameter,
                                       tuft.packing, rng)
        except PackingError as err:
            raise ValueError(f"head: {name}: {err}") from None
        material = head.tuft_material(tuft)
        for dx, dy in offsets:
            entries.append((BristleEntry(
                x=tuft.x + dx, y=tuft.y + dy, tilt_x=tuft.tilt_x, tilt_y=tuft.tilt_y,
                length=tuft.length, section=tuft.section, width=tuft.width,
                height=tuft.height, tip_radius=tuft.tip_radius), material, index))
    return entries


def head_bristles(head: Head) -> list[BristleGeometry]:
    """Resolve the head's layout into bristle geometries, perturbations included.

    Raises
    ------
    ValueError
        If a tuft's filaments do not fit in it (the message names the tuft).
    """
    rng = np.random.default_rng(head.seed)
    bristles = []
    tuft_directions: dict[int, float] = {}
    entries = _entries(head)
    drawn = imperfections(head, [tuft for _, _, tuft in entries])
    turn = misalignment(head)
    for k, (entry, material, tuft) in enumerate(entries):
        upright = UPRIGHT_FRAME
        # the filaments of a tuft share one direction: they start parallel, as they touch
        direction = (rng.uniform(0.0, 2.0 * np.pi) if tuft is None
                     else tuft_directions.setdefault(tuft, rng.uniform(0.0, 2.0 * np.pi)))
        if head.tilt_pattern == "radial" and np.hypot(entry.x, entry.y) > RADIAL_CENTRE:
            # about the tangent of the root's circle around the centre, the tip leaning
            # out; the section turned with the root's polar angle, so that the whole frame
            # turns with the head's symmetry
            polar = float(np.arctan2(entry.y, entry.x))
            direction = polar - 0.5 * np.pi
            upright = rotation_about([0.0, 0.0, 1.0], polar) @ UPRIGHT_FRAME
        frame = (
            rotation_about([1.0, 0.0, 0.0], entry.tilt_x + drawn.tilt_x[k])
            @ rotation_about([0.0, 1.0, 0.0], entry.tilt_y + drawn.tilt_y[k])
            @ upright
        )
        if head.root_tilt > 0.0:
            tilt_axis = np.array([np.cos(direction), np.sin(direction), 0.0])
            frame = rotation_about(tilt_axis, head.root_tilt) @ frame
        root = np.array([entry.x + drawn.offset[k, 0], entry.y + drawn.offset[k, 1], 0.0])
        if turn is not None:
            root, frame = turn @ root, turn @ frame
        bristles.append(
            BristleGeometry(
                root=root,
                frame=frame,
                length=entry.length * float(drawn.length_factor[k]),
                tip_radius=entry.tip_radius,
                section=section_properties(entry.section, entry.width, entry.height),
                width=entry.width,
                height=entry.height,
                shape=entry.section,
                material=material,
                tuft=tuft,
            )
        )
    return bristles
