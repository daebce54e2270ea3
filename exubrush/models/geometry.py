"""Where each bristle of a head sits and how it is oriented (pure, mm units).

Symmetry breaking (docs/model.md; measured in validation/benchmarks/README.md): a perfectly
straight, perfectly aligned bristle pressed onto a plane cannot choose a side to escape to
at a stroke reversal, and the solver jams. Each root is therefore tilted by
``Head.root_tilt`` (default 0.5°) about a horizontal axis whose direction is drawn from a
seeded uniform distribution, so two runs with the same seed are identical and
``root_tilt = 0`` restores the ideal head.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exubrush.models.sections import SectionProperties, section_properties
from exubrush.parameters.case import BristleEntry, Head

# bristle frame (x root->tip, y along the head, z = x × y) in the head frame, untilted
UPRIGHT_FRAME = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]])


def rotation_about(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation matrix for ``angle`` [rad] about unit vector ``axis`` (Rodrigues)."""
    axis = np.asarray(axis, dtype=float)
    axis = axis / np.linalg.norm(axis)
    skew = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + np.sin(angle) * skew + (1.0 - np.cos(angle)) * skew @ skew


@dataclass(frozen=True)
class BristleGeometry:
    """One bristle, resolved.

    Attributes
    ----------
    root : ndarray (3,)
        Root position in the head frame, on the roots' surface Z = 0 of the handle [mm].
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
    """

    root: np.ndarray
    frame: np.ndarray
    length: float
    tip_radius: float
    section: SectionProperties
    width: float
    height: float
    shape: str

    def point(self, s: float) -> np.ndarray:
        """Head-frame position of the undeformed centreline at arc length ``s`` [mm]."""
        return self.root + s * self.frame[:, 0]

    @property
    def lowest_reach(self) -> float:
        """Z of the tip sphere's lowest point relative to the roots' surface, upright [mm]."""
        return float(self.point(self.length)[2] - self.tip_radius)


def can_reach(bristle: BristleGeometry, interaction_distance: float) -> bool:
    """Coarse reach test: a tip touches the plane only if d < l + r (any tilt) [mm]."""
    return interaction_distance < bristle.length + bristle.tip_radius


def _entries(head: Head) -> list[BristleEntry]:
    if head.layout == "list":
        return list(head.bristles)
    shape = head.bristle
    entries = []
    for i in range(head.rows):
        for j in range(head.columns):
            entries.append(
                BristleEntry(
                    x=(j - (head.columns - 1) / 2.0) * head.pitch_along,
                    y=(i - (head.rows - 1) / 2.0) * head.pitch_across,
                    length=shape.length,
                    section=shape.section,
                    width=shape.width,
                    height=shape.height,
                    tip_radius=shape.tip_radius,
                )
            )
    return entries


def head_bristles(head: Head) -> list[BristleGeometry]:
    """Resolve the head's layout into bristle geometries, perturbations included."""
    rng = np.random.default_rng(head.seed)
    bristles = []
    for entry in _entries(head):
        frame = (
            rotation_about([1.0, 0.0, 0.0], entry.tilt_x)
            @ rotation_about([0.0, 1.0, 0.0], entry.tilt_y)
            @ UPRIGHT_FRAME
        )
        direction = rng.uniform(0.0, 2.0 * np.pi)
        if head.root_tilt > 0.0:
            tilt_axis = np.array([np.cos(direction), np.sin(direction), 0.0])
            frame = rotation_about(tilt_axis, head.root_tilt) @ frame
        bristles.append(
            BristleGeometry(
                root=np.array([entry.x, entry.y, 0.0]),
                frame=frame,
                length=entry.length,
                tip_radius=entry.tip_radius,
                section=section_properties(entry.section, entry.width, entry.height),
                width=entry.width,
                height=entry.height,
                shape=entry.section,
            )
        )
    return bristles
