"""The Panda's sets in MotionBenchMaker's scenes (scripts/mbm_panda.py): the
committed problems are what the script makes (its first problems of two sets,
made again here, byte for byte), and a problem it makes meets its query: the
goal's panda_link8 inside the query's position box and orientation
tolerances, start and goal CLEARANCE from the scene's pieces."""

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
    # Not a trivial sample: the goal is far from the start, and the can is within the hand's reach.
    assert np.abs(np.asarray(goal) - np.asarray(start)).max() > 0.5
    assert np.linalg.norm(scene["Can1"][2][:3, 3] - mbm_panda.SHOULDER) < mbm_panda.REACH + 0.3


def test_rotation_helpers_round_trip():
    rng = np.random.default_rng(3)
    for _ in range(50):
        v = rng.normal(size=3)
        v *= rng.uniform(0.0, 3.1) / np.linalg.norm(v)
        R = mbm_panda.rotation_matrix(v)
        assert np.allclose(mbm_panda.rotation_vector(R), v, atol=1e-9)
        assert np.allclose(mbm_panda.pose(mbm_panda.quaternion(R), [0, 0, 0])[:3, :3], R, atol=1e-12)


def test_the_cage_goal_is_out_of_the_pandas_reach(panda):
    """Why the cage is left out: no descent reaches its goal pose for panda_link8, though the
    position alone is reached."""
    template = mbm_panda.CAGE
    scene = mbm_panda.sample_scene(dict(template, world=((0, 0, 0), 0.0)), random.Random(1))
    target, pos_tol, orn_tol = mbm_panda.query_target(scene, template["goals"][0], template["ee_offset"])
    empty = mddual.ArmScene(panda.model, [], panda.srdf)
    assert panda.ik(target, pos_tol, orn_tol, random.Random(2), empty) is None
    loose = panda.ik(target, pos_tol, 10.0, random.Random(2), empty)  # any orientation
    assert loose is not None
    assert np.all(np.abs(_miss(panda, loose, target)[:3]) <= np.asarray(pos_tol) / 2)
