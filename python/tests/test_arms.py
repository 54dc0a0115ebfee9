"""Arms: RobotModel (forward kinematics against a NumPy reimplementation from
the URDF's text), Srdf and AllowedCollisions, and ArmScene's checks on arm7's
problems: collides against clearance, check_edges against a dense sampling of
collides along each edge, and the errors."""

import functools
import math
import pathlib
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import mddual
from conftest import cube_points, translation

if not hasattr(mddual, "ArmScene"):  # built without the planning layer
    pytest.skip("mddual was built without the planning layer", allow_module_level=True)

ARM7 = pathlib.Path(__file__).resolve().parents[2] / "configs" / "arm7"
URDF = ARM7 / "arm7.urdf"
SRDF = ARM7 / "arm7.srdf"
# The largest joint step (radians, metres for the fingers) between two dense
# samples of an edge.
DENSE_STEP = 2e-3


@pytest.fixture(scope="module")
def model():
    return mddual.RobotModel.from_urdf(URDF)


@pytest.fixture(scope="module")
def srdf():
    return mddual.Srdf.load(SRDF)


@functools.lru_cache(maxsize=None)
def load_problem(problem_set):
    """The first problem of one of arm7's sets."""
    return mddual.load_arm_problem(URDF, SRDF, mddual.list_arm_problems(ARM7 / "problems" / problem_set)[0])


@pytest.fixture(scope="module")
def problem():
    return load_problem("box")


def random_configurations(problem, rng, count):
    """`count` configurations: the problem's start with the group's variables
    drawn uniformly within their limits."""
    lim = problem.model.limits
    Q = np.tile(problem.start, (count, 1))
    for v in problem.group_variables:
        Q[:, v] = rng.uniform(lim[v, 0], lim[v, 1], size=count)
    return Q


# --- forward kinematics against the URDF's text ------------------------------


def rpy_matrix(r, p, y):
    """URDF's fixed-axis roll, pitch, yaw: Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def axis_rotation(axis, angle):
    """Rodrigues' rotation about a unit axis."""
    k = np.asarray(axis) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def numpy_fk(urdf, variable_names, q):
    """Link poses in the root frame by name, from the URDF's joints alone."""
    joints = ET.parse(urdf).getroot().findall("joint")
    values = dict(zip(variable_names, q))
    by_child, children = {}, set()
    for j in joints:
        by_child[j.find("child").get("link")] = j
        children.add(j.find("child").get("link"))
    links = [l.get("name") for l in ET.parse(urdf).getroot().findall("link")]
    poses = {l: np.eye(4) for l in links if l not in children}

    def pose(link):
        if link in poses:
            return poses[link]
        j = by_child[link]
        origin = j.find("origin")
        X_PJ = np.eye(4)
        X_PJ[:3, :3] = rpy_matrix(*map(float, origin.get("rpy", "0 0 0").split()))
        X_PJ[:3, 3] = list(map(float, origin.get("xyz", "0 0 0").split()))
        motion = np.eye(4)
        if j.get("type") != "fixed":
            mimic = j.find("mimic")
            if mimic is None:
                value = values[j.get("name")]
            else:
                value = float(mimic.get("multiplier", 1)) * values[mimic.get("joint")] + float(mimic.get("offset", 0))
            axis = np.array(list(map(float, j.find("axis").get("xyz").split())))
            if j.get("type") == "prismatic":
                motion[:3, 3] = value * axis / np.linalg.norm(axis)
            else:
                motion[:3, :3] = axis_rotation(axis, value)
        poses[link] = pose(j.find("parent").get("link")) @ X_PJ @ motion
        return poses[link]

    return {l: pose(l) for l in links}


