"""What a brush cleans: contact, wiped area, force share and gap penetration (pure).

Computed after a run from each tip's centre and contact force at the force interval
(``Results.tip_position``, ``Results.tip_force``), in the surface frame
(exubrush.world.surfaces). Definitions:

- **In contact**: the tip's contact force exceeds :data:`NO_CONTACT_FORCE`. Its contact
  point is the point of the nearest surface feature below the centre, c − r n; its
  *part* names where it lies (a tooth row: ``top``, ``edge`` (the rounding), ``wall``,
  ``floor``; other surfaces: ``surface``).
- **Strokes**: the slide cut at its reversals, every moving span, the first (from the
  approach) and a last one cut off by the end of the run included and flagged ``whole =
  false``.
- **Wiped area** of a stroke: the cells of a square grid of side ``grid`` [mm] in the
  surface frame's x-y plane that a contact patch swept (the circle in which the tip
  sphere cuts the face, radius √(2rδ − δ²); consecutive in-contact samples of a tip joined
  by a straight path), times the cell area: an area projected on that plane, so a wall of
  a tooth wipes (almost) none.
- **Force share** of a bristle in a stroke: its normal contact force (along the feature's
  normal) integrated over the stroke, over the same for the whole head; its spread is the
  coefficient of variation (standard deviation / mean) over the bristles of the head.
- **Interdental penetration** (tooth row): a tip is in a gap when its centre lies over the
  gap (|u| > w/2, exubrush.world.surfaces.fold) and its lowest point below the tooth tops; its
  depth is how far below the tops that point is [mm]. Per stroke and gap: the deepest tip
  and every tip's deepest; the time tips spent in gaps [tip-seconds].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from exubrush.output.metrics import NO_CONTACT_FORCE
from exubrush.parameters.surface_kinds import TOOTH_ROW
from exubrush.util.float_math import ARRAY_MATH
from exubrush.world.surfaces import (
    features,
    fold,
    orientation,
    resolve,
    to_surface_frame,
    tooth_pitch,
)

if TYPE_CHECKING:
    from exubrush.parameters.case import Surface

# mm: side of a wiped-area cell, a fifth of the patch width of a default tip pressed in by
# 2.5 µm (about 0.1 N: 2·√(2·0.4·0.0025) = 0.09 mm)
DEFAULT_GRID = 0.02
PARTS = {TOOTH_ROW: ("top", "edge", "wall", "floor")}


def part_names(surface: Surface) -> tuple[str, ...]:
    """Names of the surface's parts, indexed by :func:`contact_geometry`'s part codes."""
    return PARTS.get(surface.kind, ("surface",))


def contact_geometry(surface: Surface, centres: np.ndarray, radius: np.ndarray, mesh=None):
    """Contact point, outward normal and part code of tip spheres on ``surface``.

    Parameters
    ----------
    centres : ndarray (..., n_bristles, 3)
        Tip centres, head frame fixed to the surface [mm].
    radius : ndarray (n_bristles,)
        Tip radii [mm].
    mesh : exubrush.world.mesh.MeshSurface, optional
        The surface's mesh (surface.kind "mesh").

    Returns
    -------
    points, normals : ndarray (..., n_bristles, 3)
        Contact point [mm] and unit normal, surface frame, of the nearest feature.
    distances : ndarray (..., n_bristles)
        Signed distance of the centre from that feature [mm].
    parts : ndarray (..., n_bristles) of int
        Index into :func:`part_names`.
    """
    local = to_surface_frame(surface, centres)
    shape = local.shape[:-1]
    flat = local.reshape(-1, 3)
    radii = np.broadcast_to(radius, shape).reshape(-1)
    if mesh is not None:
        _, normals, distance = mesh.closest_many(flat)
        points = flat - radii[:, None] * normals
        return (points.reshape(*shape, 3), normals.reshape(*shape, 3), distance.reshape(shape),
                np.zeros(shape, dtype=int))
    found = [resolve(f, ARRAY_MATH) for f in features(surface, flat.T, float(radii.max()),
                                                      ARRAY_MATH)]
    distance = np.stack([np.broadcast_to(f.distance, radii.shape) for f in found])
    nearest = np.argmin(distance, axis=0)
    rows = np.arange(radii.size)
    normals = np.stack([np.stack([np.broadcast_to(c, radii.shape) for c in f.normal], axis=1)
                        for f in found])[nearest, rows]
    points = flat - radii[:, None] * normals
    parts = _parts(surface, points)
    return (points.reshape(*shape, 3), normals.reshape(*shape, 3),
            distance[nearest, rows].reshape(shape), parts.reshape(shape))


@dataclass(frozen=True)
class TipContacts:
    """Where each tip touches, per sample (:func:`touching_geometry`); each (n_t, n_b, ...).

    Attributes
    ----------
    touching : ndarray of bool
        Contact force above :data:`NO_CONTACT_FORCE`.
    points, normals : ndarray (..., 3)
        Contact point [mm] and outward unit normal, surface frame (0 where not touching).
    distances : ndarray
        Signed distance of the tip's centre from the touched feature [mm] (r elsewhere).
    parts : ndarray of int
        Index into :func:`part_names` (0 where not touching).
    """

    touching: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    distances: np.ndarray
    parts: np.ndarray


def touching_geometry(surface: Surface, tip_position, tip_force, radius,
                      mesh=None) -> TipContacts:
    """:func:`contact_geometry` of the samples where the tips touch (the rest stays empty):
    computed once per run, it serves the summary, tips.npz and the footprint."""
    touching = np.linalg.norm(tip_force, axis=2) > NO_CONTACT_FORCE
    radius = np.asarray(radius, dtype=float)
    shape = touching.shape
    points, normals = np.zeros((*shape, 3)), np.zeros((*shape, 3))
    distances = np.broadcast_to(radius, shape).copy()
    parts = np.zeros(shape, dtype=int)
    if touching.any():
        rows, columns = np.nonzero(touching)
        found = contact_geometry(surface, np.asarray(tip_position)[rows, columns][:, None, :],
                                 radius[columns][:, None], mesh)
        points[rows, columns] = found[0][:, 0]
        normals[rows, columns] = found[1][:, 0]
        distances[rows, columns] = found[2][:, 0]
        parts[rows, columns] = found[3][:, 0]
    return TipContacts(touching, points, normals, distances, parts)


def sample_durations(time) -> np.ndarray:
    """The time each sample stands for [s] (np.gradient of the sample times)."""
    time = np.asarray(time, dtype=float)
    return np.gradient(time) if len(time) > 1 else np.zeros_like(time)


def _parts(surface: Surface, points: np.ndarray) -> np.ndarray:
    if surface.kind != TOOTH_ROW:
        return np.zeros(len(points), dtype=int)
    u = np.abs(fold(surface, points[:, 0], ARRAY_MATH))
    z = points[:, 2]
    flat_top = 0.5 * surface.tooth_width - surface.edge_radius
    tolerance = 1e-9 + 1e-3 * surface.edge_radius  # [mm] the contact point is on the surface
    floor = z < -surface.gap_depth + tolerance
    top = (u <= flat_top) & ~floor
    edge = (u > flat_top) & (z > -surface.edge_radius - tolerance) & ~floor
    return np.select([top, edge, floor], [0, 1, 3], default=2)


def stroke_spans(time: np.ndarray, slider_position: np.ndarray) -> list[tuple[int, int, bool]]:
    """Every moving span of the slide as (first sample, last sample, whole): cut where the
    slide's direction changes; ``whole`` if it runs from one reversal to the next."""
    velocity = np.gradient(slider_position, time) if len(time) > 1 else np.zeros_like(time)
    speed = np.abs(velocity)
    if speed.size == 0 or speed.max() == 0.0:
        return []
    direction = np.where(speed > 1e-9 * speed.max(), np.sign(velocity), 0).astype(int)
    edges = np.flatnonzero(np.diff(direction) != 0) + 1
    moving = [seg for seg in np.split(np.arange(time.size), edges)
              if direction[seg[0]] != 0 and seg.size >= 2]
    spans = []
    for k, segment in enumerate(moving):
        whole = 0 < k < len(moving) - 1
        spans.append((int(segment[0]), int(segment[-1]), whole))
    return spans


