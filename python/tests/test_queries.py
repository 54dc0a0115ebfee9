"""mdd, toi, intersect, penetration_depth, width and distance on one pair: closed forms
on unit cubes, agreement with the brute force (A - B built explicitly) on
seeded random pairs, and the library's errors."""

import math

import numpy as np
import pytest

import mddual
from conftest import cube_points, random_pose, translation

# Tolerance of the comparisons, relative to the scene's size (the bodies are
# about 1 across): the library is exact up to round-off.
TOL = 1e-9


# ---- mdd: closed forms --------------------------------------------------------

def test_mdd_separated_moving_toward(unit_cube):
    r = mddual.mdd(unit_cube, None, unit_cube, translation(3.0), [-1.0, 0.0, 0.0])
    assert r.status == "separated"
    assert r.distance == pytest.approx(2.0, abs=TOL)
    assert r.t_lo == pytest.approx(2.0, abs=TOL)
    np.testing.assert_allclose(r.normal, [1, 0, 0], atol=TOL)
    assert r.point[0] == pytest.approx(0.5, abs=TOL)


def test_mdd_direction_length_does_not_matter(unit_cube):
    r = mddual.mdd(unit_cube, None, unit_cube, translation(3.0), [-7.5, 0.0, 0.0])
    assert r.distance == pytest.approx(2.0, abs=TOL)


def test_mdd_separated_moving_away_needs_backward_motion(unit_cube):
    r = mddual.mdd(unit_cube, None, unit_cube, translation(3.0), [1.0, 0.0, 0.0])
    assert r.status == "separated"
    assert r.distance == pytest.approx(2.0, abs=TOL)
    assert r.t_hi == pytest.approx(-2.0, abs=TOL)


def test_mdd_penetrating_is_minus_the_shorter_way_out(unit_cube):
    r = mddual.mdd(unit_cube, None, unit_cube, translation(0.25), [1.0, 0.0, 0.0])
    assert r.status == "penetrating"
    assert r.distance == pytest.approx(-0.75, abs=TOL)
    assert r.t_lo == pytest.approx(-1.25, abs=TOL)
    assert r.t_hi == pytest.approx(0.75, abs=TOL)


def test_mdd_touching(unit_cube):
    r = mddual.mdd(unit_cube, None, unit_cube, translation(1.0), [1.0, 0.0, 0.0])
    assert r.status == "touching"
    assert r.distance == pytest.approx(0.0, abs=TOL)


def test_mdd_no_contact_when_the_line_misses(unit_cube):
    r = mddual.mdd(unit_cube, None, unit_cube, translation(3.0, 3.0), [1.0, 0.0, 0.0])
    assert r.status == "no_contact"
    assert math.isnan(r.distance)


def test_mdd_poses_of_both_bodies_count(unit_cube):
    # Shifting both bodies by the same pose changes nothing.
    shift = translation(10.0, -4.0, 2.0)
    r = mddual.mdd(unit_cube, shift, unit_cube, shift @ translation(3.0), [-1.0, 0.0, 0.0])
    assert r.distance == pytest.approx(2.0, abs=TOL)


# ---- toi -----------------------------------------------------------------------

def test_toi_hit(unit_cube):
    r = mddual.toi(unit_cube, None, unit_cube, translation(3.0), [-1.0, 0.0, 0.0])
    assert r.status == "hit"
    assert r.toi == pytest.approx(2.0, abs=TOL)
    assert r.toi_exact
    np.testing.assert_allclose(r.normal, [1, 0, 0], atol=TOL)


def test_toi_beyond_max_distance_is_never(unit_cube):
    r = mddual.toi(unit_cube, None, unit_cube, translation(3.0), [-1.0, 0.0, 0.0], max_distance=1.5)
    assert r.status == "never"
    assert r.toi == math.inf


def test_toi_moving_away_is_never(unit_cube):
    r = mddual.toi(unit_cube, None, unit_cube, translation(3.0), [1.0, 0.0, 0.0])
    assert r.status == "never"


def test_toi_overlapping_is_in_contact(unit_cube):
    r = mddual.toi(unit_cube, None, unit_cube, translation(0.25), [1.0, 0.0, 0.0])
    assert r.status == "in_contact"
    assert r.toi == 0.0


def test_toi_inexact_hit_bounds_the_first_contact(unit_cube):
    r = mddual.toi(unit_cube, None, unit_cube, translation(3.0), [-1.0, 0.0, 0.0], max_distance=10.0, exact=False)
    assert r.status == "hit"
    assert r.toi >= 2.0 - TOL
    assert r.toi <= 10.0


# ---- intersect -----------------------------------------------------------------

