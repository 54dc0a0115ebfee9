"""The Bullet peer checker 'hull-cast' (HullCastScene, ArmHullCastScene) next
to the exact checks, on the geometry of the C++ tests
(tests/planners/ompl/test_hull_cast_checkers.cpp) with the answers they
assert: exact on translations (the first failing segment before the contact),
the whole-edge cast blind to an obstacle inside a turning link's arc that the
segments see, the segments blind to a thin one between arc and chord, and the
arm's self pairs. Then seeded random edges: on translations the cast agrees
with Scene.check_edges edge for edge; on arm7, the whole-edge check is the
cast plus its end state."""

import math

import numpy as np
import pytest

import mddual
from conftest import translation

if not hasattr(mddual, "HullCastScene"):  # built without Bullet (or without the planning layer)
    pytest.skip("mddual was built without the hull-cast peer (Bullet)", allow_module_level=True)

from test_arms import load_problem, random_configurations  # noqa: E402

BOUNDS = [[-10.0, -10.0, -10.0], [10.0, 10.0, 10.0]]


def box(half, centre=(0.0, 0.0, 0.0)):
    """A box of half extents `half` around `centre`."""
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    return mddual.ConvexPolytope(np.asarray(centre, dtype=float) + corners * np.asarray(half, dtype=float))


def radial_box(angle, radius, half):
    """A box of half extents `half` (radial, tangential, z) centred at
    `radius` along the direction at `angle` about z, its radial axis along it."""
    c, s = math.cos(angle), math.sin(angle)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    return mddual.ConvexPolytope((corners * np.asarray(half) + [radius, 0.0, 0.0]) @ R.T)


