"""Mesh surfaces: reading and checking files, closest points against brute force, and the
one-line refusals of bad mesh input."""

import numpy as np
import pytest
import trimesh

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.world.mesh import MeshError, frame_with_normal, read_mesh


@pytest.fixture(scope="module")
def sphere_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("mesh") / "sphere.stl"
    trimesh.creation.icosphere(subdivisions=3, radius=4.0).export(path)
    return path


def test_mesh_is_read_in_its_unit_with_its_top_at_zero(sphere_file):
    mesh = read_mesh(sphere_file, "mm")
    assert mesh.triangles[..., 2].max() == 0.0
    assert mesh.triangles[..., 2].min() == pytest.approx(-8.0, abs=1e-9)
    assert read_mesh(sphere_file, "cm").triangles[..., 2].min() == pytest.approx(-80.0,
                                                                                 abs=1e-8)


def test_closest_points_are_those_of_all_triangles(sphere_file):
    mesh = read_mesh(sphere_file, "mm")
    rng = np.random.default_rng(4)
    points = rng.normal(size=(60, 3)) * 3.0 + [0.0, 0.0, -4.0]
    every = len(mesh.triangles)
    for point in points:
        brute = trimesh.triangles.closest_point(mesh.triangles, np.repeat([point], every, 0))
        distance = np.linalg.norm(brute - point, axis=1).min()
        _, normal, signed = mesh.closest(point)
        assert abs(signed) == pytest.approx(distance, abs=1e-12)
        # the sign: inside the sphere is negative, and the normal points outward
        inside = np.linalg.norm(point - [0.0, 0.0, -4.0]) < 3.8
        if inside:
            assert signed < 0.0
        assert normal @ (point - [0.0, 0.0, -4.0]) > 0.0
    many = mesh.closest_many(points)
    for k, point in enumerate(points):
        one = mesh.closest(point)
        np.testing.assert_allclose(many[0][k], one[0], atol=1e-12)
        np.testing.assert_allclose(many[1][k], one[1], atol=1e-12)


def test_over_a_face_the_normal_is_the_faces_exactly():
    triangles = np.array([[[-50.0, -50.0, 0.0], [50.0, -50.0, 0.0], [50.0, 50.0, 0.0]],
                          [[-50.0, -50.0, 0.0], [50.0, 50.0, 0.0], [-50.0, 50.0, 0.0]]])
    from exubrush.world.mesh import MeshSurface

    mesh = MeshSurface.from_triangles(triangles)
    point, normal, signed = mesh.closest([0.123, -7.7, 0.39])
    assert tuple(normal) == (0.0, 0.0, 1.0) and signed == 0.39 and point[2] == 0.0
    # beyond the edge the normal turns towards the point
    _, normal, signed = mesh.closest([53.0, 0.0, 4.0])
    np.testing.assert_allclose(normal, [0.6, 0.0, 0.8], atol=1e-12)
    assert signed == pytest.approx(5.0)


@pytest.mark.parametrize("normal", [[0, 0, 1], [0.6, 0, 0.8], [0.3, -0.4, -0.866], [0, 0, -1],
                                    [1, 0, 0]])
def test_frame_with_normal_is_a_rotation_onto_the_normal(normal):
    normal = np.asarray(normal, float) / np.linalg.norm(normal)
    frame = frame_with_normal(normal)
    np.testing.assert_allclose(frame @ frame.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(frame) == pytest.approx(1.0)
    np.testing.assert_allclose(frame[:, 2], normal, atol=1e-12)
    if normal[2] == 1.0:
        assert np.array_equal(frame, np.eye(3))  # exactly: a flat face is the plane


def _prepare_mesh(path, *extra):
    return prepare(load_case("orthogonal", ["head.rows=1", "head.columns=1",
                                            "surface.kind='mesh'",
                                            f"surface.mesh_file='{path}'", *extra]))


def test_bad_mesh_input_is_refused_in_one_line(tmp_path, sphere_file):
    missing = tmp_path / "none.stl"
    garbage = tmp_path / "garbage.obj"
    garbage.write_text("v 0 0 0\nv 1 0 0\nf 1 2 3\n")  # a face with a vertex that is not there
    binary = tmp_path / "binary.stl"
    binary.write_bytes(bytes(range(256)) * 3)
    text = tmp_path / "text.stl"
    text.write_bytes(b"solid x\nthis is not an stl\n")
    other = tmp_path / "surface.step"
    other.write_text("ISO-10303-21;")
    empty = tmp_path / "empty.obj"
    empty.write_text("# no faces\n")
    flipped = tmp_path / "flipped.stl"
    box = trimesh.creation.box(extents=[10.0, 10.0, 2.0])
    faces = box.faces.copy()
    faces[0] = faces[0][::-1]
    trimesh.Trimesh(box.vertices, faces, process=False).export(flipped)
    cases = [
        ((missing,), "does not exist"),
        ((tmp_path,), "is not a file"),
        ((sphere_file / "under.stl",), "does not exist"),  # a path under a plain file
        ((garbage,), "is not a readable STL or OBJ mesh"),
        # random bytes: trimesh 4 raised on them, trimesh 5 reads a binary STL of no
        # triangles; either answer is one line naming the file
        ((binary,), "is not a readable STL or OBJ mesh|holds no triangles"),
        ((text,), "holds no triangles"),
        ((other,), "is not an STL or OBJ file"),
        ((empty,), "holds no triangles"),
        ((flipped,), "not wound consistently"),
        ((sphere_file, "surface.mesh_unit='m'"), "measures 8000 mm across"),
        ((sphere_file, "surface.mesh_unit='um'"), "is the file in another unit"),
        ((sphere_file, "surface.x='80 mm'"), "no bristle can reach the mesh"),
    ]
    for arguments, message in cases:
        with pytest.raises(ParameterError, match=message) as caught:
            _prepare_mesh(*arguments)
        assert "\n" not in str(caught.value)


def test_a_mesh_needs_a_file():
    with pytest.raises(ParameterError, match="kind 'mesh' needs mesh_file"):
        load_case("orthogonal", ["surface.kind='mesh'"])


def test_mesh_error_is_a_value_error():
    assert issubclass(MeshError, ValueError)


def test_a_mesh_sent_to_a_worker_finds_the_same_closest_points(sphere_file):
    # workers receive the prepared case pickled: the search tree (libigl) is made again
    # there, not pickled
    import pickle

    mesh = read_mesh(sphere_file, "mm")
    point = [0.3, -0.2, 0.45]
    here = mesh.closest(point)
    there = pickle.loads(pickle.dumps(mesh)).closest(point)
    np.testing.assert_array_equal(here[0], there[0])
    np.testing.assert_array_equal(here[1], there[1])
    assert here[2] == there[2]