def test_intersect_separated_gives_a_separating_normal(unit_cube):
    X_WB = translation(3.0, 0.5, 0.0)
    r = mddual.intersect(unit_cube, None, unit_cube, X_WB)
    assert r.status == "separated"
    assert not r.intersecting and not r
    n = r.separating_normal
    b_W = cube_points() + X_WB[:3, 3]
    assert (cube_points() @ n).max() < (b_W @ n).min()


@pytest.mark.parametrize("x, status", [(1.0, "touching"), (0.25, "penetrating")])
def test_intersect_in_contact(unit_cube, x, status):
    r = mddual.intersect(unit_cube, None, unit_cube, translation(x))
    assert r.status == status
    assert r.intersecting and r
    assert np.isnan(r.separating_normal).all()


# ---- penetration depth and width ----------------------------------------------

@pytest.mark.parametrize("method", ["exact", "shallow", "brute"])
def test_penetration_depth_of_overlapping_cubes(unit_cube, method):
    r = mddual.penetration_depth(unit_cube, None, unit_cube, translation(0.25, 0.1), method=method)
    assert r.status == "penetrating"
    assert r.depth == pytest.approx(0.75, abs=TOL)
    np.testing.assert_allclose(r.normal, [1, 0, 0], atol=TOL)
    np.testing.assert_allclose(r.translation, [0.75, 0, 0], atol=TOL)


def test_penetration_depth_approx_is_within_its_factor(unit_cube):
    delta = 0.05
    r = mddual.penetration_depth(unit_cube, None, unit_cube, translation(0.25, 0.1), method="approx", delta=delta)
    assert r.delta == delta
    assert 0.75 - TOL <= r.depth <= (1 + delta) * 0.75 + TOL


def test_penetration_depth_is_zero_when_separated(unit_cube):
    r = mddual.penetration_depth(unit_cube, None, unit_cube, translation(3.0))
    assert r.status == "separated"
    assert r.depth == 0.0


@pytest.mark.parametrize("method", ["exact", "shallow", "brute"])
def test_width_of_a_box_is_its_thinnest_side(rng, method):
    box = mddual.ConvexPolytope(cube_points() * [1.0, 2.0, 3.0])
    r = mddual.width(box, method=method)
    assert r.width == pytest.approx(1.0, abs=TOL)
    np.testing.assert_allclose(np.abs(r.direction), [1, 0, 0], atol=TOL)
    # A rotated pose turns the direction, not the width.
    X = random_pose(rng)
    r = mddual.width(box, X, method=method)
    assert r.width == pytest.approx(1.0, abs=TOL)
    np.testing.assert_allclose(np.abs(r.direction @ X[:3, :3]), [1, 0, 0], atol=1e-7)


def test_width_of_a_flat_polygon_is_zero():
    tri = mddual.ConvexPolytope([[0, 0, 0], [1, 0, 0], [0, 1, 0]])
    assert mddual.width(tri).width == 0.0


# ---- against the brute force on random pairs ----------------------------------

def random_pairs(rng, count):
    """Seeded random polytopes (8 to 30 points in a ball) with random poses,
    close enough to overlap in about half the cases."""
    for _ in range(count):
        pa = rng.normal(size=(int(rng.integers(8, 31)), 3))
        pb = rng.normal(size=(int(rng.integers(8, 31)), 3)) * rng.uniform(0.3, 1.5)
        yield (mddual.ConvexPolytope(pa), random_pose(rng, 2.0), mddual.ConvexPolytope(pb), random_pose(rng, 2.0),
               rng.normal(size=3))


def close(x, y):
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    return abs(x - y) <= TOL * max(1.0, abs(y))


def test_mdd_equals_the_brute_force(rng):
    statuses = set()
    for a, X_WA, b, X_WB, s in random_pairs(rng, 150):
        fast = mddual.mdd(a, X_WA, b, X_WB, s)
        ref = mddual.mdd(a, X_WA, b, X_WB, s, method="brute")
        assert fast.status == ref.status
        assert close(fast.distance, ref.distance), (fast, ref)
        # Both ends, except the far end of a separated answer, which MDD-DUAL
        # computes only when needed (NaN, or the brute force's value).
        forward = ref.t_lo > 0.0
        for t in ("t_lo", "t_hi"):
            far_end = fast.status == "separated" and (not forward if t == "t_lo" else forward)
            if not (far_end and math.isnan(getattr(fast, t))):
                assert close(getattr(fast, t), getattr(ref, t)), (t, fast, ref)
        statuses.add(fast.status)
    assert {"separated", "penetrating", "no_contact"} <= statuses


