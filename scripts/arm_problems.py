"""Problem sets for the project's arms in MotionBenchMaker's format.

Six kinds of scene, as MotionBenchMaker's: a bookshelf with thin boards, a
cage of bars, an open box, a table pick, a pick under a table, and a table
with bars above it, in front of the robot (+x). Each set holds a robot's
number of problems: sceneNNNN.yaml (a MoveIt PlanningScene: the scene's
objects moved by a seeded variation) and requestNNNN.yaml (a
MotionPlanRequest for the robot's group: a start near the ready pose and a
goal with the hand inside the scene's target region).

The builders and samplers work on any serial arm described by an ArmSpec:
its forward kinematics, spheres that contain each link, the link pairs its
SRDF exempts, its joints and limits, and the scale of its scenes (1 for
configs/arm7, whose sizes they were made for; a smaller arm's scenes are
shrunk about the origin, thin boards and bars keeping their thickness).

Start and goal are checked collision-free here with a conservative model
of the arm (spheres that contain every link, 1 cm of margin) against the
objects and between links the SRDF does not exempt, so the exact check
finds them free too (tests/configs/test_arm_problems.cpp loads every
problem and checks its start and goal exactly).

Used by scripts/arm_configs.py and scripts/panda_configs.py (through
scripts/make_configs.py `--only arm7,panda`). Python standard library only;
deterministic output.
"""

import math
import random

MARGIN = 0.01
MAX_TRIES = 20000


def fmt(x):
    s = ("%.6f" % x).rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


class ArmSpec:
    """What the scenes, samplers and YAML need of an arm.

    name: the robot's name (robot_model_name); group: the planning group of
    the requests; joints: the group's joint names; limits: their (lower,
    upper); ready: the configuration starts are drawn near; finger_joint and
    finger: the scenes' gripper opening (robot_state); link_poses(q, finger):
    (R, p) of every link with spheres, in the base frame; spheres: per link,
    (centre, radius) in the link frame containing it; disabled: the link
    pairs the SRDF exempts; hand: (link, point) whose position must reach the
    target region; scale: the size of the scenes against arm7's; problems:
    how many per set; seed: added to each set's number to seed it.
    """

    def __init__(self, name, group, joints, limits, ready, finger_joint, finger, link_poses, spheres, disabled,
                 hand, scale, problems, seed):
        self.name, self.group, self.joints, self.limits, self.ready = name, group, joints, limits, ready
        self.finger_joint, self.finger, self.link_poses, self.spheres = finger_joint, finger, link_poses, spheres
        self.disabled = set()
        for a, b in disabled:
            self.disabled.add((a, b))
            self.disabled.add((b, a))
        self.hand, self.scale, self.problems, self.seed = hand, scale, problems, seed


# ---- geometry helpers for forward kinematics and bounding spheres ----------------------

