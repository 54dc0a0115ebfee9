"""The Panda's sets in MotionBenchMaker's scenes (scripts/mbm_panda.py): the
committed problems are what the script makes (its first problems of two sets,
made again here, byte for byte; table_under_pick's start IK takes minutes per
problem and is left to the C++ tests of the committed files), a problem it
makes meets its query (the goal's panda_link8 inside the query's position box
and orientation tolerances, start and goal CLEARANCE from the scene's pieces),
a query in closed form, and the cage left out for its reason."""

import math
import pathlib
import random
import sys

import numpy as np
import pytest

import mddual

if not hasattr(mddual, "ArmScene"):  # built without the planning layer
    pytest.skip("mddual was built without the planning layer", allow_module_level=True)

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import mbm_panda  # noqa: E402

PANDA = ROOT / "configs" / "panda"


@pytest.fixture(scope="module")
def panda():
    return mbm_panda.Panda(str(PANDA))


@pytest.mark.parametrize("kind", ["mbm_bookshelf_thin", "mbm_table_pick"])
def test_committed_problems_are_the_scripts(panda, kind):
    made = mbm_panda.problem_files(panda, kind, 2)
    assert len(made) == 4
    for name, text in made.items():
        assert (PANDA / "problems" / kind / name).read_text() == text, name


def _miss(panda, q, target):
    X = panda.model.forward_kinematics(panda.full(q), ["panda_link8"])[0]
    return np.concatenate([X[:3, 3] - target[:3, 3], mbm_panda.rotation_vector(target[:3, :3].T @ X[:3, :3])])


def test_a_problem_meets_its_query(panda):
    template = mbm_panda.SETS["mbm_table_pick"]
    scene, start, goal, _ = mbm_panda.problem(panda, template, random.Random(5))
    target, pos_tol, orn_tol = mbm_panda.query_target(scene, template["goals"][0], template["ee_offset"])
    miss = _miss(panda, goal, target)
    assert np.all(np.abs(miss[:3]) <= np.asarray(pos_tol) / 2), miss
    assert np.all(np.abs(miss[3:]) <= orn_tol), miss
    check = mddual.ArmScene(panda.model, mbm_panda.world_pieces(scene), panda.srdf)
    assert check.clearance(panda.full(start)) >= mbm_panda.CLEARANCE
    assert check.clearance(panda.full(goal)) >= mbm_panda.CLEARANCE
    # Not a trivial sample: the goal is far from the start.
    assert np.abs(np.asarray(goal) - np.asarray(start)).max() > 0.5


def test_the_box_query_in_closed_form():
    """Without variation, the box query puts panda_link8 8 cm below the query point, 25 cm above
    the can: 17 cm above it, its z axis (the approach) pointing down."""
    template = mbm_panda.BOX
    scene = mbm_panda.sample_scene(dict(template, world=((0, 0, 0), 0.0), object_variations=[]), random.Random(1))
    can = np.array([0.8 - 0.15, 0.0, 0.55 - 1.02])  # the template's can, moved by the base offset
    assert np.allclose(scene["Can1"][2][:3, 3], can)
    target, _, _ = mbm_panda.query_target(scene, template["goals"][0], template["ee_offset"])
    assert np.allclose(target[:3, 3], can + [0, 0, 0.17], atol=1e-3)
    assert np.allclose(target[:3, 2], [0, 0, -1], atol=1e-3)


def test_rotation_helpers_round_trip():
    rng = np.random.default_rng(3)
    for _ in range(50):
        v = rng.normal(size=3)
        v *= rng.uniform(0.0, 3.1) / np.linalg.norm(v)
        R = mbm_panda.rotation_matrix(v)
        assert np.allclose(mbm_panda.rotation_vector(R), v, atol=1e-9)
        assert np.allclose(mbm_panda.pose(mbm_panda.quaternion(R), [0, 0, 0])[:3, :3], R, atol=1e-12)
    # x y z w order: a quarter turn about z
    h = math.sqrt(0.5)
    assert np.allclose(mbm_panda.pose((0, 0, h, h), [1, 2, 3]), [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3],
                                                                [0, 0, 0, 1]], atol=1e-12)
    assert np.allclose(mbm_panda.quaternion(np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])), [0, 0, h, h])


def test_our_ik_finds_no_cage_goal_pose_but_its_position(panda):
    """Why the cage is left out: IK_RESTARTS descents find no panda_link8 pose inside the cage
    query's tolerances, while with any orientation they reach its position box."""
    template = mbm_panda.CAGE
    scene = mbm_panda.sample_scene(dict(template, world=((0, 0, 0), 0.0)), random.Random(1))
    target, pos_tol, orn_tol = mbm_panda.query_target(scene, template["goals"][0], template["ee_offset"])
    empty = mddual.ArmScene(panda.model, [], panda.srdf)
    assert panda.ik(target, pos_tol, orn_tol, random.Random(2), empty) is None
    loose = panda.ik(target, pos_tol, 10.0, random.Random(2), empty)  # any orientation
    assert loose is not None
    assert np.all(np.abs(_miss(panda, loose, target)[:3]) <= np.asarray(pos_tol) / 2)
