"""Mass properties of a bristle's pieces, and which piece rides on the handle (pure,
mm-t units).

Each model clamps its bristle to the handle some way along it: the DFM at its first
spring-damper, half a segment from the root (exubrush.models.dfm), the PRB at the
characteristic pivot (exubrush.models.prb). The piece from the root to there is part of
the handle, the prescribed body, and in no body of the Exudyn system: its mass enters no
drive reaction, so the head's force and moment add its inertia
(exubrush.output.assemble.carried_root_pieces).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from exubrush.models.geometry import BristleGeometry
    from exubrush.models.sections import SectionProperties


def slice_moments(section: SectionProperties, density: float,
                  length: float) -> tuple[float, np.ndarray]:
    """Mass [t] and principal moments of inertia about the centre [t·mm²], (3,) along the
    bristle's x, y, z, of a prismatic slice ``length`` [mm] long: ρL·J about x (J the
    section's polar moment), ρL·I_y + mL²/12 about y, ρL·I_z + mL²/12 about z."""
    mass = density * section.area * length
    return mass, np.array([
        density * length * section.polar_moment,
        density * length * section.second_moment_y + mass * length**2 / 12.0,
        density * length * section.second_moment_z + mass * length**2 / 12.0,
    ])


def dfm_root_piece(length: float, segments: int) -> float:
    """Length [mm] of a DFM bristle ``length`` [mm] long in ``segments`` that rides on the
    handle: the half segment from the root to the first spring-damper."""
    return 0.5 * (length / segments)


def prb_root_piece(length: float, gamma: float) -> float:
    """Length [mm] of a PRB bristle ``length`` [mm] long that rides on the handle: the
    stub (1 - γ)l from the root to the characteristic pivot."""
    return length - gamma * length


def root_piece_inertia(bristle: BristleGeometry, density: float,
                       length: float) -> tuple[float, np.ndarray, np.ndarray]:
    """The bristle's first ``length`` [mm] from its root as a rigid body on the handle:
    its mass m [t], first moment m c about the head frame's origin (the handle's node)
    [t·mm] and inertia about that origin [t·mm²], in the head frame's axes: the slice's
    (:func:`slice_moments`) turned into the bristle's frame and moved to its centre c, at
    ``length``/2 along the bristle (parallel axes: + m (|c|² E − c cᵀ))."""
    mass, moments = slice_moments(bristle.section, density, length)
    frame = np.asarray(bristle.frame, dtype=float)
    centre = bristle.point(0.5 * length)
    inertia = (frame @ np.diag(moments) @ frame.T
               + mass * (float(centre @ centre) * np.eye(3) - np.outer(centre, centre)))
    return mass, mass * centre, inertia
