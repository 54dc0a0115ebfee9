"""mdd_batch, toi_batch and intersect_batch: the same answers as a loop of
single queries, broadcasting of shared arguments, and errors naming the
argument or the query."""

import concurrent.futures
import math

import numpy as np
import pytest

import mddual
from conftest import cube_points, random_pose, translation

K = 200
# Warm starts change where the search begins, not the answer: the results
# agree with the cold loop to round-off (world units, bodies about 1 across).
WARM_TOL = 1e-9


@pytest.fixture
def pair(rng):
    a = mddual.ConvexPolytope(rng.normal(size=(25, 3)))
    b = mddual.ConvexPolytope(rng.normal(size=(18, 3)) * 0.7)
    X_WA = random_pose(rng)
    # B moves along a smooth path through A (frame coherence for the warm start).
    X_WB = np.stack([random_pose(rng, 0.2) for _ in range(K)])
    X_WB[:, :3, 3] += np.linspace(-4.0, 4.0, K)[:, None] * [1.0, 0.3, -0.2]
    directions = rng.normal(size=(K, 3))
    return a, X_WA, b, X_WB, directions


def assert_same(x, y, tol):
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    assert x.shape == y.shape
    assert np.array_equal(np.isnan(x), np.isnan(y))
    finite = ~np.isnan(x)
    np.testing.assert_allclose(x[finite], y[finite], rtol=tol, atol=tol)


@pytest.mark.parametrize("warm_start, tol", [(False, 0.0), (True, WARM_TOL)])
def test_mdd_batch_equals_the_loop(pair, warm_start, tol):
    a, X_WA, b, X_WB, s = pair
    out = mddual.mdd_batch(a, X_WA, b, X_WB, s, warm_start=warm_start)
    loop = [mddual.mdd(a, X_WA, b, X_WB[k], s[k]) for k in range(K)]
    assert out["status"].dtype == np.int8
    assert [mddual.CONTACT_STATUSES[c] for c in out["status"]] == [r.status for r in loop]
    for key in ("distance", "t_lo", "t_hi"):
        assert_same(out[key], [getattr(r, key) for r in loop], tol)
    for key in ("normal", "point"):
        assert out[key].shape == (K, 3)
        assert_same(out[key], [getattr(r, key) for r in loop], tol)
    assert {"separated", "penetrating"} <= {r.status for r in loop}


@pytest.mark.parametrize("warm_start, tol", [(False, 0.0), (True, WARM_TOL)])
def test_toi_batch_equals_the_loop(pair, rng, warm_start, tol):
    a, X_WA, b, X_WB, s = pair
    limits = rng.uniform(0.5, 6.0, size=K)
    out = mddual.toi_batch(a, X_WA, b, X_WB, s, max_distance=limits, warm_start=warm_start)
    loop = [mddual.toi(a, X_WA, b, X_WB[k], s[k], max_distance=limits[k]) for k in range(K)]
    assert [mddual.TOI_STATUSES[c] for c in out["status"]] == [r.status for r in loop]
    assert_same(out["toi"], [r.toi for r in loop], tol)
    assert out["toi_exact"].all()
    assert_same(out["normal"], [r.normal for r in loop], tol)
    assert {"hit", "in_contact", "never"} == {r.status for r in loop}


@pytest.mark.parametrize("warm_start", [False, True])
def test_intersect_batch_equals_the_loop(pair, warm_start):
    a, X_WA, b, X_WB, _ = pair
    out = mddual.intersect_batch(a, X_WA, b, X_WB, warm_start=warm_start)
    loop = [mddual.intersect(a, X_WA, b, X_WB[k]) for k in range(K)]
    assert [mddual.INTERSECT_STATUSES[c] for c in out["status"]] == [r.status for r in loop]
    assert out["intersecting"].dtype == bool
    assert out["intersecting"].tolist() == [r.intersecting for r in loop]
    assert {True, False} == set(out["intersecting"].tolist())
    # Every separating normal is a proof of separation.
    va = a.vertices @ X_WA[:3, :3].T + X_WA[:3, 3]
    for k in np.flatnonzero(~out["intersecting"]):
        vb = b.vertices @ X_WB[k, :3, :3].T + X_WB[k, :3, 3]
        n = out["separating_normal"][k]
        assert (va @ n).max() < (vb @ n).min()


def test_status_tables_follow_the_enums():
    assert mddual.CONTACT_STATUSES == ("separated", "touching", "penetrating", "no_contact")
    assert mddual.TOI_STATUSES == ("hit", "in_contact", "never")
    assert mddual.INTERSECT_STATUSES == ("separated", "touching", "penetrating")