def test_toi_equals_the_brute_force(rng):
    statuses = set()
    for a, X_WA, b, X_WB, s in random_pairs(rng, 150):
        fast = mddual.toi(a, X_WA, b, X_WB, s)
        ref = mddual.toi(a, X_WA, b, X_WB, s, method="brute")
        assert fast.status == ref.status
        assert fast.toi == ref.toi or close(fast.toi, ref.toi), (fast, ref)
        statuses.add(fast.status)
    assert statuses == {"hit", "in_contact", "never"}


def test_intersect_and_penetration_equal_the_brute_force(rng):
    statuses = set()
    for a, X_WA, b, X_WB, _ in random_pairs(rng, 100):
        fast = mddual.intersect(a, X_WA, b, X_WB)
        assert fast.status == mddual.intersect(a, X_WA, b, X_WB, method="brute").status
        exact = mddual.penetration_depth(a, X_WA, b, X_WB)
        ref = mddual.penetration_depth(a, X_WA, b, X_WB, method="brute")
        assert exact.status == ref.status
        assert close(exact.depth, ref.depth), (exact, ref)
        assert (exact.status == "penetrating") == fast.intersecting
        statuses.add(fast.status)
    assert statuses == {"separated", "penetrating"}


# ---- separation distance ---------------------------------------------------------

def test_distance_of_separated_and_overlapping_cubes(unit_cube):
    r = mddual.distance(unit_cube, None, unit_cube, translation(3.0))
    assert r.status == "separated"
    assert r.distance == pytest.approx(2.0, abs=TOL)
    assert r.point_a[0] == pytest.approx(0.5, abs=TOL)
    assert r.point_b[0] == pytest.approx(2.5, abs=TOL)
    np.testing.assert_allclose(r.normal, [1, 0, 0], atol=TOL)
    r = mddual.distance(unit_cube, None, unit_cube, translation(0.25, 0.1))
    assert r.status == "penetrating"
    assert r.distance == pytest.approx(-0.75, abs=TOL)
    assert mddual.distance(unit_cube, None, unit_cube, translation(1.0)).status == "touching"


def test_distance_agrees_with_the_brute_force_toi_and_penetration(rng):
    """Separated: B moved by the distance along -normal touches A (brute-force
    toi) and the witness points are that far apart; overlapping: minus the
    brute-force penetration depth."""
    statuses = set()
    for a, X_WA, b, X_WB, _ in random_pairs(rng, 100):
        r = mddual.distance(a, X_WA, b, X_WB)
        statuses.add(r.status)
        if r.status == "separated":
            assert close(float(np.linalg.norm(r.point_b - r.point_a)), r.distance), r
            hit = mddual.toi(a, X_WA, b, X_WB, -r.normal, method="brute")
            assert hit.status == "hit" and close(hit.toi, r.distance), (r, hit)
        elif r.status == "penetrating":
            ref = mddual.penetration_depth(a, X_WA, b, X_WB, method="brute")
            assert close(r.distance, -ref.depth), (r, ref)
    assert {"separated", "penetrating"} <= statuses


def test_distance_of_a_nan_pose_raises(unit_cube):
    X = translation(3.0)
    X[1, 3] = np.nan
    with pytest.raises(mddual.InvalidInputError, match="X_WB"):
        mddual.distance(unit_cube, None, unit_cube, X)


# ---- errors --------------------------------------------------------------------

def test_zero_direction_raises_invalid_input(unit_cube):
    with pytest.raises(mddual.InvalidInputError, match="direction"):
        mddual.mdd(unit_cube, None, unit_cube, translation(3.0), [0.0, 0.0, 0.0])


def test_nan_pose_raises_invalid_input_naming_the_pose(unit_cube):
    X = translation(3.0)
    X[0, 3] = np.nan
    with pytest.raises(mddual.InvalidInputError, match="X_WB"):
        mddual.toi(unit_cube, None, unit_cube, X, [1.0, 0.0, 0.0])


def test_non_rigid_pose_raises_invalid_input(unit_cube):
    X = np.diag([2.0, 1.0, 1.0, 1.0])
    with pytest.raises(mddual.InvalidInputError, match="X_WA.*rigid"):
        mddual.intersect(unit_cube, X, unit_cube, None)


def test_pose_with_a_wrong_last_row_raises_invalid_input(unit_cube):
    X = translation(3.0)
    X[3, 0] = 1.0
    with pytest.raises(mddual.InvalidInputError, match=r"X_WB: the last row of a pose must be \[0, 0, 0, 1\]"):
        mddual.intersect(unit_cube, None, unit_cube, X)


@pytest.mark.parametrize("bad", [np.eye(3), np.eye(4)[:3], np.zeros(16)])
def test_pose_of_a_wrong_shape_is_a_value_error_naming_it(unit_cube, bad):
    with pytest.raises(ValueError, match=r"X_WA: expected a 4x4 pose.*got shape"):
        mddual.mdd(unit_cube, bad, unit_cube, None, [1.0, 0.0, 0.0])


