"""Problem sets for configs/arm7 in MotionBenchMaker's format.

Six kinds of scene, as MotionBenchMaker's: a bookshelf with thin boards, a
cage of bars, an open box, a table pick, a pick under a table, and a table
with bars above it. Each set holds PROBLEMS problems: sceneNNNN.yaml (a
MoveIt PlanningScene: the scene's objects moved by a seeded variation) and
requestNNNN.yaml (a MotionPlanRequest for group `arm`: a start near the
ready pose and a goal with the hand inside the scene's target region).

Start and goal are checked collision-free here with a conservative model
of the arm (spheres that contain every link, 1 cm of margin) against the
objects and between links the SRDF does not exempt, so the exact check
finds them free too (tests/configs/test_arm_problems.cpp loads every
problem and checks its start and goal exactly).

Used by scripts/make_configs.py (`--only arm7`). Python standard library
only; deterministic output.
"""

import math
import random

import arm_configs

PROBLEMS = 20
MARGIN = 0.01
FINGER = 0.02  # the scenes' finger opening (robot_state)
MAX_TRIES = 20000


# ---- forward kinematics of arm7 and its bounding spheres ------------------------------

def _rot(axis, a):
    c, s = math.cos(a), math.sin(a)
    if axis == (0, 0, 1):
        return ((c, -s, 0), (s, c, 0), (0, 0, 1))
    return ((c, 0, s), (0, 1, 0), (-s, 0, c))  # about y


