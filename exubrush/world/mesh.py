"""Triangle-mesh surfaces: reading, checking (trimesh), closest points (libigl).

A mesh surface is read once (``surface.mesh_file``, STL or OBJ, coordinates in
``surface.mesh_unit``), converted to mm and shifted so that its highest vertex lies at
z = 0, like every surface's top (exubrush.world.surfaces); x and y stay as in the file. Its
triangles' winding gives their outward normals (counter-clockwise seen from outside, the
STL and OBJ convention), so an open mesh such as a patch of a plane is a surface too, as
long as the winding is consistent.

Closest points are libigl's (``igl.AABB.squared_distance``: an axis-aligned bounding-box
tree of the triangles, exact, compiled), built at the first query in each process. It
replaced trimesh's ``closest_point`` over the candidates of a k-d tree of centroids (0.9.0):
the same points to 1e-16 mm; a whole :meth:`MeshSurface.closest` (the tree's query about
7 µs, the contact normal the rest) about 20 µs instead of about 110 µs, which a mesh run
pays before every step of every bristle.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from exubrush.parameters.choices import MESH_UNITS

if TYPE_CHECKING:
    from scipy.spatial import cKDTree

# a mesh whose extent in mm falls outside this range is almost surely in another unit
PLAUSIBLE_EXTENT = (0.5, 500.0)  # mm


def _igl():
    """libigl, imported at first use, like trimesh."""
    import igl

    return igl


def _trimesh():
    """trimesh, imported at first use: a process that brushes no mesh does not pay its
    import (about 80 ms, in the main process and every worker)."""
    import trimesh

    return trimesh


class MeshError(ValueError):
    """A mesh file is missing, unreadable, empty, inconsistently wound or implausibly sized."""


@dataclass(frozen=True)
class MeshSurface:
    """A checked triangle mesh in the surface frame [mm] and its search structures.

    Attributes
    ----------
    triangles : ndarray (n, 3, 3)
        Vertices of each triangle [mm], counter-clockwise seen from outside.
    normals : ndarray (n, 3)
        Outward unit normal of each triangle.
    """

    triangles: np.ndarray
    normals: np.ndarray
    _xy_tree: cKDTree = field(repr=False, compare=False)
    _xy_reach: float = field(repr=False, compare=False)
    # (vertices, faces, tree) for libigl, made at the first closest-point query of a
    # process; not pickled (a worker makes its own)
    _search: list = field(default_factory=list, repr=False, compare=False)

    def __getstate__(self):
        return {**self.__dict__, "_search": []}

    def __setstate__(self, state):
        self.__dict__.update(state)

    @classmethod
    def from_triangles(cls, triangles: np.ndarray) -> MeshSurface:
        """A mesh surface from its triangles (n, 3, 3) [mm], shifted so its top is z = 0."""
        triangles = np.array(triangles, dtype=float)
        triangles[..., 2] -= triangles[..., 2].max()
        normals = _trimesh().triangles.normals(triangles)[0]
        centroids = triangles.mean(axis=1)
        xy_reach = float(np.max(np.linalg.norm(
            triangles[..., :2] - centroids[:, None, :2], axis=2)))
        from scipy.spatial import cKDTree  # SciPy's spatial: only where a mesh is read

        return cls(triangles, normals, cKDTree(centroids[:, :2]), xy_reach)

    def closest(self, point) -> tuple[np.ndarray, np.ndarray, float]:
        """Closest point on the mesh to ``point`` (surface frame) [mm], the outward normal
        of the contact there and the signed distance [mm] (negative inside); the normal as
        :meth:`_contact_normals` gives it."""
        closest, normal, signed = self.closest_many(np.asarray(point, dtype=float)[None])
        return closest[0], normal[0], float(signed[0])

    def closest_many(self, points) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`closest` of many points (n, 3) at once: closest points, normals, signed
        distances."""
        points = np.ascontiguousarray(np.asarray(points, dtype=float).reshape(-1, 3))
        if not self._search:
            # every triangle with its own three vertices: the closest points are the same
            vertices = np.ascontiguousarray(self.triangles.reshape(-1, 3))
            faces = np.arange(len(vertices), dtype=np.int64).reshape(-1, 3)
            tree = _igl().AABB()
            tree.init(vertices, faces)
            self._search.extend((vertices, faces, tree))
        vertices, faces, tree = self._search
        squared, found, closest = tree.squared_distance(vertices, faces, points)
        distance = np.sqrt(squared)
        normal, signed = self._contact_normals(points, closest, distance, found)
        return closest, normal, signed

    def _contact_normals(self, points, closest, distance, faces):
        """Outward normals of the contacts and signed distances of ``points`` (n, 3) whose
        closest mesh points ``closest`` at ``distance`` lie on triangles ``faces``.

        The sign is the side of the face the point is on. Over a face's interior the
        direction from the closest point is the face's normal up to rounding: the face's
        exact normal is kept; beyond an edge or a vertex the normal turns with the point.
        """
        face_normal = self.normals[faces]
        offset = points - closest
        side = np.where(np.einsum("ij,ij->i", offset, face_normal) >= 0.0, 1.0, -1.0)
        tiny = distance <= 1e-9  # on the surface [mm]
        direction = side[:, None] * offset / np.maximum(distance, 1e-300)[:, None]
        on_face = tiny | (np.einsum("ij,ij->i", direction, face_normal) >= 1.0 - 1e-9)
        return np.where(on_face[:, None], face_normal, direction), side * distance

    def heights(self, xy) -> np.ndarray:
        """Height of the mesh's top above each point (n, 2) of the surface frame's x-y
        plane [mm] (the highest triangle over it), −inf where no triangle is over it."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        flat = self.triangles.copy()
        flat[..., 2] = 0.0
        tops = np.full(len(xy), -np.inf)
        for i, point in enumerate(xy):
            near = self._xy_tree.query_ball_point(point, self._xy_reach)
            if not near:
                continue
            near = np.asarray(near)
            weights = _trimesh().triangles.points_to_barycentric(
                flat[near], np.repeat([[point[0], point[1], 0.0]], len(near), axis=0))
            inside = np.all(weights >= -1e-12, axis=1)
            if inside.any():
                z = np.einsum("ij,ij->i", weights[inside], self.triangles[near[inside], :, 2])
                tops[i] = z.max()
        return tops

    def top_near_segment(self, start, end, radius: float) -> float:
        """An upper bound of the mesh's height within ``radius`` [mm] (horizontally) of
        the segment from ``start`` to ``end`` (x-y points of the surface frame): the
        highest vertex of every triangle that may reach into that region (its centroid
        within radius + its own horizontal size of the segment); −inf if none may."""
        start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        centroids = self.triangles[..., :2].mean(axis=1)
        along = end - start
        length = float(along @ along)
        share = np.clip((centroids - start) @ along / length, 0.0, 1.0) if length else 0.0
        gap = np.linalg.norm(centroids - (start + np.multiply.outer(share, along)), axis=1)
        near = gap <= radius + self._xy_reach
        return float(self.triangles[near, :, 2].max()) if near.any() else -np.inf


def frame_with_normal(normal) -> np.ndarray:
    """A rotation matrix whose third column is the unit vector ``normal``: the rotation
    of e_z onto it about e_z × normal (Rodrigues); the identity, exactly, for e_z."""
    n = np.asarray(normal, dtype=float)
    if n[2] <= -1.0 + 1e-12:  # opposite to e_z: half a turn about x
        return np.diag([1.0, -1.0, -1.0])
    k = np.array([-n[1], n[0], 0.0])  # e_z × n
    cross = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + cross + cross @ cross / (1.0 + n[2])


def read_mesh(path: str | Path, unit: str) -> MeshSurface:
    """Read and check a mesh file (module docstring). MeshError says what is wrong and
    what to do, naming the file."""
    path = Path(path)
    name = f"surface.mesh_file {str(path)!r}"
    if unit not in MESH_UNITS:
        raise MeshError(f"surface.mesh_unit {unit!r} is not one of {', '.join(MESH_UNITS)}")
    if not path.exists():
        raise MeshError(f"{name} does not exist; give the path of an STL or OBJ file "
                        "(relative to the case file)")
    if not path.is_file():
        raise MeshError(f"{name} is not a file; give the path of an STL or OBJ file")
    if path.suffix.lower() not in (".stl", ".obj"):
        raise MeshError(f"{name} is not an STL or OBJ file (by its extension); export the "
                        "surface as .stl or .obj")
    trimesh = _trimesh()
    try:
        loaded = trimesh.load(path, force="mesh", process=True)
    except Exception as err:  # trimesh raises many types for a bad file
        # an ImportError is trimesh guessing a text encoding with an optional package
        detail = ("" if isinstance(err, ImportError)
                  else f" ({type(err).__name__}: {' '.join(str(err).split())[:120]})")
        raise MeshError(f"{name} is not a readable STL or OBJ mesh{detail}") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise MeshError(f"{name} holds no triangles; export the surface as a triangle mesh")
    if not loaded.is_winding_consistent:
        raise MeshError(f"{name}: its triangles are not wound consistently, so the outside "
                        "of the surface is undefined; repair the mesh (e.g. fix its normals) "
                        "and export it again")
    triangles = np.asarray(loaded.triangles, dtype=float) * MESH_UNITS[unit]
    extent = float(np.max(np.ptp(triangles.reshape(-1, 3), axis=0)))
    low, high = PLAUSIBLE_EXTENT
    if not low <= extent <= high:
        raise MeshError(f"{name} measures {extent:.4g} mm across with surface.mesh_unit = "
                        f"{unit!r}, outside the {low:g} to {high:g} mm of a tooth surface: is "
                        "the file in another unit? Set surface.mesh_unit to it")
    return MeshSurface.from_triangles(triangles)
