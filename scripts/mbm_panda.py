"""The Panda's problem sets in MotionBenchMaker's own scenes (configs/panda/problems/mbm_*).

MotionBenchMaker (MBM) does not ship its problems as data: it makes them from
templates, per scene a nominal planning scene, a variation and queries, and
per (scene, robot) a base offset and an end-effector offset. The sets here
follow MBM's templates for the Panda (the figures below are theirs: object
sizes and poses, spreads, query offsets and tolerances, offsets, the start
state) and its procedure:

1. the nominal scene is moved by the base offset (the scene against the
   robot's base frame, panda_link0);
2. the whole scene is moved by a draw of its world variation, applied in the
   base frame (a turn about the base's z axis), and each varied object by a
   draw of its own, applied in the object's frame. MBM's templates call the
   variations `uniform`, but its sampler tests the type with
   std::string::compare, which is 0 on a match, so a `uniform` variation
   takes its Gaussian branch: a draw here is normal deviates with the
   template's figures as standard deviations;
3. the start is the Panda's ready state from MBM's robot config or, where the
   template has start queries (table_under_pick), an IK solution of one;
4. the goal is an IK solution for panda_link8 at the query pose (the object's
   pose, times the query's offset, times the inverse of the end-effector
   offset), within the query's position box and orientation tolerances.

A scene whose start is in collision, or whose query has no free IK solution
in IK_RESTARTS damped least-squares descents from random configurations, is
drawn again (MBM skips such samples too). Start and goal keep CLEARANCE from
the scene and between the links the SRDF checks, by mddual's exact clearance
(the build's Python module) on the scene with each cylinder taken as its
bounding box; tests/configs/test_arm_problems.cpp loads every problem and
checks start and goal again.

What differs from MBM's published problems: the robot is this project's
Panda of primitives (scripts/panda_configs.py), not Franka's meshes, so IK
solutions and collisions differ from a real Panda's; the IK is ours, not
BioIK or KDL; the random draws are Python's. table_bars and kitchen are left
out (their scenes are meshes that MBM ships as STL files), and so is the cage
(why: beside SETS).

    PYTHONPATH=build/release/python python3 scripts/mbm_panda.py [SET ...]   # all four sets: about 40 minutes
    MDDUAL_WITNESS_SETS="SET ..." ./scripts/arm-witnesses.sh panda            # then their witness paths

Needs the build's `mddual` module and NumPy; deterministic on a given build (one last-bit
difference in an accept or reject shifts every later draw).
"""

import copy
import math
import os
import random
import sys

import numpy as np

import mddual

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import arm_problems  # noqa: E402
import panda_configs  # noqa: E402

IK_RESTARTS = 50  # per scene draw (MBM's IK query makes 200 attempts; here a failed draw is redrawn)
IK_STEPS = 60
PROBLEMS = 10  # per set
CLEARANCE = 0.005  # m: start and goal this far from the scene (cylinders as boxes) and between checked links
DAMPING = 1e-4  # squared damping of the least-squares steps (lambda = 0.01)
SHOULDER = np.array([0.0, 0.0, 0.333])  # panda_joint2's origin: panda_link8 stays within REACH (m) of it
REACH = 0.316 + 0.0825 + 0.384 + 0.0825 + 0.088 + 0.107
SCENE_DRAWS = 3000

# ---- MBM's templates for the Panda (configs/problems/*_panda.yaml, configs/scenes/) ----------
# Objects: (id, type, dimensions, position, quaternion x y z w); a cylinder's dimensions are
# (height, radius), MoveIt's order.
_IDENTITY = (0, 0, 0, 1)


def _shelf(name, position):
    return (name, "box", (0.62, 1, 0.04), position, _IDENTITY)