def test_shared_arguments_broadcast(unit_cube):
    # One direction and one pose of A for every query; B slides along x.
    xs = np.array([3.0, 1.0, 0.25, -3.0])
    X_WB = np.stack([translation(x) for x in xs])
    out = mddual.mdd_batch(unit_cube, None, unit_cube, X_WB, [-1.0, 0.0, 0.0])
    np.testing.assert_allclose(out["distance"], [2.0, 0.0, -0.75, 2.0], atol=1e-12)
    assert [mddual.CONTACT_STATUSES[c] for c in out["status"]] == ["separated", "touching", "penetrating",
                                                                    "separated"]
    # Many directions, one pose of each body.
    s = np.array([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    out = mddual.toi_batch(unit_cube, None, unit_cube, translation(3.0), s)
    assert out["toi"][0] == pytest.approx(2.0, abs=1e-12)
    assert math.isinf(out["toi"][1]) and math.isinf(out["toi"][2])


def test_nothing_batched_is_one_query(unit_cube):
    out = mddual.intersect_batch(unit_cube, None, unit_cube, translation(0.5))
    assert out["status"].shape == (1,)
    assert out["intersecting"][0]


def test_empty_batch_gives_empty_arrays(unit_cube):
    out = mddual.mdd_batch(unit_cube, None, unit_cube, np.zeros((0, 4, 4)), [1.0, 0.0, 0.0])
    assert out["distance"].shape == (0,)
    assert out["normal"].shape == (0, 3)


def test_empty_batch_checks_what_conversion_checks(unit_cube):
    """K = 0 runs no query: shapes, types and the poses' last rows are checked, query values not."""
    none = np.zeros((0, 4, 4))
    out = mddual.mdd_batch(unit_cube, None, unit_cube, none, [0.0, 0.0, 0.0])  # a query would refuse it
    assert out["distance"].shape == (0,)
    X_WA = np.eye(4)
    X_WA[3, 0] = np.nan
    with pytest.raises(mddual.InvalidInputError, match="X_WA: the last row"):
        mddual.mdd_batch(unit_cube, X_WA, unit_cube, none, [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="directions: expected"):
        mddual.mdd_batch(unit_cube, None, unit_cube, none, [1.0, 0.0])
    with pytest.raises(TypeError, match="directions"):
        mddual.mdd_batch(unit_cube, None, unit_cube, none, ["a", "b", "c"])


def test_batch_sizes_must_agree(unit_cube):
    X_WB = np.stack([translation(x) for x in (2.0, 3.0, 4.0)])
    with pytest.raises(ValueError, match="batch sizes differ: X_WB has 3 entries, directions has 2"):
        mddual.mdd_batch(unit_cube, None, unit_cube, X_WB, np.ones((2, 3)))
    with pytest.raises(ValueError, match="max_distance has 5"):
        mddual.toi_batch(unit_cube, None, unit_cube, X_WB, [1.0, 0.0, 0.0], max_distance=np.ones(5))


def test_batch_shapes_are_checked(unit_cube):
    with pytest.raises(ValueError, match=r"X_WB: expected a \(K, 4, 4\) array of poses.*got shape \(3, 3, 3\)"):
        mddual.intersect_batch(unit_cube, None, unit_cube, np.zeros((3, 3, 3)))
    with pytest.raises(ValueError, match=r"directions: expected a \(K, 3\) array.*got shape \(2, 4\)"):
        mddual.mdd_batch(unit_cube, None, unit_cube, None, np.ones((2, 4)))
    with pytest.raises(TypeError, match="directions"):
        mddual.toi_batch(unit_cube, None, unit_cube, None, None)


def test_bad_pose_in_a_batch_names_its_index(unit_cube):
    X_WB = np.stack([translation(x) for x in (2.0, 3.0, 4.0)])
    X_WB[2, 3, 3] = 2.0
    with pytest.raises(mddual.InvalidInputError, match=r"X_WB\[2\]: the last row"):
        mddual.intersect_batch(unit_cube, None, unit_cube, X_WB)


def test_library_error_in_a_batch_names_the_query(unit_cube):
    s = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    with pytest.raises(mddual.InvalidInputError, match=r"^mdd_batch: query 2: .*direction") as info:
        mddual.mdd_batch(unit_cube, None, unit_cube, translation(3.0), s)
    assert isinstance(info.value, ValueError)
    X_WB = np.stack([translation(3.0), np.diag([1.0, 2.0, 1.0, 1.0])])
    with pytest.raises(mddual.InvalidInputError, match=r"^toi_batch: query 1: .*X_WB"):
        mddual.toi_batch(unit_cube, None, unit_cube, X_WB, [1.0, 0.0, 0.0])


def test_batches_in_threads_give_the_same_answers(pair):
    # The batch loops run without the GIL; concurrent calls (each with its
    # own warm start) must not disturb one another.
    a, X_WA, b, X_WB, s = pair
    expected = mddual.mdd_batch(a, X_WA, b, X_WB, s)["distance"]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        runs = list(pool.map(lambda _: mddual.mdd_batch(a, X_WA, b, X_WB, s)["distance"], range(8)))
    for r in runs:
        assert_same(r, expected, 0.0)