def test_model_names_and_limits(model):
    assert model.name == "arm7"
    assert model.num_variables == 8
    assert model.variable_names == [f"joint{i}" for i in range(1, 8)] + ["finger_left_joint"]
    assert model.link_names[0] == "base" and len(model.link_names) == model.num_links == 11
    assert model.limits.shape == (8, 2)
    assert model.limits[3].tolist() == [-3.0, -0.07]
    assert model.variable_index("joint4") == 3
    assert model.link_index("hand") == model.link_names.index("hand")
    joints = {j["name"]: j for j in model.joints}
    assert joints["finger_right_joint"]["mimic"] and joints["finger_right_joint"]["variable"] == 7
    assert joints["hand_mount"]["type"] == "fixed" and joints["hand_mount"]["variable"] == -1
    np.testing.assert_array_equal(joints["joint2"]["axis"], [0, 1, 0])
    # joint4's limits exclude 0: its default is their middle.
    np.testing.assert_allclose(model.default_configuration(), [0, 0, 0, -1.535, 0, 0, 0, 0])
    ready = model.configuration({"joint2": -0.3, "finger_right_joint": 0.5})  # the mimic joint is skipped
    assert ready[1] == -0.3 and ready[7] == 0.0
    assert len(model.link_pieces("link6")) >= 2 and isinstance(model.link_pieces(0)[0], mddual.ConvexPolytope)


def test_forward_kinematics_at_zero_sums_the_joint_offsets(model):
    # Every joint of arm7 is offset along z only: at q = 0 the link frames
    # stay unrotated, at the running sum of the offsets.
    fk = model.forward_kinematics(np.zeros(8))
    assert fk.shape == (11, 4, 4)
    heights = dict(base=0, link1=.15, link2=.35, link3=.65, link4=.75, link5=1.05, link6=1.15, link7=1.25,
                   hand=1.30, finger_left=1.36, finger_right=1.36)
    for name, X in zip(model.link_names, fk):
        np.testing.assert_allclose(X[:3, :3], np.eye(3), atol=1e-15)
        np.testing.assert_allclose(X[:3, 3], [0, 0, heights[name]], atol=1e-15)


def test_forward_kinematics_matches_numpy(model, problem):
    rng = np.random.default_rng(7)
    Q = random_configurations(problem, rng, 20)
    Q[:, 7] = rng.uniform(0, 0.04, size=20)
    fk = model.forward_kinematics(Q)
    assert fk.shape == (20, 11, 4, 4)
    for q, poses in zip(Q, fk):
        expected = numpy_fk(URDF, model.variable_names, q)
        for name, X in zip(model.link_names, poses):
            np.testing.assert_allclose(X, expected[name], atol=1e-12, err_msg=name)
    some = model.forward_kinematics(Q[0], links=["hand", "link3"])
    np.testing.assert_array_equal(some, fk[0][[model.link_index("hand"), model.link_index("link3")]])
    # The scene's poses are in the world frame: X_WB X_BL.
    np.testing.assert_allclose(problem.scene.forward_kinematics(Q), problem.scene.X_WB @ fk, atol=1e-14)


# --- SRDF and allowed collisions ----------------------------------------------


def test_srdf_groups_states_and_matrix(model, srdf):
    assert srdf.robot_name == "arm7"
    assert srdf.group_names == ["arm", "hand", "arm_hand"]
    assert srdf.group_variables(model, "arm") == list(range(7))
    assert srdf.group_variables(model, "hand") == [7]
    assert ("arm", "ready") in srdf.group_states
    ready = model.configuration(srdf.group_state(model, "arm", "ready"))
    np.testing.assert_allclose(ready[:7], [0, -0.3, 0, -1.2, 0, 1.4, 0.8])
    assert ("link1", "link2") in srdf.disabled_pairs

    acm = mddual.AllowedCollisions(model, srdf)
    assert acm.allowed("link1", "link2") and acm.allowed("link2", "link1")
    assert not acm.allowed("base", "hand")
    assert len(acm.allowed_pairs) == len(srdf.disabled_pairs)
    acm.allow("base", "hand")
    assert acm.allowed(0, np.int64(model.link_index("hand")))
    assert not acm.allowed_with_world("base")
    acm.allow_with_world("base")
    assert acm.allowed_with_world("base")
    assert not mddual.AllowedCollisions(model).allowed("link1", "link2")  # no SRDF: every pair