_CANS = [("Can%d" % (k + 1), "cylinder", (0.14, 0.03), (x, y, z), _IDENTITY)
         for k, (x, y, z) in enumerate([(1.1, 0.25, 0.44), (0.8, 0.25, 0.44), (1.1, -0.25, 0.69), (0.8, -0.25, 0.69),
                                        (1.1, 0.25, 0.94), (0.8, 0.25, 0.94), (1.1, -0.25, 1.19), (0.8, -0.25, 1.19),
                                        (1.1, 0.25, 1.44), (0.8, 0.25, 1.44)])]

BOOKSHELF_THIN = {
    "objects": _CANS + [_shelf("shelf_bottom", (1.0, 0, 0.35)), _shelf("shelf_middle_bottom", (1.0, 0, 0.6)),
                        _shelf("shelf_middle", (1.0, 0, 0.85)), _shelf("shelf_middle_top", (1, 0, 1.1)),
                        _shelf("shelf_top", (1, 0, 1.35)),
                        ("shelf_vert", "box", (0.62, 0.04, 1.4), (1, 0, 0.9), _IDENTITY),
                        _shelf("shelf_top_top", (1, 0, 1.6))]
    + [("leg_" + n, "box", (0.04, 0.04, 1.64), p, _IDENTITY)
       for n, p in (("fr", (0.7, 0.5, 0.82)), ("fl", (0.7, -0.5, 0.82)), ("br", (1.3, 0.5, 0.82)),
                    ("bl", (1.3, -0.5, 0.82)))],
    "base_offset": (-0.1, 0, -0.7),
    "world": ((0.1, 0.1, 0), 1.57),
    "object_variations": [([c[0] for c in _CANS], (0, 0.2, 0), 0.0)],
    # easy_queries_thin (the front cans) and hard_queries_thin (the back ones)
    "goals": [("Can%d" % k, (-0.2, 0, 0.05), _IDENTITY, (0.01, 0.01, 0.01), 0.01) for k in range(1, 11)],
    "starts": [],
    "ee_offset": ((0, 0, -0.08), (-0.271, -0.653, -0.271, 0.653)),
}

_CAGE_WALLS = [("base", "box", (0.7, 0.7, 0.04), (0.8, 0, 0.44), _IDENTITY),
               ("side_left", "box", (0.7, 0.04, 0.7), (0.8, -0.35, 0.8), _IDENTITY),
               ("side_right", "box", (0.7, 0.04, 0.7), (0.8, 0.35, 0.8), _IDENTITY)]

CAGE = {  # not a set: its goal is out of reach (beside SETS; python/tests/test_mbm_panda.py)
    "objects": [("Cube1", "box", (0.07, 0.07, 0.07), (0.8, 0, 0.52), _IDENTITY)] + _CAGE_WALLS
    + [("side_frontB", "box", (0.04, 0.7, 0.04), (0.45, 0, 0.9), _IDENTITY),
       ("side_frontA", "box", (0.04, 0.7, 0.04), (0.45, 0, 0.6), _IDENTITY),
       ("side_cap", "box", (0.65, 0.65, 0.04), (0.85, 0, 1.15), _IDENTITY),
       ("side_back", "box", (0.04, 0.7, 0.7), (1.15, 0, 0.8), _IDENTITY)],
    "base_offset": (0, 0, -0.18),
    "world": ((0.1, 0.1, 0.1), 0.5),
    "object_variations": [],
    "goals": [("Cube1", (0, 0, 0.21), (0, 0.707, 0, 0.707), (0.05, 0.05, 0.01), 0.01)],
    "starts": [],
    "ee_offset": ((0.13, -0.13, 0.11), (0, 0, 0.924, 0.383)),
}

