"""mddual.Scene: configs loaded from files, state validity, edge checks and
directed clearance on arrays, against closed forms on boxes and against the
core's queries (through this module) on the same pieces."""

import math
import pathlib

import numpy as np
import pytest

import mddual
from conftest import random_rotation, translation

if not hasattr(mddual, "Scene"):  # built without the planning layer
    pytest.skip("mddual was built without the planning layer", allow_module_level=True)

CONFIGS = pathlib.Path(__file__).resolve().parents[2] / "configs"
TOL = 1e-9

BOX_URDF = """<?xml version="1.0"?>
<robot name="{name}">
  <link name="{name}_link">
    <collision>
      <origin xyz="{x} {y} {z}" rpy="0 0 0"/>
      <geometry><box size="{size} {size} {size}"/></geometry>
    </collision>
  </link>
</robot>
"""

CFG = """[problem]
name = boxes
robot = robot.urdf
world = world.urdf
start.x = -3
start.y = 0
start.z = 0
start.axis.x = 0
start.axis.y = 0
start.axis.z = 1
start.theta = 0
goal.x = 3
goal.y = 0
goal.z = 0
goal.axis.x = 0
goal.axis.y = 0
goal.axis.z = 1
goal.theta = 0
volume.min.x = -5
volume.min.y = -5
volume.min.z = -5
volume.max.x = 5
volume.max.y = 5
volume.max.z = 5
{extra}
[planner]
rrtconnect =
"""


def write_boxes(folder, extra=""):
    """A unit-cube robot and a unit-cube world piece at the origin."""
    (folder / "robot.urdf").write_text(BOX_URDF.format(name="robot", x=0, y=0, z=0, size=1))
    (folder / "world.urdf").write_text(BOX_URDF.format(name="world", x=0, y=0, z=0, size=1))
    cfg = folder / "boxes.cfg"
    cfg.write_text(CFG.format(extra=extra))
    return cfg


@pytest.fixture
def boxes(tmp_path):
    return mddual.Scene.load(write_boxes(tmp_path))


@pytest.fixture
def boxes_r3(tmp_path):
    return mddual.Scene.load(write_boxes(tmp_path, "translation_only = true"))


def test_load_reads_the_config(boxes):
    assert boxes.name == "boxes"
    assert boxes.space == "SE3"
    assert boxes.state_dimension == 7
    np.testing.assert_array_equal(boxes.bounds, [[-5, -5, -5], [5, 5, 5]])
    np.testing.assert_array_equal(boxes.start, translation(-3.0))
    np.testing.assert_allclose(boxes.start_state, [-3, 0, 0, 0, 0, 0, 1])
    assert len(boxes.robot_pieces) == 1 and len(boxes.world_pieces) == 1
    assert boxes.robot_pieces[0].num_vertices == 8
    assert "robot.urdf" in boxes.robot_piece_origins[0]
    assert boxes.warnings == []
    assert "boxes" in repr(boxes)


def test_state_and_pose_round_trip(boxes, rng):
    X = translation(1.0, -2.0, 0.5)
    X[:3, :3] = random_rotation(rng)
    np.testing.assert_allclose(boxes.pose(boxes.state(X)), X, atol=1e-12)


def test_translation_only_space(boxes_r3):
    assert boxes_r3.space == "R3"
    np.testing.assert_array_equal(boxes_r3.start_state, [-3, 0, 0])
    with pytest.raises(mddual.InvalidInputError):
        X = np.eye(4)
        X[:3, :3] = random_rotation(np.random.default_rng(1))
        boxes_r3.state(X)


def test_collides_closed_form(boxes):
    # Unit cubes: they meet when the robot's centre is within 1 along x.
    xs = np.array([-3.0, -1.0 - 1e-6, -1.0, 0.0, 0.999, 1.0 + 1e-6])
    poses = np.stack([translation(x) for x in xs])
    assert boxes.collides(poses).tolist() == [False, False, True, True, True, False]
    assert boxes.collides(translation(0.5)) is True
    assert boxes.collides(None) is True


