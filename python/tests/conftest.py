"""Shared fixtures: polytopes with closed-form answers, seeded random poses."""

import numpy as np
import pytest

import mddual


def cube_points(half=0.5, centre=(0.0, 0.0, 0.0)):
    """The 8 corners of an axis-aligned cube of side 2 * half."""
    c = np.asarray(centre, dtype=float)
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    return c + half * corners


def translation(x, y=0.0, z=0.0):
    """A 4x4 pose that translates by (x, y, z)."""
    X = np.eye(4)
    X[:3, 3] = (x, y, z)
    return X


def random_rotation(rng):
    """A uniformly random rotation matrix (from a random unit quaternion)."""
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def random_pose(rng, spread=1.0):
    """A random rigid transform with translation in [-spread, spread]^3."""
    X = np.eye(4)
    X[:3, :3] = random_rotation(rng)
    X[:3, 3] = rng.uniform(-spread, spread, size=3)
    return X


@pytest.fixture
def rng():
    return np.random.default_rng(20261124)


@pytest.fixture
def unit_cube():
    return mddual.ConvexPolytope(cube_points())


@pytest.fixture(scope="session", autouse=True)
def module_is_the_built_one():
    """Fail loudly if an installed mddual shadows the one under test."""
    import os

    path = os.environ.get("PYTHONPATH", "").split(os.pathsep)[0]
    if path:
        assert os.path.dirname(os.path.abspath(mddual.__file__)) == os.path.abspath(path), mddual.__file__