BOX = {
    "objects": [("Can1", "cylinder", (0.14, 0.03), (0.8, 0, 0.55), _IDENTITY)] + _CAGE_WALLS
    + [("side_front", "box", (0.04, 0.7, 0.6), (0.45, 0, 0.7), _IDENTITY),
       ("side_cap", "box", (0.7, 0.7, 0.04), (0.9, 0, 1.35), (0, 0.383, 0, 0.924)),
       ("side_back", "box", (0.04, 0.7, 0.7), (1.15, 0, 0.8), _IDENTITY)],
    "base_offset": (-0.15, 0, -1.02),
    "world": ((0.1, 0.1, 0.1), 1.57),
    "object_variations": [(["Can1"], (0, 0.2, 0), 0.0)],
    "goals": [("Can1", (0, 0, 0.25), (0, 0.707, 0, 0.707), (0.01, 0.01, 0.01), 0.01)],  # hard_queries_box
    "starts": [],
    "ee_offset": ((0, 0, -0.08), (-0.653, -0.271, -0.653, 0.271)),
}

_TABLE_OBJECTS = [("Can1", "cylinder", (0.12, 0.03), (0.85, 0, 0.8), _IDENTITY),
                  ("Cube", "box", (0.25, 0.25, 0.25), (0.75, 0.4, 0.85), _IDENTITY)] \
    + [("table_leg_" + n, "box", (0.05, 0.05, 0.7), p, _IDENTITY)
       for n, p in (("left_back", (1.5, 0.85, 0.35)), ("left_front", (0.6, 0.85, 0.35)),
                    ("right_back", (1.5, -0.85, 0.35)), ("right_front", (0.6, -0.85, 0.35)))] \
    + [("table_top", "box", (1.2, 2, 0.04), (1.05, 0, 0.7), _IDENTITY),
       ("Object1", "cylinder", (0.35, 0.05), (1.35, 0, 0.85), _IDENTITY),
       ("Object2", "box", (0.2, 0.02, 0.4), (1.05, -0.2, 0.9), _IDENTITY),
       ("Object3", "box", (0.02, 0.2, 0.4), (0.65, 0.2, 0.9), _IDENTITY),
       ("Object4", "box", (0.2, 0.05, 0.35), (0.65, -0.2, 0.9), _IDENTITY),
       ("Object5", "box", (0.2, 0.05, 0.35), (1.05, 0.2, 0.9), _IDENTITY)]
_TABLE_GOAL = ("Can1", (-0.2, 0, 0.025), _IDENTITY, (0.0001, 0.0001, 0.0001), 0.003)

TABLE_PICK = {
    "objects": _TABLE_OBJECTS,
    "base_offset": (0.1, 0.1, -0.5),
    "world": ((0.1, 0.1, 0.1), 1.57),
    "object_variations": [(["Can1"], (0.05, 0.05, 0), 0.0),
                          (["Object1", "Object2", "Object3", "Object4", "Object5", "Cube"], (0.1, 0.1, 0), 1.57)],
    "goals": [_TABLE_GOAL],
    "starts": [],
    "ee_offset": ((0, 0, -0.08), (-0.271, -0.653, -0.271, 0.653)),
}
TABLE_UNDER_PICK = dict(TABLE_PICK, starts=[("table_top", (-0.5, 0, -0.3), _IDENTITY, (0.0001, 0.0001, 0.0001),
                                             0.003)])

# The cage is left out: its end-effector offset puts panda_link8 level, pointing +x, 0.69 m out and 0.37 m
# up, a pose our IK does not reach though it reaches the position
# (python/tests/test_mbm_panda.py); MBM's Panda goals there presumably use another tip.
SETS = {"mbm_bookshelf_thin": BOOKSHELF_THIN, "mbm_box": BOX, "mbm_table_pick": TABLE_PICK,
        "mbm_table_under_pick": TABLE_UNDER_PICK}
FINGER = 0.04  # MBM's robot config opens the fingers to 0.065: the Panda's limit, 0.04, here

# ---- poses: 4x4 homogeneous matrices -----------------------------------------------------------