def test_is_valid_checks_bounds_and_collision(boxes_r3):
    states = np.array([[-3, 0, 0], [0.5, 0, 0], [4.9, 0, 0], [5.5, 0, 0]], dtype=float)
    assert boxes_r3.is_valid(states).tolist() == [True, False, True, False]
    assert boxes_r3.is_valid([-3, 0, 0]) is True


def test_check_edges_translation_first_contact_is_exact(boxes_r3):
    # From x = -3 to x = 3: the robot's front face reaches the world's at x = -1,
    # a third of the way.
    out = boxes_r3.check_edges([[-3, 0, 0], [-3, 2, 0]], [[3, 0, 0], [3, 2, 0]])
    assert out["collides"].tolist() == [True, False]
    assert out["fraction"][0] == pytest.approx(1.0 / 3.0, abs=TOL)
    assert math.isinf(out["fraction"][1])
    assert out["exact"].all()
    assert not out["start_collides"].any()


def test_check_edges_rotating_edge_is_sound(boxes, rng):
    # Rotating edges near the world cube: every state before the reported
    # fraction is free (a lower bound), and a colliding sampled state means
    # the edge collides. Guard: enough edges must hit for these to be tested.
    hits = 0
    for _ in range(30):
        X1 = translation(*rng.uniform(-2.5, 2.5, size=3))
        X1[:3, :3] = random_rotation(rng)
        X2 = translation(*rng.uniform(-2.5, 2.5, size=3))
        X2[:3, :3] = random_rotation(rng)
        s1, s2 = boxes.state(X1), boxes.state(X2)
        out = boxes.check_edges(s1, s2)
        frac = out["fraction"][0]
        ts = np.linspace(0.0, 1.0, 201)
        # Sampled states by OMPL-like interpolation (positions linear; the
        # orientation by slerp) through the module's own pose().
        q1, q2 = s1[3:], s2[3:]
        if np.dot(q1, q2) < 0:
            q2 = -q2
        hit = False
        for t in ts:
            omega = math.acos(min(1.0, abs(float(np.dot(q1, q2)))))
            if omega < 1e-12:
                q = q1
            else:
                q = (math.sin((1 - t) * omega) * q1 + math.sin(t * omega) * q2) / math.sin(omega)
            state = np.concatenate([(1 - t) * s1[:3] + t * s2[:3], q])
            collides = boxes.collides(boxes.pose(state))
            if collides:
                hit = True
                assert t >= frac - 1e-9
        if hit:
            hits += 1
            assert out["collides"][0]
    assert hits >= 10  # 15 of the 30 edges


def test_directed_clearance_closed_form(boxes):
    out = boxes.directed_clearance(np.stack([translation(-3.0), translation(-3.0), translation(0.25)]),
                                   [[1, 0, 0], [0, 1, 0], [1, 0, 0]])
    # The robot's front face (x = -2.5) reaches the world's (x = -0.5).
    assert out["distance"][0] == pytest.approx(2.0, abs=TOL)
    assert math.isinf(out["distance"][1])
    np.testing.assert_allclose(out["normal"][0], [-1, 0, 0], atol=TOL)
    assert out["point"][0][0] == pytest.approx(-0.5, abs=TOL)
    assert out["robot_piece"][0] == 0 and out["world_piece"][0] == 0
    assert out["start_collides"].tolist() == [False, False, True]
    assert out["distance"][2] == pytest.approx(-0.75, abs=TOL)
    short = boxes.directed_clearance(translation(-3.0), [1, 0, 0], max_distance=1.5)
    assert math.isinf(short["distance"][0])


def test_thin_walls_known_answers():
    scene = mddual.Scene.load(CONFIGS / "thin_walls" / "thin_walls.cfg")
    assert scene.space == "R3"
    # The cube (0.8 across) starts at x = 1; the first wall's face is at x = 3.995.
    out = scene.check_edges(scene.start_state, scene.goal_state)
    assert out["collides"][0]
    assert out["fraction"][0] == pytest.approx((3.995 - 1.4) / 18.0, abs=TOL)
    clear = scene.directed_clearance(scene.start, [1, 0, 0])
    assert clear["distance"][0] == pytest.approx(2.595, abs=TOL)


