"""Rigid surfaces the tip spheres brush: plane, cylinder, sphere and tooth row (pure geometry).

Every surface is described in its own frame (x, y, z): its highest point is the origin and
z points out of it, towards the head (``exubrush.parameters.case.Surface`` places the frame
in the head frame). A surface is a union of convex parts, its *features*; for a point p
each feature gives

- the signed distance d(p) of p from the feature's boundary [mm], positive outside, and
- the unit outward normal n(p) at the boundary point closest to p (the gradient of d),

so a sphere of radius r centred at p penetrates the feature by δ = r − d along n. The
contact law acts on every feature a tip penetrates, independently (exubrush.contact.laws):
a sphere in a narrow gap, or in the corner between a tooth's wall and the gap's floor,
touches two features at once and feels both. At a convex rounded edge the normal turns
smoothly with the closest point; the surface itself has no sharp convex edge.

The functions are written once against a math back end ``m`` (exubrush.util.float_math): on
floats, element-wise on numpy arrays, or on Exudyn's symbolic expressions, which records
them into the C++ contact user function.

Features of each kind, in the surface frame:

- ``plane``: z = 0.
- ``cylinder``: axis along y through (0, 0, −R): d = √(x² + (z+R)²) − R.
- ``sphere``: centre (0, 0, −R): d = √(x² + y² + (z+R)²) − R.
- ``tooth-row``: teeth of crown width w centred at x = kP (pitch P = w + g, gap width g),
  each a 2D rounded rectangle (top z = 0, top edges of radius ρ, walls down to the floor)
  extruded along y, and the gaps' floor, the plane z = −h. The point's x is folded into
  the period around the nearest tooth, u = x − P·floor(x/P + 1/2); the neighbour tooth
  across the gap is a feature only if the sphere is wider than the gap (2r > g), the only
  case in which it can touch both teeth at once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from exubrush.parameters.surface_kinds import CYLINDER, PLANE, SPHERE, TOOTH_ROW
from exubrush.util.float_math import ARRAY_MATH, FLOAT_MATH

if TYPE_CHECKING:  # only attributes are read: no import at run time
    from exubrush.parameters.case import Surface

# guards a division by a distance that is exactly zero only where the result is unused
_TINY = 1e-300


@dataclass(frozen=True)
class Feature:
    """One convex part's outward unit normal (3 numbers or expressions) and the signed
    distance of the point from it [mm]. A plain-number normal lets the contact law drop
    the terms it multiplies by zero."""

    normal: tuple
    distance: Any


@dataclass(frozen=True)
class Choice:
    """A feature whose formula depends on where the point is: ``if_true`` where
    ``condition`` holds, else ``if_false`` (each a Feature or a Choice). Exudyn evaluates
    only the branch taken, so each region costs only its own formula."""

    condition: Any
    if_true: Feature | Choice
    if_false: Feature | Choice


def features(surface: Surface, point, radius: float, m=FLOAT_MATH) -> list:
    """The features of ``surface`` at ``point`` (surface frame, 3 components) that a sphere
    of ``radius`` [mm] centred there can touch: a list of Feature or Choice."""
    x, y, z = point[0], point[1], point[2]
    kind = surface.kind
    if kind == PLANE:
        return [Feature((0.0, 0.0, 1.0), z)]
    if kind == CYLINDER:
        return [_round_feature(x, None, z + surface.radius, surface.radius, m)]
    if kind == SPHERE:
        return [_round_feature(x, y, z + surface.radius, surface.radius, m)]
    if kind == TOOTH_ROW:
        return _tooth_row_features(surface, x, z, radius, m)
    raise ValueError(f"surface kind {kind!r} has no analytic features")


def resolve(feature: Feature | Choice, m=FLOAT_MATH) -> Feature:
    """The Feature a Choice selects at the point, as one formula (both branches are
    evaluated with numpy arrays)."""
    if isinstance(feature, Feature):
        return feature
    yes, no = resolve(feature.if_true, m), resolve(feature.if_false, m)
    normal = tuple(m.IfThenElse(feature.condition, a, b)
                   for a, b in zip(yes.normal, no.normal, strict=True))
    return Feature(normal, m.IfThenElse(feature.condition, yes.distance, no.distance))


def taken(feature: Feature | Choice) -> Feature:
    """The Feature a Choice selects at the point, on floats (its conditions plain
    booleans): the branch :func:`resolve` would pick, without evaluating the others."""
    while isinstance(feature, Choice):
        feature = feature.if_true if feature.condition else feature.if_false
    return feature


def _round_feature(a, b, c, radius, m) -> Feature:
    """Outside of a ball (b given) or of a cylinder along the second axis (b None) of
    ``radius`` centred at the origin of (a, b, c)."""
    square = m.square(a) + m.square(c) if b is None else (
        m.square(a) + m.square(b) + m.square(c))
    length = m.sqrt(square)
    inverse = 1.0 / m.max(length, _TINY)
    normal = (a * inverse, 0.0 if b is None else b * inverse, c * inverse)
    return Feature(normal, length - radius)


def tooth_pitch(surface: Surface) -> float:
    """Distance between the centres of neighbouring teeth, w + g [mm]."""
    return surface.tooth_width + surface.gap_width


def fold(surface: Surface, x, m=FLOAT_MATH):
    """x relative to the nearest tooth's centre, in [−P/2, P/2) [mm]."""
    pitch = tooth_pitch(surface)
    return x - pitch * m.floor(x / pitch + 0.5)