def wiped_cells(points: np.ndarray, touching: np.ndarray, half_width: np.ndarray,
                grid: float) -> np.ndarray:
    """Grid cells of side ``grid`` [mm] that the contact patches swept.

    ``points`` (n_t, n_b, 3) are contact points (x, y used), ``touching`` (n_t, n_b) where
    the tips touch and ``half_width`` (n_t, n_b) the radius of each contact patch [mm].
    Consecutive touching samples of a tip are joined by a straight path sampled every
    grid/2 (radius interpolated); a cell counts if its centre lies in a patch or a patch's
    centre lies in it. Returns the unique cells as rows (i, j).
    """
    xs, ys, radii = [], [], []
    for b in range(points.shape[1]):
        on = np.flatnonzero(touching[:, b])
        if on.size == 0:
            continue
        path, width = points[:, b, :2], half_width[:, b]
        xs.append(path[on, 0])
        ys.append(path[on, 1])
        radii.append(width[on])
        followed = on[on + 1 < len(path)]
        joined = followed[touching[followed + 1, b]]
        steps = np.ceil(2.0 * np.linalg.norm(path[joined + 1] - path[joined], axis=1)
                        / grid).astype(int)
        inner = np.maximum(steps - 1, 0)  # points strictly between the two samples
        start = np.repeat(joined, inner)
        rank = np.arange(inner.sum()) - np.repeat(np.cumsum(inner) - inner, inner) + 1
        s = (rank / np.repeat(np.maximum(steps, 1), inner))[:, None]
        between = path[start] + s * (path[start + 1] - path[start])
        xs.append(between[:, 0])
        ys.append(between[:, 1])
        radii.append(width[start] + s[:, 0] * (width[start + 1] - width[start]))
    if not xs:
        return np.zeros((0, 2), dtype=np.int64)
    x, y, r = np.concatenate(xs), np.concatenate(ys), np.concatenate(radii)
    reach = int(np.ceil(r.max() / grid)) + 1
    i0, j0 = np.floor(x / grid).astype(np.int64), np.floor(y / grid).astype(np.int64)
    keys = [_cell_key(i0, j0)]
    # widest patches first: a cell di, dj away from a point's own is at least
    # (|di| - 1/2, |dj| - 1/2) cells from it, so only the patches wider than that are tested
    # (the same test on fewer points; a 1e-12 margin keeps round-off on the safe side)
    order = np.argsort(-r, kind="stable")
    x, y, r, i0, j0 = x[order], y[order], r[order], i0[order], j0[order]
    for di in range(-reach, reach + 1):
        for dj in range(-reach, reach + 1):
            nearest = grid * np.hypot(max(abs(di) - 0.5, 0.0), max(abs(dj) - 0.5, 0.0))
            n = int(np.searchsorted(-r, -nearest * (1.0 - 1e-12), side="right"))
            if n == 0:
                continue
            inside = (np.hypot((i0[:n] + di + 0.5) * grid - x[:n],
                               (j0[:n] + dj + 0.5) * grid - y[:n]) <= r[:n])
            keys.append(_distinct(_cell_key(i0[:n][inside] + di, j0[:n][inside] + dj)))
    unique = _distinct(np.concatenate(keys))
    return np.stack([unique >> 32, (unique & 0xFFFFFFFF) - 2**31], axis=1)