@pytest.mark.parametrize("cfg", ["thin_walls/thin_walls.cfg", "maze_se2/maze_se2.cfg"])
def test_scene_answers_equal_the_core_on_the_same_pieces(cfg, rng):
    scene = mddual.Scene.load(CONFIGS / cfg)
    robot, world = scene.robot_pieces, scene.world_pieces
    lo, hi = scene.bounds
    K = 60
    states = []
    for _ in range(K):
        p = rng.uniform(lo, hi)
        X = translation(*p)
        if scene.space == "SE2":
            yaw = rng.uniform(-math.pi, math.pi)
            X[:3, :3] = [[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0], [0, 0, 1]]
            X[2, 3] = 0.0
        elif scene.space == "R3":
            X[:3, :3] = scene.start[:3, :3]
        states.append(X)
    poses = np.stack(states)
    directions = rng.normal(size=(K, 3))
    if scene.space == "SE2":
        directions[:, 2] = 0.0
    collides = scene.collides(poses)
    clearance = scene.directed_clearance(poses, directions)
    assert {True, False} == set(collides.tolist())
    for k in range(K):
        core = any(mddual.intersect(w, None, r, poses[k]).intersecting for w in world for r in robot)
        assert collides[k] == core
        assert clearance["start_collides"][k] == core
        if not core:
            tois = [mddual.toi(w, None, r, poses[k], directions[k]).toi for w in world for r in robot]
            expected = min(tois)
            got = clearance["distance"][k]
            assert got == expected or abs(got - expected) <= TOL * max(1.0, abs(expected)), (k, got, expected)


def test_bad_inputs_raise(boxes, tmp_path):
    with pytest.raises(ValueError, match=r"states: expected a \(K, 7\) array"):
        boxes.is_valid(np.zeros((2, 3)))
    with pytest.raises(mddual.InvalidInputError, match=r"states\[1\]: component 0 is not finite"):
        boxes.is_valid(np.array([[0, 0, 0, 0, 0, 0, 1], [np.nan, 0, 0, 0, 0, 0, 1]]))
    with pytest.raises(ValueError, match="batch sizes differ: starts has 2 entries, ends has 3"):
        boxes.check_edges(np.zeros((2, 7)) + [0, 0, 0, 0, 0, 0, 1], np.zeros((3, 7)) + [0, 0, 0, 0, 0, 0, 1])
    with pytest.raises(mddual.InvalidInputError, match="directed_clearance: query 0: .*direction"):
        boxes.directed_clearance(translation(-3.0), [0, 0, 0])
    with pytest.raises(ValueError, match=r"X_WR: expected a \(K, 4, 4\)"):
        boxes.collides(np.zeros((3, 3)))
    with pytest.raises(mddual.SceneError, match="missing.cfg") as info:
        mddual.Scene.load(tmp_path / "missing.cfg")
    assert isinstance(info.value, mddual.InvalidInputError)
    bad = tmp_path / "bad.cfg"
    bad.write_text(CFG.format(extra="").replace("start.x = -3", "start.x = abc"))
    with pytest.raises(mddual.SceneError, match=r"bad.cfg:5: start.x: 'abc' is not a number"):
        mddual.Scene.load(bad)


def test_quaternions_are_made_unit_and_one_of_no_rotation_is_refused(boxes):
    # A hostile-input hunt: a zero quaternion aborted the interpreter in
    # check_edges (OMPL's SO(3) assertion) and was the identity in pose();
    # one of 1e200 gave a pose of infinities. Below a norm of 1e-12 (the
    # planning layer's "no rotation") it is refused.
    for q in ([0, 0, 0, 0], [0, 0, 0, 1e-300], [1e-13, 0, 0, 0]):
        state = [3, 0, 0] + q
        for call in (lambda: boxes.check_edges([3, 0, 0, 0, 0, 0, 1], state), lambda: boxes.pose(state),
                     lambda: boxes.is_valid(state)):
            with pytest.raises(mddual.InvalidInputError,
                               match=r"the quaternion \(components 3 to 6\) has norm .*, below 1e-12: not a rotation"):
                call()
    with pytest.raises(mddual.InvalidInputError, match=r"ends\[1\]: the quaternion .* has norm 0,"):
        boxes.check_edges([3, 0, 0, 0, 0, 0, 1], [[3, 0, 0, 0, 0, 0, 1], [3, 0, 0, 0, 0, 0, 0]])
    half_turn = np.diag([1.0, -1.0, -1.0])  # about x
    for scale in (1e200, 2.0, 1e-12):
        np.testing.assert_allclose(boxes.pose([1, 2, 3, scale, 0, 0, 0])[:3, :3], half_turn, atol=1e-15)
    edge = boxes.check_edges([3, 0, 0, 0, 0, 0, 1], [3, 0, 0, 0, 0, 0, 1e-6])
    assert not edge["collides"][0]