def test_direction_of_a_wrong_shape_is_a_value_error_naming_it(unit_cube):
    with pytest.raises(ValueError, match=r"direction: expected a 3-vector, got shape \(2,\)"):
        mddual.mdd(unit_cube, None, unit_cube, None, [1.0, 0.0])


def test_non_numeric_pose_is_a_type_error_naming_it(unit_cube):
    with pytest.raises(TypeError, match="X_WB"):
        mddual.intersect(unit_cube, None, unit_cube, "identity")


def test_unknown_method_is_a_value_error(unit_cube):
    with pytest.raises(ValueError, match="method: expected 'mddual' or 'brute', got 'fast'"):
        mddual.mdd(unit_cube, None, unit_cube, None, [1.0, 0.0, 0.0], method="fast")
    with pytest.raises(ValueError, match="method: expected 'exact'"):
        mddual.penetration_depth(unit_cube, None, unit_cube, None, method="quick")


@pytest.mark.parametrize("delta", [1e4, -0.5, math.nan])
def test_delta_out_of_range_raises_invalid_input(unit_cube, delta):
    with pytest.raises(mddual.InvalidInputError, match="delta"):
        mddual.penetration_depth(unit_cube, None, unit_cube, translation(0.5), method="approx", delta=delta)


def test_polytope_argument_must_be_a_polytope(unit_cube):
    with pytest.raises(TypeError):
        mddual.mdd(cube_points(), None, unit_cube, None, [1.0, 0.0, 0.0])


def test_complex_date_and_string_values_are_refused(unit_cube):
    # A hostile-input hunt: NumPy's cast to float64 dropped the imaginary
    # part (direction -1j -> 0) and read dates and numeric strings as numbers.
    for bad in (np.array([-1j, 1, 0]), np.array(["-1", "0", "0"]), np.array([1, 2, 3], dtype="timedelta64[s]"),
                np.array([b"1", b"0", b"0"])):
        with pytest.raises(TypeError, match=r"direction: expected .* of dtype .*real numbers only"):
            mddual.mdd(unit_cube, None, unit_cube, translation(3.0), bad)
    with pytest.raises(TypeError, match="max_distance"):
        mddual.toi_batch(unit_cube, None, unit_cube, translation(3.0), [-1, 0, 0], max_distance="3")
    # Object arrays are converted by float() per element (Fraction, Decimal,
    # integers beyond 64 bits).
    from fractions import Fraction
    r = mddual.mdd(unit_cube, None, unit_cube, translation(3.0), np.array([Fraction(-1), 0, 2**70 * 0], dtype=object))
    assert r.distance == pytest.approx(2.0, abs=TOL)


def test_errors_other_than_a_bad_value_pass_through(unit_cube):
    class Raising:
        def __array__(self, dtype=None):
            raise RuntimeError("from __array__")

    with pytest.raises(RuntimeError, match="from __array__"):
        mddual.mdd(unit_cube, None, unit_cube, translation(3.0), Raising())


def test_a_method_name_is_shown_safely(unit_cube):
    with pytest.raises(ValueError, match=r"got '\?a'$"):
        mddual.intersect(unit_cube, None, unit_cube, None, method="\x00a")


def test_an_array_too_large_to_convert_raises_memory_error(unit_cube):
    # A broadcast view of 10^10 poses (no memory of its own) needs 1.2 TiB as
    # float64 in C order: NumPy's MemoryError, not "not convertible".
    X = np.broadcast_to(np.eye(4, dtype=np.float32), (10**10, 4, 4))
    with pytest.raises(MemoryError):
        mddual.intersect_batch(unit_cube, None, unit_cube, X)


def test_any_layout_and_numeric_dtype_is_accepted(unit_cube):
    # Fortran-order and strided arrays, integers and lists are converted.
    X = np.asfortranarray(translation(3.0))
    s = np.array([[-2, 9], [0, 9], [0, 9]])[:, 0]  # a strided int view
    r = mddual.mdd(unit_cube, np.eye(4, dtype=np.float32), unit_cube, X, s)
    assert r.distance == pytest.approx(2.0, abs=TOL)
    X_WB = np.stack([translation(3.0), translation(4.0)]).transpose(0, 2, 1).copy().transpose(0, 2, 1)
    out = mddual.mdd_batch(unit_cube, None, unit_cube, X_WB, [-1, 0, 0])
    np.testing.assert_allclose(out["distance"], [2.0, 3.0], atol=TOL)
    ints = mddual.ConvexPolytope([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)])
    assert ints.num_faces == 6
