"""Where the filaments of a tuft stand inside the tuft's circle (pure, mm units).

Two packings (docs/tufts.md):

- ``hexagonal``: filament centres on a hexagonal lattice of pitch p (the filament's outer
  diameter, so neighbours touch, as they do in a tuft), the ``n`` lattice points nearest to
  the tuft's centre. n = 1, 7, 19, 37, 61 fill whole rings (3k(k+1) + 1).
- ``random``: random sequential addition: seeded uniform candidates inside the circle,
  each kept if it keeps a distance p from every filament kept before. Its densest packings
  stay well below the hexagonal one (jamming near 55 % of the area), so a tuft that is
  full in hexagonal packing does not fit in random packing.
"""

from __future__ import annotations

import math

import numpy as np

# rounding allowed when a filament's circle touches the tuft's circle or a neighbour [mm]
FIT_TOLERANCE = 1e-9
# candidates drawn per filament before random packing gives up, in batches of
RANDOM_ATTEMPTS = 20_000
RANDOM_BATCH = 500
# largest share of the tuft's area its filaments may cover in random packing: random
# sequential addition of disks jams near 0.547 in the plane (Feder 1980), less in a circle
RANDOM_FILL = 0.5


class PackingError(ValueError):
    """The filaments do not fit in their tuft; the message says by how much."""


def hexagonal_offsets(count: int, pitch: float) -> np.ndarray:
    """The ``count`` points of a hexagonal lattice of ``pitch`` [mm] nearest to the origin,
    shape (count, 2), ordered by distance (ties by angle from the x axis), so that the first
    1, 7, 19, ... form whole rings."""
    if count < 1 or pitch <= 0:
        raise ValueError(f"need count >= 1 and pitch > 0, got {count} and {pitch}")
    rings = 1
    while 3 * rings * (rings + 1) + 1 < count:
        rings += 1
    rings += 1  # one more ring: the nearest points of a partial ring may lie beyond it
    i, j = np.meshgrid(np.arange(-rings, rings + 1), np.arange(-rings, rings + 1))
    points = np.column_stack([(i + 0.5 * j).ravel(), (j * math.sqrt(3.0) / 2.0).ravel()])
    distance = np.round(np.hypot(points[:, 0], points[:, 1]), 9)
    angle = np.round(np.mod(np.arctan2(points[:, 1], points[:, 0]), 2.0 * math.pi), 9)
    order = np.lexsort((angle, distance))
    return pitch * points[order[:count]]


def hexagonal_diameter(count: int, pitch: float) -> float:
    """Smallest tuft diameter [mm] that holds ``count`` filaments of outer diameter
    ``pitch`` in hexagonal packing."""
    offsets = hexagonal_offsets(count, pitch)
    return 2.0 * float(np.hypot(offsets[:, 0], offsets[:, 1]).max()) + pitch


def random_offsets(count: int, pitch: float, diameter: float,
                   rng: np.random.Generator) -> np.ndarray:
    """``count`` filament centres [mm], shape (count, 2), placed by random sequential
    addition inside a tuft of ``diameter``: no two closer than ``pitch``, every filament
    inside the circle.

    Raises
    ------
    PackingError
        If the filaments would cover more of the tuft than random packing can
        (RANDOM_FILL), or a filament finds no place in RANDOM_ATTEMPTS candidates.
    """
    room = 0.5 * (diameter - pitch)
    if room < -FIT_TOLERANCE:
        raise PackingError(f"a filament of {pitch:g} mm does not fit in a tuft of "
                           f"{diameter:g} mm")
    fill = count * pitch**2 / diameter**2
    if fill > RANDOM_FILL:
        raise PackingError(
            f"{count} filaments of {pitch:g} mm would cover {fill:.0%} of a {diameter:g} mm "
            f"tuft; random packing reaches at most about {RANDOM_FILL:.0%}: widen the tuft, "
            "use fewer filaments or packing 'hexagonal'")
    room = max(room, 0.0)
    kept = np.empty((0, 2))
    for _ in range(count):
        for _batch in range(RANDOM_ATTEMPTS // RANDOM_BATCH):
            radius = room * np.sqrt(rng.uniform(size=RANDOM_BATCH))
            angle = rng.uniform(0.0, 2.0 * math.pi, size=RANDOM_BATCH)
            candidates = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
            if len(kept):
                gaps = np.linalg.norm(candidates[:, None, :] - kept[None, :, :], axis=2)
                free = np.flatnonzero(gaps.min(axis=1) >= pitch - FIT_TOLERANCE)
            else:
                free = np.array([0])
            if len(free):
                kept = np.vstack([kept, candidates[free[0]]])
                break
        else:
            raise PackingError(
                f"random packing placed {len(kept)} of {count} filaments of {pitch:g} mm in a "
                f"tuft of {diameter:g} mm: widen the tuft, use fewer filaments or packing "
                "'hexagonal'")
    return kept


def filament_offsets(count: int, pitch: float, diameter: float, packing: str,
                     rng: np.random.Generator) -> np.ndarray:
    """Filament centres relative to the tuft's centre [mm], shape (count, 2).

    Raises
    ------
    PackingError
        If they do not fit in the tuft's ``diameter``.
    """
    if packing == "random":
        return random_offsets(count, pitch, diameter, rng)
    if packing != "hexagonal":
        raise ValueError(f"unknown packing {packing!r}")
    needed = hexagonal_diameter(count, pitch)
    if needed > diameter + FIT_TOLERANCE:
        raise PackingError(
            f"{count} filaments of {pitch:g} mm need a tuft of {needed:.4g} mm in hexagonal "
            f"packing, the tuft is {diameter:g} mm: widen it or use fewer filaments")
    return hexagonal_offsets(count, pitch)