# ---- scenes from memory -----------------------------------------------------------

def test_from_polytopes_equals_the_loaded_scene(boxes, tmp_path, rng):
    cube = mddual.ConvexPolytope(np.array([[x, y, z] for x in (-.5, .5) for y in (-.5, .5) for z in (-.5, .5)]))
    mem = mddual.Scene.from_polytopes([cube], [cube], space="SE3", bounds=[[-5, -5, -5], [5, 5, 5]],
                                      start=translation(-3.0), goal=translation(3.0), name="boxes")
    assert mem.space == "SE3" and mem.name == "boxes"
    np.testing.assert_array_equal(mem.start_state, boxes.start_state)
    poses = np.stack([translation(*rng.uniform(-2.5, 2.5, size=3)) for _ in range(100)])
    for k in range(len(poses)):
        poses[k, :3, :3] = random_rotation(rng)
    assert mem.collides(poses).tolist() == boxes.collides(poses).tolist()
    directions = rng.normal(size=(100, 3))
    a = mem.directed_clearance(poses, directions)["distance"]
    b = boxes.directed_clearance(poses, directions)["distance"]
    np.testing.assert_array_equal(a, b)
    starts = np.stack([mem.state(X) for X in poses[:50]])
    ends = np.stack([mem.state(X) for X in poses[50:]])
    np.testing.assert_array_equal(mem.check_edges(starts, ends)["fraction"],
                                  boxes.check_edges(starts, ends)["fraction"])


def test_from_polytopes_planar_and_empty_world():
    square = mddual.ConvexPolytope([[x, y, z] for x in (-.5, .5) for y in (-.5, .5) for z in (-.5, .5)])
    free = mddual.Scene.from_polytopes([square], [], space="R2", bounds=[[0, 0, 0], [10, 10, 0]])
    assert free.state_dimension == 2
    assert free.is_valid([[1, 1], [11, 1]]).tolist() == [True, False]
    assert free.check_edges([1, 1], [9, 9])["collides"].tolist() == [False]


def test_from_polytopes_bad_inputs():
    cube = mddual.ConvexPolytope(np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]))
    with pytest.raises(mddual.SceneError):
        mddual.Scene.from_polytopes([], [cube], bounds=[[0, 0, 0], [1, 1, 1]])
    with pytest.raises(ValueError, match="space: expected 'SE2', 'SE3', 'R2' or 'R3', got 'se4'"):
        mddual.Scene.from_polytopes([cube], [], space="se4", bounds=[[0, 0, 0], [1, 1, 1]])
    with pytest.raises(ValueError, match=r"bounds: expected a \(2, 3\) array"):
        mddual.Scene.from_polytopes([cube], [], bounds=[0, 0, 0, 1, 1, 1])
    with pytest.raises(mddual.InvalidInputError):  # an empty box
        mddual.Scene.from_polytopes([cube], [], bounds=[[1, 1, 1], [0, 0, 0]])
    with pytest.raises(mddual.InvalidInputError):  # an SE2 start off the plane
        mddual.Scene.from_polytopes([cube], [], space="SE2", bounds=[[0, 0, 0], [5, 5, 0]],
                                    start=translation(1.0, 1.0, 2.0))
    with pytest.raises(TypeError):
        mddual.Scene.from_polytopes([np.eye(3)], [], bounds=[[0, 0, 0], [1, 1, 1]])