def mul(R, S):
    return tuple(tuple(sum(R[i][k] * S[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def apply(R, p, v):
    return tuple(p[i] + sum(R[i][k] * v[k] for k in range(3)) for i in range(3))


def slab_spheres(profile):
    """Spheres on the axis that cover a revolved body: one per pair of
    consecutive profile rings, centred between them, through the farther
    ring's vertices (every point of the solid between the rings is within)."""
    out = []
    for (r0, z0), (r1, z1) in zip(profile, profile[1:]):
        out.append(((0.0, 0.0, (z0 + z1) / 2), math.hypot(max(r0, r1), (z1 - z0) / 2)))
    return out


def box_spheres(centre, size, axis, pieces):
    """Spheres that cover a box: `pieces` slabs along `axis`, each covered by
    the sphere through its corners."""
    out = []
    step = size[axis] / pieces
    half = [s / 2 for s in size]
    half[axis] = step / 2
    for k in range(pieces):
        c = list(centre)
        c[axis] = centre[axis] - size[axis] / 2 + (k + 0.5) * step
        out.append((tuple(c), math.sqrt(sum(h * h for h in half))))
    return out


def capsule_spheres(centre, direction, radius, length, grow):
    """Spheres that cover a capsule (a cylinder of `radius` and `length`
    along the unit `direction` through `centre`, capped by two spheres) with
    every primitive grown by `grow`: the caps, and the cylinder cut into
    slabs no longer than its radius, each covered by the sphere through its
    rims."""
    r = radius + grow
    out = [(apply(((1, 0, 0), (0, 1, 0), (0, 0, 1)), centre, [t * d for d in direction]), r)
           for t in (-length / 2, length / 2)]
    pieces = max(1, math.ceil(length / radius))
    step = length / pieces
    for k in range(pieces):
        t = -length / 2 + (k + 0.5) * step
        out.append((tuple(centre[i] + t * direction[i] for i in range(3)), math.hypot(r, step / 2)))
    return out


def world_spheres(arm, q):
    out = []
    for name, (R, p) in arm.link_poses(q, arm.finger).items():
        out += [(name, apply(R, p, c), r) for c, r in arm.spheres.get(name, [])]
    return out


def _box_distance(centre, half, c):
    d = [max(abs(c[i] - centre[i]) - half[i], 0.0) for i in range(3)]
    return math.sqrt(sum(x * x for x in d))


def free(arm, q, boxes):
    """Conservatively collision-free: no sphere within MARGIN of an object
    box (centre, half extents; axis-aligned) or of a sphere of a link the
    SRDF does not exempt."""
    spheres = world_spheres(arm, q)
    for _, c, r in spheres:
        for centre, half in boxes:
            if _box_distance(centre, half, c) <= r + MARGIN:
                return False
    for i, (na, ca, ra) in enumerate(spheres):
        for nb, cb, rb in spheres[i + 1:]:
            if na == nb or (na, nb) in arm.disabled:
                continue
            if math.dist(ca, cb) <= ra + rb + MARGIN:
                return False
    return True


def hand_point(arm, q):
    link, point = arm.hand
    R, p = arm.link_poses(q, 0.0)[link]
    return apply(R, p, point)


# ---- scenes (sizes for arm7; s shrinks them for a smaller arm) ------------------------

def _box(name, centre, size):
    return (name, centre, size)


def bookshelf(rng, s):
    x = 0.75 * s + rng.uniform(-0.05, 0.05)
    y = rng.uniform(-0.1, 0.1)
    boards = [0.25 * s, 0.55 * s, 0.85 * s, 1.15 * s]
    objects = [_box("board%d" % k, (x, y, z), (0.35 * s, 0.8 * s, 0.01)) for k, z in enumerate(boards)]
    objects += [_box("side_left", (x, y - 0.405 * s, 0.7 * s), (0.35 * s, 0.01, 1.0 * s)),
                _box("side_right", (x, y + 0.405 * s, 0.7 * s), (0.35 * s, 0.01, 1.0 * s)),
                _box("back", (x + 0.18 * s, y, 0.7 * s), (0.01, 0.8 * s, 1.0 * s))]
    shelf = rng.randrange(3)
    target = ((x - 0.12 * s, x + 0.1 * s), (y - 0.3 * s, y + 0.3 * s),
              (boards[shelf] + 0.08 * s, boards[shelf + 1] - 0.08 * s))
    return objects, target


def cage(rng, s):
    x = 0.6 * s + rng.uniform(-0.05, 0.05)
    objects = []
    for k, y in enumerate((-0.45 * s, -0.15 * s, 0.15 * s, 0.45 * s)):
        objects.append(_box("post%d" % k, (x - 0.25 * s, y + rng.uniform(-0.02, 0.02), 0.6 * s), (0.03, 0.03, 1.2 * s)))
        objects.append(_box("rear%d" % k, (x + 0.25 * s, y, 0.6 * s), (0.03, 0.03, 1.2 * s)))
    for k, z in enumerate((0.25 * s, 1.0 * s)):
        objects.append(_box("rail%d" % k, (x - 0.25 * s, 0, z), (0.03, 0.95 * s, 0.03)))
    objects.append(_box("roof", (x, 0, 1.2 * s), (0.53 * s, 0.95 * s, 0.02)))
    target = ((x - 0.15 * s, x + 0.15 * s), (-0.2 * s, 0.2 * s), (0.4 * s, 0.8 * s))
    return objects, target


def box(rng, s):
    x = 0.65 * s + rng.uniform(-0.05, 0.05)
    y = rng.uniform(-0.15, 0.15) * s
    objects = [_box("bottom", (x, y, 0.3 * s), (0.5 * s, 0.5 * s, 0.02)),
               _box("side_a", (x, y - 0.25 * s, 0.45 * s), (0.5 * s, 0.02, 0.3 * s)),
               _box("side_b", (x, y + 0.25 * s, 0.45 * s), (0.5 * s, 0.02, 0.3 * s)),
               _box("front", (x - 0.25 * s, y, 0.42 * s), (0.02, 0.5 * s, 0.24 * s)),
               _box("back", (x + 0.25 * s, y, 0.45 * s), (0.02, 0.5 * s, 0.3 * s))]
    target = ((x - 0.15 * s, x + 0.15 * s), (y - 0.15 * s, y + 0.15 * s), (0.42 * s, 0.55 * s))
    return objects, target


def table_pick(rng, s):
    x = 0.7 * s + rng.uniform(-0.05, 0.05)
    objects = [_box("table", (x, 0, 0.4 * s), (0.6 * s, 1.0 * s, 0.03))]
    for k in range(4):
        objects.append(_box("can%d" % k, (x + rng.uniform(-0.2, 0.2) * s, rng.uniform(-0.4, 0.4) * s,
                                          0.4 * s + 0.1), (0.06, 0.06, 0.17)))
    target = ((x - 0.25 * s, x + 0.2 * s), (-0.35 * s, 0.35 * s), (0.4 * s + 0.1, 0.4 * s + 0.25))
    return objects, target


def table_under_pick(rng, s):
    x = 0.7 * s + rng.uniform(-0.05, 0.05)
    objects = [_box("table", (x, 0, 0.7 * s), (0.6 * s, 1.0 * s, 0.03)),
               _box("leg_a", (x + 0.27 * s, -0.47 * s, 0.35 * s), (0.04, 0.04, 0.7 * s)),
               _box("leg_b", (x + 0.27 * s, 0.47 * s, 0.35 * s), (0.04, 0.04, 0.7 * s))]
    target = ((x - 0.2 * s, x + 0.15 * s), (-0.3 * s, 0.3 * s), (0.3 * s, 0.55 * s))
    return objects, target


def table_bars(rng, s):
    x = 0.7 * s + rng.uniform(-0.05, 0.05)
    objects = [_box("table", (x, 0, 0.35 * s), (0.6 * s, 1.0 * s, 0.03))]
    for k, y in enumerate((-0.3 * s, 0.0, 0.3 * s)):
        objects.append(_box("bar%d" % k, (x, y + rng.uniform(-0.03, 0.03), 0.75 * s), (0.6 * s, 0.03, 0.03)))
    target = ((x - 0.2 * s, x + 0.2 * s), (-0.35 * s, 0.35 * s), (0.45 * s, 0.65 * s))
    return objects, target


KINDS = {"bookshelf_thin": bookshelf, "cage": cage, "box": box, "table_pick": table_pick,
         "table_under_pick": table_under_pick, "table_bars": table_bars}


# ---- start and goal -------------------------------------------------------------------

def _inside(p, region):
    return all(lo <= p[i] <= hi for i, (lo, hi) in enumerate(region))


def sample_start(arm, rng, boxes):
    lim = arm.limits
    for _ in range(MAX_TRIES):
        q = [min(max(v + rng.uniform(-0.3, 0.3), lo), hi) for v, (lo, hi) in zip(arm.ready, lim)]
        q[0] = rng.uniform(-2.5, -1.2) if rng.random() < 0.5 else rng.uniform(1.2, 2.5)
        if free(arm, q, boxes):
            return q
    raise RuntimeError("no free start found")


def sample_goal(arm, rng, boxes, target):
    """A free configuration with the hand in the target region: random
    restarts, each a short hill climb of the hand toward a random point of
    the region, kept when it ends inside and free."""
    lim = arm.limits
    for _ in range(MAX_TRIES // 50):
        aim = [rng.uniform(lo, hi) for lo, hi in target]
        q = [rng.uniform(lo, hi) for lo, hi in lim]
        q[0] = math.atan2(aim[1], aim[0])
        best = math.dist(hand_point(arm, q), aim)
        for _ in range(150):
            trial = [min(max(v + rng.gauss(0.0, 0.15), lo), hi) for v, (lo, hi) in zip(q, lim)]
            d = math.dist(hand_point(arm, trial), aim)
            if d < best:
                q, best = trial, d
        if _inside(hand_point(arm, q), target) and free(arm, q, boxes):
            return q
    raise RuntimeError("no free goal found in the target region")


# ---- YAML text ------------------------------------------------------------------------

def scene_yaml(arm, kind, objects):
    """objects: (name, centre, size) boxes without a turn, or (name, type, dimensions, position, quaternion x y
    z w) with type box or cylinder (dimensions height, radius)."""
    lines = ["name: %s" % kind, "robot_state:", "  joint_state:",
             "    name: [%s]" % arm.finger_joint, "    position: [%s]" % fmt(arm.finger),
             "robot_model_name: %s" % arm.name, "world:", "  collision_objects:"]
    for obj in objects:
        name, kind, dims, centre, quat = obj if len(obj) == 5 else (obj[0], "box", obj[2], obj[1], (0, 0, 0, 1))
        lines += ["    - header: {frame_id: world}", "      id: %s" % name, "      primitives:",
                  "        - type: %s" % kind, "          dimensions: [%s]" % ", ".join(fmt(s) for s in dims),
                  "      primitive_poses:",
                  "        - position: [%s]" % ", ".join(fmt(c) for c in centre),
                  "          orientation: [%s]" % ", ".join(fmt(c) for c in quat)]
    return "\n".join(lines) + "\n"


def request_yaml(arm, start, goal):
    lines = ["planner_id: RRTConnectkConfigDefault", "group_name: %s" % arm.group, "allowed_planning_time: 10",
             "start_state:", "  joint_state:", "    name: [%s]" % ", ".join(arm.joints),
             "    position: [%s]" % ", ".join(fmt(v) for v in start), "goal_constraints:", "  - joint_constraints:"]
    for name, v in zip(arm.joints, goal):
        lines += ["      - joint_name: %s" % name, "        position: %s" % fmt(v),
                  "        tolerance_above: 0.001", "        tolerance_below: 0.001", "        weight: 1"]
    return "\n".join(lines) + "\n"


def problems(files, folder, arm):
    for seed, (kind, make) in enumerate(KINDS.items(), start=1):
        rng = random.Random(arm.seed + seed)
        for n in range(1, arm.problems + 1):
            objects, target = make(rng, arm.scale)
            boxes = [(c, tuple(s / 2 for s in size)) for _, c, size in objects]
            start = [round(v, 6) for v in sample_start(arm, rng, boxes)]
            goal = [round(v, 6) for v in sample_goal(arm, rng, boxes, target)]
            files["%sproblems/%s/scene%04d.yaml" % (folder, kind, n)] = scene_yaml(arm, kind, objects)
            files["%sproblems/%s/request%04d.yaml" % (folder, kind, n)] = request_yaml(arm, start, goal)