def test_scene_from_polytopes(model, srdf):
    # A 0.1 m cube at (0.3, 0, 0.37) touches nothing when the arm stands
    # along z, and holds link3's origin when joint2 turns it by 1.5 rad about
    # y (0.35 + 0.3 (sin 1.5, 0, cos 1.5)).
    cube = mddual.ConvexPolytope(cube_points(0.05, (0.3, 0.0, 0.37)))
    scene = mddual.ArmScene(model, [cube], srdf)
    upright = np.zeros(8)
    upright[3] = -0.07
    bent = upright.copy()
    bent[1] = 1.5  # joint2 about y: the arm leans over +x
    assert scene.collides(np.stack([upright, bent])).tolist() == [False, True]
    assert scene.world_piece_origins == ["world 0"]
    assert scene.contact(upright) is None
    hit = scene.contact(bent)
    assert hit["link"] in model.link_names and hit["other_link"] is None
    assert hit["world_piece"] == 0 and hit["world_piece_origin"] == "world 0"
    # The same world moved away by the base pose: nothing is reached.
    far = mddual.ArmScene(model, [cube], srdf, translation(-3.0))
    assert not far.collides(bent)
    np.testing.assert_allclose(far.forward_kinematics(bent)[0], translation(-3.0))
    # A link allowed to touch the world is not checked against it.
    acm = mddual.AllowedCollisions(model, srdf)
    for link in model.link_names:
        acm.allow_with_world(link)
    assert not mddual.ArmScene(model, [cube], acm).collides(bent)
    # Without a matrix every pair is checked, adjacent links included.
    bare = mddual.ArmScene(model)
    assert bare.collides(upright)
    hit = bare.contact(upright)
    assert hit["other_link"] in model.link_names and hit["world_piece"] is None


# --- the checks on a problem ----------------------------------------------------


def test_problem_start_goal_and_group(problem, model):
    assert problem.name == "box-0001" and problem.group == "arm"
    assert problem.group_variables == list(range(7))
    assert problem.group_variable_names == model.variable_names[:7]
    assert problem.files.number == 1
    scene = problem.scene
    assert scene.num_variables == 8 and scene.num_pairs > len(scene.self_pairs) > 0
    assert not scene.collides(problem.start) and not scene.collides(problem.goal)
    assert scene.clearance(problem.start) > 0
    lim = model.limits
    assert np.all((problem.goal >= lim[:, 0]) & (problem.goal <= lim[:, 1]))
    # The same problem from paths: the URDF, the SRDF and (scene, request).
    files = problem.files
    again = mddual.load_arm_problem(URDF, SRDF, (files.scene, files.request))
    np.testing.assert_array_equal(again.goal, problem.goal)


def test_witness_trajectory_is_certified_free(problem, tmp_path):
    assert problem.files.trajectory.name == "trajectory0001.yaml"
    Q = problem.load_trajectory()
    assert Q.shape[1] == problem.scene.num_variables and Q.shape[0] >= 2
    np.testing.assert_allclose(Q[0], problem.start, atol=1e-12)
    np.testing.assert_allclose(Q[-1], problem.goal, atol=1e-12)
    collides, _ = problem.scene.check_edges(Q[:-1], Q[1:])
    assert not collides.any()
    # A state through the base in the middle: both edges through it collide.
    folded = problem.start.copy()
    folded[[1, 3]] = [1.7, -3.0]
    bad = tmp_path / "t.yaml"
    names = ", ".join(problem.group_variable_names)
    bad.write_text("joint_trajectory:\n  joint_names: [%s]\n  points:\n" % names +
                   "".join("    - positions: [%s]\n" % ", ".join(repr(float(q[v])) for v in problem.group_variables)
                           for q in (Q[0], folded, Q[-1])))
    B = problem.load_trajectory(bad)
    np.testing.assert_array_equal(B[1], folded)
    assert problem.scene.check_edges(B[:-1], B[1:])[0].all()
    bad.write_text("joint_trajectory: {joint_names: [joint1], points: [{positions: [0]}]}")
    with pytest.raises(mddual.SceneError, match="lacks joint 'joint2' of group 'arm'"):
        problem.load_trajectory(bad)


