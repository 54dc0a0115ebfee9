"""ConvexPolytope from NumPy arrays: properties and the library's errors."""

import numpy as np
import pytest

import mddual
from conftest import cube_points


def test_cube_has_eight_vertices_and_six_faces(unit_cube):
    assert unit_cube.num_vertices == 8
    assert unit_cube.num_faces == 6
    assert unit_cube.num_edges == 12
    assert not unit_cube.is_flat
    assert unit_cube.vertices.shape == (8, 3)
    assert sorted(map(tuple, unit_cube.vertices)) == sorted(map(tuple, cube_points()))
    np.testing.assert_allclose(unit_cube.centroid, [0, 0, 0], atol=1e-15)
    assert unit_cube.radius == pytest.approx(np.sqrt(3) / 2)
    # Each face n . x <= h with h = 1/2 and n an axis.
    np.testing.assert_allclose(unit_cube.face_offsets, 0.5)
    np.testing.assert_allclose(np.sort(np.abs(unit_cube.face_normals).sum(axis=1)), 1.0)
    assert [len(f) for f in unit_cube.faces] == [4] * 6


def test_interior_points_are_dropped():
    points = np.vstack([cube_points(), [[0.1, 0.2, -0.1], [0.0, 0.0, 0.0]]])
    assert mddual.ConvexPolytope(points).num_vertices == 8


def test_triangle_is_flat_with_two_faces():
    tri = mddual.ConvexPolytope([[0, 0, 0], [1, 0, 0], [0, 1, 0]])
    assert tri.is_flat
    assert tri.num_faces == 2
    assert "flat" in repr(tri)


def test_nan_point_raises_invalid_input_naming_the_point():
    points = cube_points()
    points[3, 1] = np.nan
    with pytest.raises(mddual.InvalidInputError, match="point 3") as info:
        mddual.ConvexPolytope(points)
    assert isinstance(info.value, ValueError)
    assert isinstance(info.value, mddual.Error)


def test_empty_set_raises_invalid_input():
    with pytest.raises(mddual.InvalidInputError, match="empty"):
        mddual.ConvexPolytope(np.zeros((0, 3)))


def test_too_few_points_raise_degenerate_geometry():
    with pytest.raises(mddual.DegenerateGeometryError, match="polytope") as info:
        mddual.ConvexPolytope([[0, 0, 0], [1, 1, 1]])
    assert isinstance(info.value, mddual.InvalidInputError)
    with pytest.raises(mddual.DegenerateGeometryError):
        mddual.ConvexPolytope([[0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3]])


@pytest.mark.parametrize("bad", [np.zeros((4, 2)), np.zeros(12), np.zeros((2, 3, 3))])
def test_wrong_shape_is_a_value_error_naming_points(bad):
    with pytest.raises(ValueError, match=r"points: expected an \(N, 3\) array"):
        mddual.ConvexPolytope(bad)


def test_non_numeric_points_are_a_type_error_naming_points():
    with pytest.raises(TypeError, match="points"):
        mddual.ConvexPolytope("not points")
    with pytest.raises(TypeError, match="points"):
        mddual.ConvexPolytope(None)


def test_exception_hierarchy():
    assert issubclass(mddual.Error, Exception)
    assert issubclass(mddual.InvalidInputError, mddual.Error)
    assert issubclass(mddual.InvalidInputError, ValueError)
    assert issubclass(mddual.DegenerateGeometryError, mddual.InvalidInputError)
    assert issubclass(mddual.HullError, mddual.Error)
    assert issubclass(mddual.NumericalError, mddual.Error)
    assert issubclass(mddual.NumericalError, RuntimeError)