def _distinct(keys: np.ndarray) -> np.ndarray:
    """The distinct values of ``keys``, sorted (np.unique by sorting: NumPy 2.3's hashing
    np.unique took 0.7 s of a run's 1.1 s of wiped-area cells)."""
    keys = np.sort(keys)
    return keys[np.concatenate(([True], keys[1:] != keys[:-1]))] if keys.size else keys


def _cell_key(i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """One int64 per cell (i, j), |j| < 2³¹."""
    return (i << 32) + (j + 2**31)


def patch_radius(radius, distance) -> np.ndarray:
    """Radius of the circle in which a sphere of ``radius`` whose centre lies ``distance``
    from a face cuts it, √(2rδ − δ²) with δ = r − d [mm] (0 without overlap)."""
    depth = np.clip(radius - distance, 0.0, radius)
    return np.sqrt(2.0 * radius * depth - depth * depth)


def gap_depths(surface: Surface, centres_local: np.ndarray, radius: np.ndarray):
    """Depth below the tooth tops of each tip's lowest point while it is in a gap [mm]
    (0 elsewhere), the index k of the gap under the tip (between teeth k and k + 1, teeth
    counted from the one at the surface's origin) and whether the tip is in it."""
    x, z = centres_local[..., 0], centres_local[..., 2]
    u = fold(surface, x, ARRAY_MATH)
    depth = np.maximum(radius - z, 0.0)
    inside = (np.abs(u) > 0.5 * surface.tooth_width) & (depth > 0.0)
    gap = np.floor(x / tooth_pitch(surface)).astype(int)
    return np.where(inside, depth, 0.0), gap, inside


def cleaning_summary(surface: Surface, time, slider_position, tip_position, tip_force,
                     tip_radius, grid: float = DEFAULT_GRID, mesh=None,
                     contacts: TipContacts | None = None) -> dict:
    """The cleaning metrics of a run (see module docstring) as plain JSON-ready values.

    ``tip_position``, ``tip_force``: (n_t, n_bristles, 3), head frame fixed to the surface
    [mm, N]; ``tip_radius``: (n_bristles,) [mm]; ``grid``: wiped-area cell side [mm];
    ``mesh``: the surface's mesh if it is one; ``contacts``: their
    :func:`touching_geometry`, if already computed.
    """
    time = np.asarray(time, dtype=float)
    radius = np.asarray(tip_radius, dtype=float)
    if not grid > 0.0:
        raise ValueError(f"the wiped-area grid must be positive, got {grid!r} mm")
    if contacts is None:
        contacts = touching_geometry(surface, tip_position, tip_force, radius, mesh)
    touching, points, parts = contacts.touching, contacts.points, contacts.parts
    half_width = patch_radius(radius, contacts.distances)
    force_local = np.asarray(tip_force) @ orientation(surface)  # rows: Rᵀ f
    normal_force = np.einsum("tbi,tbi->tb", force_local, contacts.normals)
    names = part_names(surface)
    dt = sample_durations(time)
    summary = {
        "surface": surface.kind,
        "grid_mm": grid,
        "parts": list(names),
        "contact_time_per_part_tip_s": {
            name: float(np.sum(dt[:, None] * (touching & (parts == k))))
            for k, name in enumerate(names)},
        "strokes": [],
    }
    teeth = surface.kind == TOOTH_ROW
    if teeth:
        local = to_surface_frame(surface, tip_position)
        depth, gap, inside = gap_depths(surface, local, radius)
    for index, (first, last, whole) in enumerate(stroke_spans(time, slider_position)):
        rows = slice(first, last + 1)
        span_dt = dt[rows, None]
        count = touching[rows].sum(axis=1)
        pressed = np.sum(np.maximum(normal_force[rows], 0.0) * span_dt, axis=0)
        share = pressed / pressed.sum() if pressed.sum() > 0 else np.zeros_like(pressed)
        stroke = {
            "index": index,
            "start_s": float(time[first]),
            "end_s": float(time[last]),
            "whole": whole,
            "tips_in_contact_mean": float(count.mean()),
            "tips_in_contact_max": int(count.max()),
            "wiped_area_mm2": len(wiped_cells(points[rows], touching[rows], half_width[rows],
                                              grid)) * grid**2,
            "force_share": share.tolist(),
            "force_share_max": float(share.max()),
            "force_share_spread": float(share.std() / share.mean()) if share.mean() else 0.0,
        }
        if teeth:
            stroke["interdental"] = _interdental(depth[rows], gap[rows], inside[rows], span_dt)
        summary["strokes"].append(stroke)
    return summary


def _interdental(depth: np.ndarray, gap: np.ndarray, inside: np.ndarray,
                 dt: np.ndarray) -> dict:
    gaps = []
    for k in sorted(set(gap[inside].tolist())):
        per_tip = np.where(inside & (gap == k), depth, 0.0).max(axis=0)
        entered = per_tip > 0.0
        gaps.append({"gap": int(k), "max_depth_mm": float(per_tip.max()),
                     "tips_entered": int(entered.sum()),
                     "depths_mm": per_tip[entered].tolist()})
    return {
        "max_depth_mm": float(depth.max()) if depth.size else 0.0,
        "time_in_gaps_tip_s": float(np.sum(dt * inside)),
        "gaps": gaps,
    }


def footprint(time, contacts: TipContacts, cell: float):
    """Contact time per cell of side ``cell`` [mm] in the surface frame's x-y plane
    [tip-seconds], over the run: (counts (n_x, n_y), x edges, y edges)."""
    touching = contacts.touching
    weights = np.broadcast_to(sample_durations(time)[:, None], touching.shape)[touching]
    x, y = contacts.points[touching][:, 0], contacts.points[touching][:, 1]
    if x.size == 0:
        x, y, weights = np.zeros(1), np.zeros(1), np.zeros(1)
    bins = [np.arange(np.floor(v.min() / cell) * cell, v.max() + 1.5 * cell, cell)
            for v in (x, y)]
    counts, x_edges, y_edges = np.histogram2d(x, y, bins=bins, weights=weights)
    return counts, x_edges, y_edges


def gap_depth_history(surface: Surface, tip_position, tip_radius) -> np.ndarray:
    """Deepest tip in a gap at each sample [mm] (0 when none is; tooth rows only)."""
    local = to_surface_frame(surface, tip_position)
    depth, _, _ = gap_depths(surface, local, np.asarray(tip_radius, dtype=float))
    return depth.max(axis=1)