def _mul(R, S):
    return tuple(tuple(sum(R[i][k] * S[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def _apply(R, p, v):
    return tuple(p[i] + sum(R[i][k] * v[k] for k in range(3)) for i in range(3))


def _slab_spheres(profile):
    """Spheres on the axis that cover a revolved body: one per pair of
    consecutive profile rings, centred between them, through the farther
    ring's vertices (every point of the solid between the rings is within)."""
    out = []
    for (r0, z0), (r1, z1) in zip(profile, profile[1:]):
        out.append(((0.0, 0.0, (z0 + z1) / 2), math.hypot(max(r0, r1), (z1 - z0) / 2)))
    return out


def _box_spheres(centre, size, axis, pieces):
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


def link_spheres():
    """Per link, spheres (centre, radius) in the link frame that contain it
    (the URDF's primitives grown by 2 mm for their circumscribed polygons)."""
    h = arm_configs.BASE_HEIGHT
    spheres = {"base": [((0, 0, z), math.hypot(0.102, h / 6)) for z in (h / 6, h / 2, 5 * h / 6)]}
    for i, (_, _, _, length, radius) in enumerate(arm_configs.JOINTS, start=1):
        spheres["link%d" % i] = _slab_spheres(arm_configs.link_profile(length, radius, "link%d" % i in
                                                                        arm_configs.WAISTED))
    spheres["link6"] += _box_spheres((0.05, 0, 0.05), (0.06, 0.05, 0.06), 2, 1)
    spheres["hand"] = _box_spheres((0, 0, 0.035), (0.06, 0.2, 0.05), 1, 4) + [((0, 0, 0.01), math.hypot(0.042, 0.01))]
    for side, sign in (("left", 1), ("right", -1)):
        spheres["finger_" + side] = _box_spheres((0, sign * 0.0125, 0.025), (0.02, 0.015, 0.05), 2, 2)
    return spheres


SPHERES = link_spheres()


def link_poses(q, finger=0.0):
    """(R, p) of every link in the base frame for the 7 arm angles q."""
    poses = {"base": (((1, 0, 0), (0, 1, 0), (0, 0, 1)), (0.0, 0.0, 0.0))}
    R, p = poses["base"]
    origin = (0, 0, arm_configs.BASE_HEIGHT)
    for i, (_, axis, _, length, _) in enumerate(arm_configs.JOINTS, start=1):
        p = _apply(R, p, origin)
        R = _mul(R, _rot(axis, q[i - 1]))
        poses["link%d" % i] = (R, p)
        origin = (0, 0, length)
    hand = (R, _apply(R, p, origin))
    poses["hand"] = hand
    poses["finger_left"] = (hand[0], _apply(hand[0], hand[1], (0, finger, 0.06)))
    poses["finger_right"] = (hand[0], _apply(hand[0], hand[1], (0, -finger, 0.06)))
    return poses


def world_spheres(q):
    out = []
    for name, (R, p) in link_poses(q, FINGER).items():
        out += [(name, _apply(R, p, c), r) for c, r in SPHERES[name]]
    return out


def _box_distance(centre, half, c):
    d = [max(abs(c[i] - centre[i]) - half[i], 0.0) for i in range(3)]
    return math.sqrt(sum(x * x for x in d))


ADJACENT = set()
for _a, _b in arm_configs.disabled_pairs():
    ADJACENT.add((_a, _b))
    ADJACENT.add((_b, _a))


def free(q, boxes):
    """Conservatively collision-free: no sphere within MARGIN of an object
    box (centre, half extents; axis-aligned) or of a sphere of a link the
    SRDF does not exempt."""
    spheres = world_spheres(q)
    for _, c, r in spheres:
        for centre, half in boxes:
            if _box_distance(centre, half, c) <= r + MARGIN:
                return False
    for i, (na, ca, ra) in enumerate(spheres):
        for nb, cb, rb in spheres[i + 1:]:
            if na == nb or (na, nb) in ADJACENT:
                continue
            if math.dist(ca, cb) <= ra + rb + MARGIN:
                return False
    return True


def hand_point(q):
    R, p = link_poses(q)["hand"]
    return _apply(R, p, (0, 0, 0.08))


# ---- scenes ---------------------------------------------------------------------------

def _box(name, centre, size):
    return (name, centre, size)


def bookshelf(rng):
    x = 0.75 + rng.uniform(-0.05, 0.05)
    y = rng.uniform(-0.1, 0.1)
    boards = [0.25, 0.55, 0.85, 1.15]
    objects = [_box("board%d" % k, (x, y, z), (0.35, 0.8, 0.01)) for k, z in enumerate(boards)]
    objects += [_box("side_left", (x, y - 0.405, 0.7), (0.35, 0.01, 1.0)),
                _box("side_right", (x, y + 0.405, 0.7), (0.35, 0.01, 1.0)),
                _box("back", (x + 0.18, y, 0.7), (0.01, 0.8, 1.0))]
    shelf = rng.randrange(3)
    target = ((x - 0.12, x + 0.1), (y - 0.3, y + 0.3), (boards[shelf] + 0.08, boards[shelf + 1] - 0.08))
    return objects, target


def cage(rng):
    x = 0.6 + rng.uniform(-0.05, 0.05)
    objects = []
    for k, y in enumerate((-0.45, -0.15, 0.15, 0.45)):
        objects.append(_box("post%d" % k, (x - 0.25, y + rng.uniform(-0.02, 0.02), 0.6), (0.03, 0.03, 1.2)))
        objects.append(_box("rear%d" % k, (x + 0.25, y, 0.6), (0.03, 0.03, 1.2)))
    for k, z in enumerate((0.25, 1.0)):
        objects.append(_box("rail%d" % k, (x - 0.25, 0, z), (0.03, 0.95, 0.03)))
    objects.append(_box("roof", (x, 0, 1.2), (0.53, 0.95, 0.02)))
    target = ((x - 0.15, x + 0.15), (-0.2, 0.2), (0.4, 0.8))
    return objects, target


def box(rng):
    x = 0.65 + rng.uniform(-0.05, 0.05)
    y = rng.uniform(-0.15, 0.15)
    objects = [_box("bottom", (x, y, 0.3), (0.5, 0.5, 0.02)),
               _box("side_a", (x, y - 0.25, 0.45), (0.5, 0.02, 0.3)),
               _box("side_b", (x, y + 0.25, 0.45), (0.5, 0.02, 0.3)),
               _box("front", (x - 0.25, y, 0.42), (0.02, 0.5, 0.24)),
               _box("back", (x + 0.25, y, 0.45), (0.02, 0.5, 0.3))]
    target = ((x - 0.15, x + 0.15), (y - 0.15, y + 0.15), (0.42, 0.55))
    return objects, target


def table_pick(rng):
    x = 0.7 + rng.uniform(-0.05, 0.05)
    objects = [_box("table", (x, 0, 0.4), (0.6, 1.0, 0.03))]
    for k in range(4):
        objects.append(_box("can%d" % k, (x + rng.uniform(-0.2, 0.2), rng.uniform(-0.4, 0.4), 0.5),
                            (0.06, 0.06, 0.17)))
    target = ((x - 0.25, x + 0.2), (-0.35, 0.35), (0.5, 0.65))
    return objects, target


def table_under_pick(rng):
    x = 0.7 + rng.uniform(-0.05, 0.05)
    objects = [_box("table", (x, 0, 0.7), (0.6, 1.0, 0.03)),
               _box("leg_a", (x + 0.27, -0.47, 0.35), (0.04, 0.04, 0.7)),
               _box("leg_b", (x + 0.27, 0.47, 0.35), (0.04, 0.04, 0.7))]
    target = ((x - 0.2, x + 0.15), (-0.3, 0.3), (0.3, 0.55))
    return objects, target


def table_bars(rng):
    x = 0.7 + rng.uniform(-0.05, 0.05)
    objects = [_box("table", (x, 0, 0.35), (0.6, 1.0, 0.03))]
    for k, y in enumerate((-0.3, 0.0, 0.3)):
        objects.append(_box("bar%d" % k, (x, y + rng.uniform(-0.03, 0.03), 0.75), (0.6, 0.03, 0.03)))
    target = ((x - 0.2, x + 0.2), (-0.35, 0.35), (0.45, 0.65))
    return objects, target


KINDS = {"bookshelf_thin": bookshelf, "cage": cage, "box": box, "table_pick": table_pick,
         "table_under_pick": table_under_pick, "table_bars": table_bars}


# ---- start and goal -------------------------------------------------------------------

def _limits():
    return [limits for _, _, limits, _, _ in arm_configs.JOINTS]


def _inside(p, region):
    return all(lo <= p[i] <= hi for i, (lo, hi) in enumerate(region))


def sample_start(rng, boxes):
    lim = _limits()
    for _ in range(MAX_TRIES):
        q = [min(max(v + rng.uniform(-0.3, 0.3), lo), hi) for v, (lo, hi) in zip(arm_configs.READY, lim)]
        q[0] = rng.uniform(-2.5, -1.2) if rng.random() < 0.5 else rng.uniform(1.2, 2.5)
        if free(q, boxes):
            return q
    raise RuntimeError("no free start found")


def sample_goal(rng, boxes, target):
    """A free configuration with the hand in the target region: random
    restarts, each a short hill climb of the hand toward a random point of
    the region, kept when it ends inside and free."""
    lim = _limits()
    for _ in range(MAX_TRIES // 50):
        aim = [rng.uniform(lo, hi) for lo, hi in target]
        q = [rng.uniform(lo, hi) for lo, hi in lim]
        q[0] = math.atan2(aim[1], aim[0])
        best = math.dist(hand_point(q), aim)
        for _ in range(150):
            trial = [min(max(v + rng.gauss(0.0, 0.15), lo), hi) for v, (lo, hi) in zip(q, lim)]
            d = math.dist(hand_point(trial), aim)
            if d < best:
                q, best = trial, d
        if _inside(hand_point(q), target) and free(q, boxes):
            return q
    raise RuntimeError("no free goal found in the target region")


# ---- YAML text ------------------------------------------------------------------------

def fmt(x):
    return arm_configs.fmt(x)


def scene_yaml(kind, objects):
    lines = ["name: %s" % kind, "robot_state:", "  joint_state:",
             "    name: [finger_left_joint]", "    position: [%s]" % fmt(FINGER), "robot_model_name: arm7",
             "world:", "  collision_objects:"]
    for name, centre, size in objects:
        lines += ["    - header: {frame_id: world}", "      id: %s" % name, "      primitives:",
                  "        - type: box", "          dimensions: [%s]" % ", ".join(fmt(s) for s in size),
                  "      primitive_poses:",
                  "        - position: [%s]" % ", ".join(fmt(c) for c in centre),
                  "          orientation: [0, 0, 0, 1]"]
    return "\n".join(lines) + "\n"


def request_yaml(start, goal):
    names = ["joint%d" % i for i in range(1, 8)]
    lines = ["planner_id: RRTConnectkConfigDefault", "group_name: arm", "allowed_planning_time: 10",
             "start_state:", "  joint_state:", "    name: [%s]" % ", ".join(names),
             "    position: [%s]" % ", ".join(fmt(v) for v in start), "goal_constraints:", "  - joint_constraints:"]
    for name, v in zip(names, goal):
        lines += ["      - joint_name: %s" % name, "        position: %s" % fmt(v),
                  "        tolerance_above: 0.001", "        tolerance_below: 0.001", "        weight: 1"]
    return "\n".join(lines) + "\n"


def problems(files, folder):
    for seed, (kind, make) in enumerate(KINDS.items(), start=1):
        rng = random.Random(1000 + seed)
        for n in range(1, PROBLEMS + 1):
            objects, target = make(rng)
            boxes = [(c, tuple(s / 2 for s in size)) for _, c, size in objects]
            start = [round(v, 6) for v in sample_start(rng, boxes)]
            goal = [round(v, 6) for v in sample_goal(rng, boxes, target)]
            files["%sproblems/%s/scene%04d.yaml" % (folder, kind, n)] = scene_yaml(kind, objects)
            files["%sproblems/%s/request%04d.yaml" % (folder, kind, n)] = request_yaml(start, goal)