def pose_se2(yaw):
    X = np.eye(4)
    X[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    return X


# --- rigid bodies -------------------------------------------------------------------


@pytest.fixture
def cubes():
    """A unit cube robot and a unit cube at x = 5 (R3)."""
    scene = mddual.Scene.from_polytopes([box([0.5] * 3)], [box([0.5] * 3, (5.0, 0.0, 0.0))], space="R3",
                                        bounds=BOUNDS)
    return scene, mddual.HullCastScene(scene)


def test_translation_agrees_with_the_exact_answer(cubes):
    scene, cast = cubes
    starts = np.array([[0.0, 0, 0], [0, 2, 0], [0, 1.001, 0], [0, 0.999, 0]])
    ends = starts + [9.0, 0, 0]
    expected = [True, False, False, True]  # through; 1 apart; 1e-3 apart; 1e-3 overlap
    for segments in ("resolution", "whole_edge"):
        assert cast.check_edges(starts, ends, segments=segments)["collides"].tolist() == expected, segments
    assert scene.check_edges(starts, ends)["collides"].tolist() == expected
    X_a = np.stack([translation(*s) for s in starts])
    X_b = np.stack([translation(*e) for e in ends])
    assert cast.cast_collides(X_a, X_b).tolist() == expected
    assert cast.cast_collides(X_a[0], X_b[0]) is True and cast.cast_collides(X_a[1], X_b[1]) is False


def test_last_valid_is_the_start_of_the_first_failing_segment(cubes):
    scene, cast = cubes
    a, b = [0.0, 0, 0], [9.0, 0, 0]
    n = cast.segment_count(a, b)
    assert n > 9  # segments shorter than the gap of 4 / 9 before the contact
    # The cubes touch at x = 4 (t = 4 / 9): the segment start just before.
    fraction = cast.check_edges(a, b)["fraction"][0]
    contact = 4.0 / 9.0
    assert contact - 1.0 / n < fraction <= contact
    assert fraction * n == pytest.approx(round(fraction * n), abs=1e-9)
    assert scene.check_edges(a, b)["fraction"][0] == pytest.approx(contact, abs=1e-9)
    assert cast.check_edges(a, b, segments="whole_edge")["fraction"][0] == 0.0
    assert np.isinf(cast.check_edges([0.0, 2, 0], [9.0, 2, 0])["fraction"][0])
    # An end outside the bounds fails the edge at 0 (the validator's check).
    out = cast.check_edges([0.0, 2, 0], [11.0, 2, 0])
    assert out["collides"][0] and out["fraction"][0] == 0.0


def turning_link(obstacle, half_width=0.05):
    """A link 2 long and 2 half_width wide turning about one end (SE2) past `obstacle`."""
    link = box([1.0, half_width, 0.25], (1.0, 0.0, 0.0))
    scene = mddual.Scene.from_polytopes([link], [obstacle], space="SE2", bounds=BOUNDS)
    return scene, mddual.HullCastScene(scene)


def test_whole_edge_cast_misses_an_obstacle_the_segments_see():
    # A small box on the arc's bisector at radius 1.7 to 1.9. The hull of the
    # link's two end poses reaches only 2 cos(45 deg) + 0.05 sin(45 deg) = 1.45
    # along the bisector: one cast between the ends calls the edge free, the
    # link passes through the box at 45 degrees.
    scene, cast = turning_link(radial_box(math.pi / 4, 1.8, [0.1, 0.1, 0.5]))
    a, b, mid = [0.0, 0.0, 0.0], [0.0, 0.0, math.pi / 2], [0.0, 0.0, math.pi / 4]
    assert scene.is_valid(np.array([a, b, mid])).tolist() == [True, True, False]  # a real collision
    assert cast.cast_collides(pose_se2(0.0), pose_se2(math.pi / 2)) is False, "the cast now sees the arc"
    assert not cast.check_edges(a, b, segments="whole_edge")["collides"][0]
    assert cast.check_edges(a, b)["collides"][0]  # OMPL's segments see it
    exact = scene.check_edges(a, b)
    assert exact["collides"][0] and 0.0 < exact["fraction"][0] <= 0.5


def test_segments_miss_a_thin_obstacle_between_arc_and_chord():
    # A thin link (0.004 wide): a segment turning 2 alpha about the link's end
    # has a hull reaching h = 2 cos(alpha) + 0.002 sin(alpha) along its
    # bisector, short of the link's reach of 2. A box beyond h on the middle
    # segment's bisector is outside every segment's hull; the link passes
    # through it there.
    _, probe = turning_link(radial_box(math.pi, 5.0, [0.1, 0.1, 0.1]))
    a, b = [0.0, 0.0, 0.0], [0.0, 0.0, math.pi / 2]
    n = probe.segment_count(a, b)
    assert n >= 2
    alpha = math.pi / 4 / n
    bisector = math.pi / 2 * (n // 2 + 0.5) / n
    h = 2.0 * math.cos(alpha) + 0.002 * math.sin(alpha)
    r0, r1 = h + 5e-5, 2.05
    assert r0 < 2.0, f"no sliver between arc and chord at {n} segments"
    scene, cast = turning_link(radial_box(bisector, (r0 + r1) / 2, [(r1 - r0) / 2, 0.02, 0.5]), 0.002)
    assert scene.is_valid(np.array([a, b, [0.0, 0.0, bisector]])).tolist() == [True, True, False]
    assert not cast.check_edges(a, b)["collides"][0], "the segments now see the sliver"
    assert scene.check_edges(a, b)["collides"][0]


def test_random_translations_agree_with_the_exact_check():
    # On a translation the hull of a piece's two poses is its swept volume: the
    # cast, the whole-edge and the segmented checks all answer as the exact one.
    rng = np.random.default_rng(20261201)
    world = [box(rng.uniform(0.2, 0.8, 3), rng.uniform(-3.0, 3.0, 3)) for _ in range(12)]
    robot = [box([0.3, 0.2, 0.1]), box([0.1, 0.1, 0.4], (0.3, 0.0, 0.0))]
    scene = mddual.Scene.from_polytopes(robot, world, space="R3", bounds=[[-4.0] * 3, [4.0] * 3])
    cast = mddual.HullCastScene(scene)
    starts = rng.uniform(-3.5, 3.5, (300, 3))
    ends = np.clip(starts + rng.uniform(-2.5, 2.5, (300, 3)), -3.9, 3.9)
    exact = scene.check_edges(starts, ends)["collides"]
    assert 50 <= exact.sum() <= 250, "both outcomes must occur"
    np.testing.assert_array_equal(cast.check_edges(starts, ends, segments="whole_edge")["collides"], exact)
    np.testing.assert_array_equal(cast.check_edges(starts, ends)["collides"], exact)
    X_a = np.stack([translation(*s) for s in starts])
    X_b = np.stack([translation(*e) for e in ends])
    np.testing.assert_array_equal(cast.cast_collides(X_a, X_b), exact)


# --- arms ---------------------------------------------------------------------------


def planar_arm_urdf(folder, lengths, half_width=0.05, half_height=0.05):
    """examples::planarArm as a URDF: links of boxes along x turning about z,
    each joint at the end of the link before."""
    parts = ['<robot name="planar_arm">', '<link name="base"/>']
    for i, length in enumerate(lengths, start=1):
        parts.append(f'<link name="link{i}"><collision><origin xyz="{length / 2} 0 0"/><geometry>'
                     f'<box size="{length} {2 * half_width} {2 * half_height}"/></geometry></collision></link>')
        parent = "base" if i == 1 else f"link{i - 1}"
        x = 0.0 if i == 1 else lengths[i - 2]
        parts.append(f'<joint name="joint{i}" type="revolute"><parent link="{parent}"/><child link="link{i}"/>'
                     f'<origin xyz="{x} 0 0"/><axis xyz="0 0 1"/>'
                     f'<limit lower="{-math.pi!r}" upper="{math.pi!r}" effort="1" velocity="1"/></joint>')
    parts.append("</robot>")
    path = folder / f"planar_{len(lengths)}_{half_width}.urdf"
    path.write_text("\n".join(parts))
    return mddual.RobotModel.from_urdf(path)


def planar_arm(folder, obstacles, lengths=(1.0, 1.0), half_width=0.05):
    """The arm over `obstacles`, adjacent links allowed to touch, with its cast."""
    model = planar_arm_urdf(folder, lengths, half_width)
    allowed = mddual.AllowedCollisions(model)
    for k in range(model.num_links - 1):
        allowed.allow(k, k + 1)
    scene = mddual.ArmScene(model, obstacles, allowed)
    return scene, mddual.ArmHullCastScene(scene)


Q0, Q1, MID = np.array([-math.pi / 4, 0.0]), np.array([math.pi / 4, 0.0]), np.array([0.0, 0.0])


def test_arm_whole_edge_cast_misses_an_obstacle_the_segments_see(tmp_path):
    # Joint 1 turns from -45 to +45 degrees: the tip's arc reaches x = 2 on the
    # bisector, the hull of link 2's end poses only 1.45. A box at x in
    # [1.65, 1.85] is inside the arc, outside that hull.
    scene, cast = planar_arm(tmp_path, [box([0.1] * 3, (1.75, 0.0, 0.0))])
    assert scene.collides(np.stack([Q0, Q1, MID])).tolist() == [False, False, True]
    assert scene.check_edges(Q0, Q1)[0]
    assert cast.check_edges(Q0, Q1)[0] and cast.check_edges(Q1, Q0)[0]
    assert cast.check_edges(Q0, Q1, segments="whole_edge") == (False, math.inf)
    assert cast.cast_collides(Q0, Q1) is False, "the arm cast now sees the arc"
    assert cast.cast_contact(Q0, Q1) is None
    # A short edge that ends in the box is seen by both.
    assert cast.cast_contact(Q0, MID) == {"link": "link2", "other_link": None, "world_piece": 0,
                                          "world_piece_origin": "world 0"}


def test_arm_segments_miss_a_thin_obstacle_between_arc_and_chord(tmp_path):
    _, probe = planar_arm(tmp_path, [box([0.1] * 3, (5.0, 0.0, 0.0))], half_width=0.005)
    n = probe.segment_count(Q0, Q1)
    assert n >= 2
    alpha = math.pi / 4 / n
    bisector = -math.pi / 4 + math.pi / 2 * (n // 2 + 0.5) / n
    h = 2.0 * math.cos(alpha) + 0.005 * math.sin(alpha)
    assert h + 2e-4 < 2.0, f"no sliver between arc and chord at {n} segments"
    r0, r1 = h + 2e-4, 2.05
    scene, cast = planar_arm(tmp_path, [radial_box(bisector, (r0 + r1) / 2, [(r1 - r0) / 2, 0.02, 0.1])],
                             half_width=0.005)
    assert scene.collides(np.stack([Q0, Q1, [bisector, 0.0]])).tolist() == [False, False, True]
    assert scene.check_edges(Q0, Q1)[0]
    assert cast.check_edges(Q0, Q1) == (False, math.inf), "the segments now see the sliver"


def test_arm_sees_a_collision_at_the_end_pose(tmp_path):
    # The box around link 2's middle at +45 degrees: the end state collides,
    # every check refuses the edge; the cast's fraction is a segment start
    # before the first contact.
    scene, cast = planar_arm(tmp_path, [box([0.08, 0.08, 0.1], math.sqrt(0.5) * np.array([1.5, 1.5, 0.0]))])
    assert not scene.collides(Q0) and scene.collides(Q1)
    collides, first = scene.check_edges(Q0, Q1, first_contact=True)
    assert collides and first > 0.1
    for segments in ("resolution", "whole_edge"):
        hit, fraction = cast.check_edges(Q0, Q1, segments=segments)
        assert hit and 0.0 <= fraction <= first, segments
    t = np.linspace(0.0, 1.0, 1001)
    dense = t[np.flatnonzero(scene.collides(Q0 + t[:, None] * (Q1 - Q0)))[0]]
    assert cast.check_edges(Q0, Q1)[1] <= dense


def test_arm_cast_checks_the_self_pairs(tmp_path):
    # Link 3 folds back onto link 1 over a short link 2 (links 1 and 3 are
    # checked, adjacent ones not); no world.
    scene, cast = planar_arm(tmp_path, [], lengths=(1.0, 0.06, 1.0))
    open_, folded = np.zeros(3), np.array([0.0, math.pi / 2, math.pi / 2])
    assert not scene.collides(open_) and scene.collides(folded)
    hit = cast.cast_contact(open_, folded)
    assert hit["link"] == "link1" and hit["other_link"] == "link3" and hit["world_piece"] is None
    assert cast.cast_collides(open_, open_) is False


def test_arm_whole_edge_check_is_the_cast_and_its_end_state():
    # Seeded random edges on arm7's box problem within the joint limits: the
    # whole-edge check refuses exactly the edges whose cast hits or whose end
    # state collides; threads change nothing.
    problem = load_problem("box")
    scene = problem.scene
    cast = mddual.ArmHullCastScene(scene)
    rng = np.random.default_rng(7)
    Q = random_configurations(problem, rng, 600)
    Q0 = Q[~scene.collides(Q)][:200]
    lim = problem.model.limits
    Q1 = np.clip(Q0 + rng.uniform(-0.6, 0.6, Q0.shape), lim[:, 0], lim[:, 1])
    whole, fraction = cast.check_edges(Q0, Q1, segments="whole_edge", threads=2)
    casts = cast.cast_collides(Q0, Q1)
    assert 20 <= casts.sum() <= 180, "both outcomes must occur"
    np.testing.assert_array_equal(whole, casts | scene.collides(Q1))
    assert np.all(fraction[whole] == 0.0) and np.all(np.isinf(fraction[~whole]))
    segmented, _ = cast.check_edges(Q0, Q1)
    np.testing.assert_array_equal(cast.check_edges(Q0, Q1, threads=2)[0], segmented)
    np.testing.assert_array_equal(cast.cast_collides(Q0, Q1, threads=0), casts)
    hit, _ = cast.check_edges(Q0[0], Q1[0])
    assert type(hit) is bool and hit == segmented[0]


def test_bad_arguments(cubes, tmp_path):
    _, cast = cubes
    with pytest.raises(ValueError, match="segments: expected 'resolution' or 'whole_edge', got 'fine'"):
        cast.check_edges([0.0, 0, 0], [1.0, 0, 0], segments="fine")
    with pytest.raises(TypeError, match="segments: expected 'resolution' or 'whole_edge', got a int"):
        cast.check_edges([0.0, 0, 0], [1.0, 0, 0], segments=1)
    with pytest.raises(ValueError, match="batch sizes differ: starts has 3 entries, ends has 2"):
        cast.check_edges(np.zeros((3, 3)), np.zeros((2, 3)))
    with pytest.raises(ValueError, match="expected one state each"):
        cast.segment_count(np.zeros((2, 3)), np.zeros(3))
    with pytest.raises(mddual.InvalidInputError, match=r"starts\[1\]: component 2 is not finite"):
        cast.check_edges([[0.0, 0, 0], [0, 0, np.nan]], [1.0, 0, 0])
    with pytest.raises(TypeError):
        mddual.HullCastScene(None)
    scene, arm = planar_arm(tmp_path, [])
    with pytest.raises(ValueError, match="Q0: expected a \\(K, 2\\) array of configurations"):
        arm.check_edges(np.zeros(3), np.zeros(2))
    with pytest.raises(ValueError, match="expected one configuration each"):
        arm.cast_contact(np.zeros((2, 2)), np.zeros(2))
    with pytest.raises(ValueError, match="threads"):
        arm.check_edges(np.zeros(2), np.zeros(2), threads=-1)
    with pytest.raises(TypeError):
        mddual.ArmHullCastScene(mddual.HullCastScene)