def test_collides_and_clearance_agree(problem):
    scene = problem.scene
    Q = random_configurations(problem, np.random.default_rng(11), 300)
    collides = scene.collides(Q)
    clearance = scene.clearance(Q)
    assert collides.dtype == bool and clearance.shape == (300,)
    assert 30 <= collides.sum() <= 270, "both outcomes must occur"
    np.testing.assert_array_equal(clearance > 0, ~collides)
    # Two workers answer the same; a single configuration gives scalars.
    np.testing.assert_array_equal(scene.collides(Q, threads=2), collides)
    np.testing.assert_array_equal(scene.clearance(Q[:40], threads=0), clearance[:40])
    assert scene.collides(Q[0]) is bool(collides[0])
    assert scene.clearance(Q[0]) == clearance[0]


def dense_first_contact(scene, q0, q1):
    """The first of samples at most DENSE_STEP apart in every variable that
    collides (a fraction), or inf."""
    steps = max(1, math.ceil(np.abs(q1 - q0).max() / DENSE_STEP))
    t = np.linspace(0.0, 1.0, steps + 1)
    hits = np.flatnonzero(scene.collides(q0 + t[:, None] * (q1 - q0)))
    return t[hits[0]] if hits.size else math.inf


@pytest.mark.parametrize("problem_set", ["box", "bookshelf_thin"])
def test_check_edges_never_misses_a_dense_contact(problem_set):
    problem = load_problem(problem_set)
    scene = problem.scene
    rng = np.random.default_rng(5)
    # From free configurations, steps of up to 0.8 rad per joint: free and
    # colliding edges both.
    Q = random_configurations(problem, rng, 600)
    Q0 = Q[~scene.collides(Q)][:80]
    Q1 = Q0.copy()
    Q1[:, :7] += rng.uniform(-0.8, 0.8, size=(len(Q0), 7))
    collides, fraction = scene.check_edges(Q0, Q1, first_contact=True, threads=2)
    validity, unbounded = scene.check_edges(Q0, Q1)
    np.testing.assert_array_equal(validity, collides)
    assert np.all(np.isinf(unbounded[~collides])) and np.all(np.isnan(unbounded[collides]))
    dense = np.array([dense_first_contact(scene, a, b) for a, b in zip(Q0, Q1)])
    missed = np.flatnonzero(np.isfinite(dense) & ~collides)
    assert missed.size == 0, f"edges {missed} called free, a dense sample collides"
    hit = np.isfinite(dense)
    assert 10 <= hit.sum() <= len(Q0) - 10, "both outcomes must occur"
    assert np.all(fraction[hit] <= dense[hit])
    assert np.all((fraction[collides] >= 0) & (fraction[collides] <= 1))
    assert np.all(np.isinf(fraction[~collides]))
    # OMPL's lastValid query: the same decisions, a bound at most the
    # tolerance below the first contact (so below kFirstContact's bound too).
    tolerance = 0.05
    last, last_fraction = scene.check_edges(Q0, Q1, first_contact=True, fraction_tolerance=tolerance, threads=2)
    np.testing.assert_array_equal(last, collides)
    assert np.all(np.isinf(last_fraction[~collides]))
    assert np.all(last_fraction[hit] <= dense[hit])
    assert np.all(last_fraction[collides] >= fraction[collides] - tolerance)
    # Not vacuous: enough first contacts lie beyond the tolerance that a
    # bound of 0 (or any bound too low by more than it) fails above.
    assert np.sum(fraction[collides] > 2 * tolerance) >= 10
    # One start shared by every edge; a single edge gives scalars.
    shared, _ = scene.check_edges(Q0[0], Q1)
    assert shared[0] == collides[0]
    c0, f0 = scene.check_edges(Q0[0], Q1[0])
    assert c0 is bool(collides[0]) and (f0 == unbounded[0] or math.isnan(f0) and math.isnan(unbounded[0]))


# --- errors ---------------------------------------------------------------------