def pose(quat, position):
    x, y, z, w = np.asarray(quat, float) / np.linalg.norm(quat)
    X = np.eye(4)
    X[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    X[:3, 3] = position
    return X


def quaternion(R):
    """(x, y, z, w) of a rotation matrix, w >= 0."""
    t = np.trace(R)
    if t > 0:
        s = 2 * math.sqrt(1 + t)
        q = [(R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s, s / 4]
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + R[i, i] - R[j, j] - R[k, k])
        q = [0.0, 0.0, 0.0, (R[k, j] - R[j, k]) / s]
        q[i], q[j], q[k] = s / 4, (R[j, i] + R[i, j]) / s, (R[k, i] + R[i, k]) / s
    return q if q[3] >= 0 else [-c for c in q]


def rotation_vector(R):
    """Axis times angle (|angle| <= pi) of a rotation matrix."""
    x, y, z, w = quaternion(R)
    v = np.array([x, y, z])
    s = np.linalg.norm(v)
    return 2 * v if s < 1e-15 else v / s * 2 * math.atan2(s, w)


def rotation_matrix(v):
    """The rotation by the rotation vector v (Rodrigues)."""
    angle = np.linalg.norm(v)
    if angle < 1e-15:
        return np.eye(3)
    k = np.asarray(v) / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def _draw(rng, spread, yaw):
    """A variation draw: normal deviates of position and yaw (every template varies only yaw)."""
    a = rng.gauss(0.0, yaw) if yaw else 0.0
    return pose((0, 0, math.sin(a / 2), math.cos(a / 2)), [rng.gauss(0.0, s) if s else 0.0 for s in spread])


# ---- scene ---------------------------------------------------------------------------------


def sample_scene(template, rng):
    """The template's objects as {id: (type, dimensions, X_BO)} in the base frame."""
    offset = pose((0, 0, 0, 1), template["base_offset"])
    world = _draw(rng, *template["world"])
    scene = {name: (kind, dims, world @ offset @ pose(quat, position))
             for name, kind, dims, position, quat in template["objects"]}
    for names, spread, yaw in template["object_variations"]:
        for name in names:
            kind, dims, X = scene[name]
            scene[name] = (kind, dims, X @ _draw(rng, spread, yaw))
    return scene


def world_pieces(scene):
    """The objects as convex pieces in the base frame, each cylinder as its bounding box."""
    pieces = []
    for kind, dims, X in scene.values():
        half = np.array(dims) / 2 if kind == "box" else np.array([dims[1], dims[1], dims[0] / 2])
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
        pieces.append(mddual.ConvexPolytope(corners @ X[:3, :3].T + X[:3, 3]))
    return pieces


class Panda:
    """The Panda of configs/panda: its model, the arm's variables, and the exact clearance in a scene."""

    def __init__(self, folder):
        self.model = mddual.RobotModel.from_urdf(os.path.join(folder, "panda.urdf"))
        self.srdf = mddual.Srdf.load(os.path.join(folder, "panda.srdf"))
        self.joints = [j[0] for j in panda_configs.JOINTS]
        self.index = [self.model.variable_index(j) for j in self.joints]
        self.limits = self.model.limits[self.index]
        self.links = ["panda_link%d" % k for k in range(1, 9)]
        self.base = self.model.configuration({"panda_finger_joint1": FINGER})
        self.spec = copy.copy(panda_configs.PANDA)  # names and group, for the YAML
        self.spec.finger = FINGER

    def full(self, q):
        Q = self.base.copy()
        Q[self.index] = q
        return Q

    def free(self, scene_check, q):
        return scene_check.clearance(self.full(q)) >= CLEARANCE

    def ik(self, target, pos_tol, orn_tol, rng, scene_check):
        """A configuration whose panda_link8 is at the target within the tolerances and keeps CLEARANCE, or
        None. Each of IK_RESTARTS attempts aims at a random pose inside the tolerances (MBM's query is a
        region) and descends to it by damped least squares from a random configuration inside the limits
        (every Panda joint turns its link about the link frame's z)."""
        if np.linalg.norm(target[:3, 3] - SHOULDER) > REACH:
            return None
        lo, hi = self.limits[:, 0], self.limits[:, 1]
        pos_tol = np.asarray(pos_tol)
        for _ in range(IK_RESTARTS):
            aim = target.copy()
            aim[:3, 3] += [rng.uniform(-0.45, 0.45) * t for t in pos_tol]
            turn = np.array([rng.uniform(-0.9, 0.9) * orn_tol for _ in range(3)])
            aim[:3, :3] = target[:3, :3] @ rotation_matrix(turn)
            q = np.array([rng.uniform(a, b) for a, b in self.limits])
            for step in range(IK_STEPS + 1):
                X = self.model.forward_kinematics(self.full(q), self.links)
                p = X[7, :3, 3]
                e = np.concatenate([p - aim[:3, 3], rotation_vector(aim[:3, :3].T @ X[7, :3, :3])])
                if np.abs(e).max() < 1e-7 or step == IK_STEPS:
                    break
                a = X[:7, :3, 2]  # joint axes
                J = np.vstack([np.cross(a, p - X[:7, :3, 3]).T, aim[:3, :3].T @ a.T])
                q = np.clip(q - J.T @ np.linalg.solve(J @ J.T + DAMPING * np.eye(6), e), lo, hi)
            miss = np.concatenate([p - target[:3, 3], rotation_vector(target[:3, :3].T @ X[7, :3, :3])])
            if np.all(np.abs(miss[:3]) <= pos_tol / 2) and np.all(np.abs(miss[3:]) <= orn_tol) \
                    and self.free(scene_check, q):
                return q
        return None


def query_target(scene, query, ee_offset):
    """panda_link8's target: the object's pose, times the offset, times the inverse of the ee offset."""
    name, position, quat, pos_tol, orn_tol = query
    target = scene[name][2] @ pose(quat, position) @ np.linalg.inv(pose(ee_offset[1], ee_offset[0]))
    return target, pos_tol, orn_tol


def problem(panda, template, rng):
    """(scene, start, goal, draws): redraws the scene until its start keeps CLEARANCE and a goal query has a
    solution."""
    for draws in range(1, SCENE_DRAWS + 1):
        scene = sample_scene(template, rng)
        check = mddual.ArmScene(panda.model, world_pieces(scene), panda.srdf)
        if template["starts"]:
            start = panda.ik(*query_target(scene, rng.choice(template["starts"]), template["ee_offset"]), rng, check)
        else:
            start = np.array(panda_configs.READY) if panda.free(check, panda_configs.READY) else None
        if start is None:
            continue
        goal = panda.ik(*query_target(scene, rng.choice(template["goals"]), template["ee_offset"]), rng, check)
        if goal is not None:
            return scene, start, goal, draws
    raise RuntimeError("no scene with a free start and goal in %d draws" % SCENE_DRAWS)


def seed_of(kind):
    """The seed of a set's draws."""
    return 3001 + list(SETS).index(kind)


def problem_files(panda, kind, count):
    """{file name: text} of a set's first `count` problems."""
    rng = random.Random(seed_of(kind))
    files = {}
    for n in range(1, count + 1):
        scene, start, goal, draws = problem(panda, SETS[kind], rng)
        objects = [(name, k, dims, X[:3, 3], quaternion(X[:3, :3])) for name, (k, dims, X) in scene.items()]
        files["scene%04d.yaml" % n] = arm_problems.scene_yaml(panda.spec, kind, objects)
        files["request%04d.yaml" % n] = arm_problems.request_yaml(panda.spec, [round(v, 6) for v in start],
                                                                  [round(v, 6) for v in goal])
        print("%s/scene%04d.yaml: %d scene draws" % (kind, n, draws), flush=True)
    return files


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "configs", "panda")
    panda = Panda(root)
    for kind in sys.argv[1:] or list(SETS):
        if kind not in SETS:
            raise SystemExit("mbm_panda: unknown set %s (known: %s)" % (kind, ", ".join(SETS)))
        folder = os.path.join(root, "problems", kind)
        os.makedirs(folder, exist_ok=True)
        for name, text in problem_files(panda, kind, PROBLEMS).items():
            with open(os.path.join(folder, name), "w") as f:
                f.write(text)


if __name__ == "__main__":
    main()