def flat_top_clearance(surface: Surface, x: float, z: float) -> float:
    """Tooth row: how far [mm] the point (x, z) of the surface frame (a tip sphere's
    centre) can move along the row before it leaves the flat part of the tooth top under
    it, where the closest feature is the top plane (the edges' rounding begins at
    w/2 − ρ from the tooth's centre); negative beyond it (over a rounding or a gap), and
    −inf for a centre below the tops (z < 0: inside a gap or a tooth)."""
    if z < 0.0:
        return -math.inf
    return 0.5 * surface.tooth_width - surface.edge_radius - abs(fold(surface, x))


def _tooth_row_features(surface: Surface, x, z, radius, m) -> list:
    u = fold(surface, x, m)
    found: list[Feature | Choice] = [_tooth_feature(surface, u, z, m)]
    if 2.0 * radius > surface.gap_width:
        pitch = tooth_pitch(surface)
        found.append(_tooth_feature(surface, m.IfThenElse(u >= 0.0, u - pitch, u + pitch), z, m))
    found.append(Feature((0.0, 0.0, 1.0), z + surface.gap_depth))
    return found


def _tooth_feature(surface: Surface, u, z, m) -> Choice:
    """One tooth centred at u = 0: a rounded rectangle with its top at z = 0.

    On each side, a and b are the point's coordinates from the centre of that side's edge
    rounding: beyond both (a, b > 0) the closest point is on the rounding, otherwise on the
    wall (a > b) or on the top.
    """
    rho = surface.edge_radius
    half = 0.5 * surface.tooth_width
    b = z + rho
    top = Feature((0.0, 0.0, 1.0), z)

    def side(sign: float) -> Choice:
        a = (u if sign > 0 else -u) - (half - rho)
        wall = Feature((sign, 0.0, 0.0), (u if sign > 0 else -u) - half)
        corner = m.sqrt(m.square(a) + m.square(b))
        # used only where a, b > 0 (the Choice below); the guard keeps numpy's evaluation
        # of every branch free of 0/0
        inverse = 1.0 / m.max(corner, _TINY)
        rounding = Feature(((a if sign > 0 else -a) * inverse, 0.0, b * inverse), corner - rho)
        return Choice(a > 0.0, Choice(b > 0.0, rounding, wall), Choice(a > b, wall, top))

    return Choice(u >= 0.0, side(1.0), side(-1.0))


def height(surface: Surface, x, y) -> np.ndarray:
    """Height of the surface's top envelope above the point (x, y) of its frame [mm]
    (−radius beyond a cylinder's or sphere's rim, −gap_depth in a gap), element-wise."""
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    kind = surface.kind
    if kind == PLANE:
        return np.zeros_like(x)
    if kind in (CYLINDER, SPHERE):
        r = surface.radius
        across = x * x if kind == CYLINDER else x * x + y * y
        return np.sqrt(np.maximum(r * r - across, 0.0)) - r
    if kind == TOOTH_ROW:
        rho = surface.edge_radius
        a = np.abs(fold(surface, x, ARRAY_MATH)) - (0.5 * surface.tooth_width - rho)
        rounded = np.sqrt(np.maximum(rho * rho - a * a, 0.0)) - rho
        return np.where(a <= 0.0, 0.0, np.where(a <= rho, rounded, -surface.gap_depth))
    raise ValueError(f"surface kind {kind!r} has no height function")


def to_surface_frame(surface: Surface, points) -> np.ndarray:
    """Points of the head frame (..., 3) in the surface's frame [mm]."""
    points = np.asarray(points, dtype=float)
    c, s = np.cos(surface.yaw), np.sin(surface.yaw)
    dx = points[..., 0] - surface.x
    dy = points[..., 1] - surface.y
    return np.stack([c * dx + s * dy, -s * dx + c * dy, points[..., 2]], axis=-1)


def orientation(surface: Surface) -> np.ndarray:
    """Rotation matrix whose columns are the surface frame's axes in the head frame."""
    c, s = np.cos(surface.yaw), np.sin(surface.yaw)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def highest_near(surface: Surface, centres, radius: float, rings: int = 12,
                 spokes: int = 36) -> np.ndarray:
    """The highest point of the surface's top within ``radius`` [mm] (horizontally) of
    each head-frame point ``centres`` (n, 2), sampled on ``rings`` circles of ``spokes``
    points and the centre [mm]."""
    centres = np.asarray(centres, dtype=float)
    ring = np.linspace(0.0, radius, rings + 1)[:, None]
    angle = np.linspace(0.0, 2.0 * np.pi, spokes, endpoint=False)[None, :]
    offsets = np.stack([(ring * np.cos(angle)).ravel(), (ring * np.sin(angle)).ravel()],
                       axis=1)
    points = centres[:, None, :] + offsets[None, :, :]
    flat = np.concatenate([points, np.zeros((*points.shape[:2], 1))], axis=2)
    local = to_surface_frame(surface, flat)
    return height(surface, local[..., 0], local[..., 1]).max(axis=1)