def test_shape_and_value_errors(problem):
    scene = problem.scene
    with pytest.raises(ValueError, match=r"Q: expected a \(K, 8\) array of configurations .* got shape \(7,\)"):
        scene.collides(np.zeros(7))
    with pytest.raises(ValueError, match=r"got shape \(2, 3, 8\)"):
        scene.clearance(np.zeros((2, 3, 8)))
    with pytest.raises(TypeError, match="Q: expected"):
        scene.collides("joint1")
    Q = np.tile(problem.start, (3, 1))
    Q[2, 4] = np.nan
    with pytest.raises(mddual.InvalidInputError, match=r"Q\[2\]: variable 'joint5' \(4\) is not finite"):
        scene.collides(Q)
    with pytest.raises(mddual.InvalidInputError, match=r"Q1\[2\]: variable 'joint5'"):
        scene.check_edges(problem.start, Q)
    with pytest.raises(ValueError, match=r"fraction_tolerance: expected a number in \[0, 1\], got nan"):
        scene.check_edges(problem.start, problem.start, first_contact=True, fraction_tolerance=math.nan)
    with pytest.raises(ValueError, match="fraction_tolerance: only with first_contact=True"):
        scene.check_edges(problem.start, problem.start, fraction_tolerance=0.1)
    with pytest.raises(ValueError, match="batch sizes differ: Q0 has 3 entries, Q1 has 2"):
        scene.check_edges(np.zeros((3, 8)), np.zeros((2, 8)))
    with pytest.raises(ValueError, match="q: expected one configuration, got a batch"):
        scene.contact(Q[:2])
    with pytest.raises(ValueError, match="threads"):
        scene.collides(Q[:2], threads=-1)
    with pytest.raises(mddual.InvalidInputError, match="contact_distance"):
        mddual.ArmScene(problem.model, contact_distance=0.0)
    with pytest.raises(ValueError, match="another RobotModel"):
        mddual.ArmScene(mddual.RobotModel.from_urdf(URDF), None, mddual.AllowedCollisions(problem.model))


def test_unknown_names_and_missing_files(model, srdf, problem, tmp_path):
    with pytest.raises(mddual.SceneError, match="no_such_link"):
        model.link_index("no_such_link")
    with pytest.raises(mddual.SceneError, match="no_such_link"):
        model.forward_kinematics(problem.start, links=["no_such_link"])
    with pytest.raises(IndexError, match="link index 11 is out of range"):
        mddual.AllowedCollisions(model).allow(0, 11)
    with pytest.raises(TypeError, match="link: expected a link name or index, got a float"):
        model.link_pieces(1.0)
    with pytest.raises(mddual.SceneError, match="no_such_joint"):
        model.configuration({"no_such_joint": 0.0})
    with pytest.raises(mddual.SceneError, match="no_such_group"):
        srdf.group_variables(model, "no_such_group")
    with pytest.raises(mddual.SceneError, match="no_such_group"):
        mddual.load_arm_problem(model, srdf, problem.files, group="no_such_group")
    with pytest.raises(mddual.SceneError, match="missing.urdf"):
        mddual.RobotModel.from_urdf(tmp_path / "missing.urdf")
    with pytest.raises(mddual.SceneError, match="missing.srdf"):
        mddual.Srdf.load(tmp_path / "missing.srdf")
    with pytest.raises(mddual.SceneError, match="nowhere"):
        mddual.list_arm_problems(tmp_path / "nowhere")
    with pytest.raises(TypeError, match="ArmProblemFiles"):
        mddual.load_arm_problem(model, srdf, 3)
    # A mesh found nowhere names every place searched, package_path included.
    (tmp_path / "robot.urdf").write_text(URDF.read_text())
    with pytest.raises(mddual.SceneError, match="extra_dir"):
        mddual.RobotModel.from_urdf(tmp_path / "robot.urdf", package_path=[tmp_path / "extra_dir"],
                                    use_environment=False)
    assert mddual.RobotModel.from_urdf(tmp_path / "robot.urdf", package_path=[ARM7.parent]).num_variables == 8
