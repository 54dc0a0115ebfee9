#!/usr/bin/env python3
"""Writes mddual's benchmark configs and their assets into configs/.

Every config is an OMPL.app benchmark file (.cfg, INI) with its robot and
world: URDF files of primitives, or meshes (OBJ, STL, COLLADA) made here by
scripts/meshgen.py, never taken from OMPL.app. The output is deterministic
(seeded, integer geometry where faces must be exactly planar), so
`make_configs.py --check` can verify that the committed files are what this
script makes. Python standard library only.

    scripts/make_configs.py                       # (re)write every config
    scripts/make_configs.py --only bugtrap,apartment   # (re)write some of them
    scripts/make_configs.py --check               # exit 1 if configs/ differs

The configs (see configs/README.md for what each one exercises):
  thin_walls      walls 1 cm thick, thinner than OMPL's default motion-check
                  resolution, with one door each; translation only (R^3)
  convex_field    a 3D field of random convex obstacles (OBJ meshes);
                  translation only (R^3)
  narrow_passage  a bar that must turn to pass a slot in a wall, SE(3)
  maze_se2        a planar maze, car-like polygonal robot, SE(2)
  cubicles        an office of cubicles made of boxes, SE(3)
Mesh configs of OMPL.app's sizes and shapes (one non-convex triangle mesh
each for robot and world, and a collision-free witness path):
  bugtrap         a finned spindle escaping a cup through a funnel, SE(3)
  twistycool      a twisted bar screwing through a slot in a wall, SE(3)
  cubicles_mesh   an office of cubicles welded into one mesh, SE(3)
  apartment       a couch carried through an apartment of 40,000 triangles
  maze_planar     a boomerang in a maze welded into one mesh, SE(2)
Articulated robots, with MotionBenchMaker problem sets (scripts/arm_problems.py):
  arm7            our own 7-joint arm with a two-finger gripper: URDF, SRDF
                  and link meshes (scripts/arm_configs.py)
  panda           a Franka Emika Panda: its published kinematics, collision
                  geometry of primitives (scripts/panda_configs.py)
"""

import argparse
import math
import os
import random
import sys

import arm_configs
import meshgen
import panda_configs

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
OUT = os.path.join(ROOT, "configs")


def fmt(x):
    """Numbers as short, exact-enough text (no trailing zeros)."""
    s = "%.6f" % x
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def vec(v):
    return " ".join(fmt(x) for x in v)


# ---- URDF and OBJ writers ---------------------------------------------------

def urdf(name, collisions):
    """One link holding every collision element; collisions are dicts with
    'geometry' (XML text) and 'xyz', 'rpy'."""
    lines = ['<?xml version="1.0"?>', '<robot name="%s">' % name, '  <link name="%s_link">' % name]
    for c in collisions:
        lines += [
            "    <collision>",
            '      <origin xyz="%s" rpy="%s"/>' % (vec(c["xyz"]), vec(c.get("rpy", (0, 0, 0)))),
            "      <geometry>%s</geometry>" % c["geometry"],
            "    </collision>",
        ]
    lines += ["  </link>", "</robot>", ""]
    return "\n".join(lines)


def box(centre, size, rpy=(0, 0, 0)):
    return {"xyz": centre, "rpy": rpy, "geometry": '<box size="%s"/>' % vec(size)}


def mesh(filename, centre=(0, 0, 0), rpy=(0, 0, 0)):
    return {"xyz": centre, "rpy": rpy, "geometry": '<mesh filename="%s"/>' % filename}


def obj(vertices, faces, comment, decimals=None):
    """OBJ text; coordinates with 6 decimals, or exactly with up to
    `decimals` decimals."""
    lines = ["# " + comment]
    if decimals is None:
        lines += ["v %s" % vec(v) for v in vertices]
    else:
        lines += ["v %s" % " ".join(meshgen.num(c, decimals) for c in v) for v in vertices]
    lines += ["f %s" % " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def prism(polygon, z0, z1, top_scale=1.0):
    """Vertices and triangles of a convex polygon (counter-clockwise, in x-y)
    extruded from z0 to z1; the top scaled about the polygon's centroid (a
    frustum when top_scale < 1). Convex by construction."""
    k = len(polygon)
    cx = sum(p[0] for p in polygon) / k
    cy = sum(p[1] for p in polygon) / k
    bottom = [(x, y, z0) for x, y in polygon]
    top = [(cx + top_scale * (x - cx), cy + top_scale * (y - cy), z1) for x, y in polygon]
    faces = [(0, j + 1, j) for j in range(1, k - 1)]          # bottom: clockwise seen from +z
    faces += [(k, k + j, k + j + 1) for j in range(1, k - 1)]  # top: counter-clockwise
    for j in range(k):
        a, b = j, (j + 1) % k
        faces += [(a, b, k + b), (a, k + b, k + a)]
    return bottom + top, faces


def rotate(points, quat):
    w, x, y, z = quat
    r = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]
    return [tuple(sum(r[i][j] * p[j] for j in range(3)) for i in range(3)) for p in points]


def random_quaternion(rng):
    u1, u2, u3 = rng.random(), rng.random() * 2 * math.pi, rng.random() * 2 * math.pi
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return (b * math.cos(u3), a * math.sin(u2), a * math.cos(u2), b * math.sin(u3))


# ---- cfg writer -------------------------------------------------------------

def cfg(problem, benchmark, planners, comment):
    lines = ["# " + l for l in comment.strip().splitlines()] + ["", "[problem]"]
    lines += ["%s = %s" % (k, v) for k, v in problem]
    lines += ["", "[benchmark]"] + ["%s = %s" % (k, v) for k, v in benchmark]
    lines += ["", "[planner]"]
    for name, params in planners:
        lines.append("%s =" % name)
        lines += ["%s.%s = %s" % (name, k, v) for k, v in params]
    return "\n".join(lines) + "\n"


def pose(prefix, xyz, axis=None, theta=0.0, planar=False):
    out = [(prefix + ".x", fmt(xyz[0])), (prefix + ".y", fmt(xyz[1]))]
    if not planar:
        out.append((prefix + ".z", fmt(xyz[2])))
        ax = axis or (0, 0, 1)
        out += [(prefix + ".axis.x", fmt(ax[0])), (prefix + ".axis.y", fmt(ax[1])), (prefix + ".axis.z", fmt(ax[2]))]
    out.append((prefix + ".theta", fmt(theta)))
    return out


def volume(lo, hi):
    return [("volume.min." + a, fmt(v)) for a, v in zip("xyz", lo)] + [
        ("volume.max." + a, fmt(v)) for a, v in zip("xyz", hi)]


PLANNERS = [("rrtconnect", []), ("mdd_rrtconnect", []), ("rrt", []), ("kpiece", [])]


# ---- the configs -------------------------------------------------------------

def thin_walls(files):
    """Four walls 1 cm thick across a 20 x 10 x 10 m hall, one 1.6 m door in
    each at a seeded position; a 0.8 m cube flies from one end to the other
    without rotating. OMPL's default resolution here is 0.01 x 24.5 m."""
    rng = random.Random(1)
    walls = []
    t, door = 0.01, 1.6
    for i, x in enumerate((4.0, 8.0, 12.0, 16.0)):
        y0 = rng.uniform(1.0, 9.0 - door)
        z0 = rng.uniform(1.0, 9.0 - door)
        y1, z1 = y0 + door, z0 + door
        walls += [
            box((x, y0 / 2, 5), (t, y0, 10)),                         # left of the door
            box((x, (y1 + 10) / 2, 5), (t, 10 - y1, 10)),             # right
            box((x, (y0 + y1) / 2, z0 / 2), (t, door, z0)),           # below
            box((x, (y0 + y1) / 2, (z1 + 10) / 2), (t, door, 10 - z1)),  # above
        ]
    files["thin_walls/world.urdf"] = urdf("thin_walls", walls)
    files["thin_walls/robot.urdf"] = urdf("cube", [box((0, 0, 0), (0.8, 0.8, 0.8))])
    files["thin_walls/thin_walls.cfg"] = cfg(
        [("name", "thin_walls"), ("robot", "robot.urdf"), ("world", "world.urdf")]
        + pose("start", (1.0, 5.0, 5.0)) + pose("goal", (19.0, 5.0, 5.0))
        + volume((0, 0, 0), (20, 10, 10)) + [("translation_only", "true")],
        [("time_limit", "2.0"), ("mem_limit", "10000.0"), ("run_count", "20")],
        PLANNERS,
        """mddual benchmark config (made by scripts/make_configs.py): thin walls.
Four walls 1 cm thick, each with one door, between start and goal. The walls
are far thinner than OMPL's default motion-check resolution (1% of the
space's extent, 0.245 m here): a discrete motion validator can step over
them. Translation only (translation_only = true is mddual's key: R^3 space,
orientation fixed at the start's). The default config of scripts/run.sh.""")


ROCK_GRID = 2 ** 14  # convex_field's vertices are multiples of 1/ROCK_GRID m


def convex_field(files):
    """60 random convex frusta (OBJ meshes, one convex piece each) in a 20 m
    cube; a 1 x 0.6 x 0.4 m box robot crosses it diagonally, translating."""
    rng = random.Random(2)
    collisions = []
    for i in range(60):
        k = rng.randint(4, 8)
        a, b = rng.uniform(0.4, 1.3), rng.uniform(0.4, 1.3)
        angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(k))
        polygon = [(a * math.cos(t), b * math.sin(t)) for t in angles]
        h = rng.uniform(0.8, 2.5)
        vertices, _ = prism(polygon, -h / 2, h / 2, rng.uniform(0.4, 1.0))
        q = random_quaternion(rng)
        centre = (rng.uniform(3, 17), rng.uniform(3, 17), rng.uniform(3, 17))
        vertices = [tuple(p[j] + centre[j] for j in range(3)) for p in rotate(vertices, q)]
        # Written as the exact hull of its vertices snapped to multiples of
        # 2^-14 m, values that the decimals written and assimp's floats hold
        # exactly: every face is planar as loaded. (Rounded anyhow, the side
        # faces bend slightly and the loader reads the rock as a hollow soup.)
        snapped = [tuple(round(c * ROCK_GRID) / ROCK_GRID for c in p) for p in vertices]
        vertices, faces = meshgen.exact_hull(snapped, ROCK_GRID)
        name = "meshes/rock_%02d.obj" % i
        files["convex_field/" + name] = obj(vertices, faces, "convex obstacle %d (frustum), world frame" % i, 14)
        collisions.append(mesh(name))
    files["convex_field/world.urdf"] = urdf("convex_field", collisions)
    files["convex_field/robot.urdf"] = urdf("box", [box((0, 0, 0), (1.0, 0.6, 0.4))])
    files["convex_field/convex_field.cfg"] = cfg(
        [("name", "convex_field"), ("robot", "robot.urdf"), ("world", "world.urdf")]
        + pose("start", (1, 1, 1)) + pose("goal", (19, 19, 19))
        + volume((0, 0, 0), (20, 20, 20)) + [("translation_only", "true")],
        [("time_limit", "10.0"), ("mem_limit", "10000.0"), ("run_count", "20")],
        PLANNERS,
        """mddual benchmark config (made by scripts/make_configs.py): a 3D field
of 60 random convex obstacles (OBJ meshes, each one convex piece) in a 20 m
cube; a box robot crosses it diagonally. Translation only.""")


def narrow_passage(files):
    """A 0.5 m thick wall with a 0.6 x 3 m slot; a 0.3 x 2 x 0.3 m bar held
    across the slot at start and goal must turn upright to pass it."""
    w = []
    t, half = 0.5, 5.0
    slot_y, slot_z = 0.3, 1.5
    w.append(box((0, -(half + slot_y) / 2, 0), (t, half - slot_y, 2 * half)))   # y < -slot_y
    w.append(box((0, (half + slot_y) / 2, 0), (t, half - slot_y, 2 * half)))    # y > slot_y
    w.append(box((0, 0, -(half + slot_z) / 2), (t, 2 * slot_y, half - slot_z)))  # below the slot
    w.append(box((0, 0, (half + slot_z) / 2), (t, 2 * slot_y, half - slot_z)))   # above
    files["narrow_passage/world.urdf"] = urdf("narrow_passage", w)
    files["narrow_passage/robot.urdf"] = urdf("bar", [box((0, 0, 0), (0.3, 2.0, 0.3))])
    files["narrow_passage/narrow_passage.cfg"] = cfg(
        [("name", "narrow_passage"), ("robot", "robot.urdf"), ("world", "world.urdf")]
        + pose("start", (-3, 0, 0), (0, 0, 1), 0.0) + pose("goal", (3, 0, 0), (1, 0, 0), math.pi)
        + volume((-5, -5, -5), (5, 5, 5)),
        [("time_limit", "10.0"), ("mem_limit", "10000.0"), ("run_count", "20")],
        PLANNERS,
        """mddual benchmark config (made by scripts/make_configs.py): a narrow
passage. A bar (0.3 x 2 x 0.3 m) lies across a 0.6 m wide, 3 m tall slot in a
wall; it must turn upright to pass. SE(3).""")


def maze_se2(files):
    """A seeded depth-first maze of 8 x 8 cells of 2 m (walls 0.2 m thick,
    1 m tall across z = 0); a car-like hexagonal robot (1 x 0.5 m footprint)
    drives from one corner to the opposite one in SE(2)."""
    rng = random.Random(4)
    n, cell, t = 8, 2.0, 0.2
    right = [[True] * n for _ in range(n)]   # wall on the +x side of cell (i, j)
    up = [[True] * n for _ in range(n)]      # wall on the +y side
    seen = [[False] * n for _ in range(n)]
    stack = [(0, 0)]
    seen[0][0] = True
    while stack:
        i, j = stack[-1]
        options = [(i + di, j + dj, di, dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                   if 0 <= i + di < n and 0 <= j + dj < n and not seen[i + di][j + dj]]
        if not options:
            stack.pop()
            continue
        a, b, di, dj = rng.choice(options)
        if di == 1: right[i][j] = False
        if di == -1: right[a][b] = False
        if dj == 1: up[i][j] = False
        if dj == -1: up[a][b] = False
        seen[a][b] = True
        stack.append((a, b))
    size = n * cell
    walls = [box((size / 2, 0, 0), (size + t, t, 1)), box((size / 2, size, 0), (size + t, t, 1)),
             box((0, size / 2, 0), (t, size + t, 1)), box((size, size / 2, 0), (t, size + t, 1))]
    for i in range(n):
        for j in range(n):
            if right[i][j] and i < n - 1:
                walls.append(box(((i + 1) * cell, (j + 0.5) * cell, 0), (t, cell + t, 1)))
            if up[i][j] and j < n - 1:
                walls.append(box(((i + 0.5) * cell, (j + 1) * cell, 0), (cell + t, t, 1)))
    files["maze_se2/world.urdf"] = urdf("maze", walls)
    car = [(-0.5, -0.25), (0.3, -0.25), (0.5, -0.1), (0.5, 0.1), (0.3, 0.25), (-0.5, 0.25)]
    vertices, faces = prism(car, -0.2, 0.2)
    files["maze_se2/meshes/car.obj"] = obj(vertices, faces, "car-like hexagonal robot, body frame (x forward)")
    files["maze_se2/robot.urdf"] = urdf("car", [mesh("meshes/car.obj")])
    files["maze_se2/maze_se2.cfg"] = cfg(
        [("name", "maze_se2"), ("robot", "robot.urdf"), ("world", "world.urdf")]
        + pose("start", (1, 1, 0), theta=0.0, planar=True)
        + pose("goal", (size - 1, size - 1, 0), theta=math.pi / 2, planar=True)
        + volume((0, 0, -1), (size, size, 1)),
        [("time_limit", "10.0"), ("mem_limit", "10000.0"), ("run_count", "20")],
        PLANNERS,
        """mddual benchmark config (made by scripts/make_configs.py): a planar
maze (8 x 8 cells of 2 m) and a car-like hexagonal robot in SE(2): no z and no
axis in start and goal, so theta is the yaw and the pose is at z = 0.""")


def cubicles(files):
    """An office floor of 4 x 3 cubicles (partitions 5 cm thick, 1.6 m tall,
    a doorway in each) with desks, under a 3 m ceiling; an L-shaped robot of
    two boxes flies from a corner cubicle to the opposite one in SE(3)."""
    rng = random.Random(5)
    parts = [box((10, 7.5, -0.05), (20, 15, 0.1)), box((10, 7.5, 3.05), (20, 15, 0.1))]  # floor, ceiling
    cw, cd, h, t = 5.0, 5.0, 1.6, 0.05
    for i in range(4):
        for j in range(3):
            x0, y0 = i * cw, j * cd
            door = rng.uniform(1.0, 3.0)
            # partition along +x side with a 1.2 m doorway, and along +y side
            if i < 3:
                parts.append(box((x0 + cw, y0 + door / 2, h / 2), (t, door, h)))
                parts.append(box((x0 + cw, y0 + (door + 1.2 + cd) / 2, h / 2), (t, cd - door - 1.2, h)))
            if j < 2:
                parts.append(box((x0 + (cw - 1.2) / 2, y0 + cd, h / 2), (cw - 1.2, t, h)))
            desk = (x0 + rng.uniform(1.2, 3.8), y0 + rng.uniform(1.2, 3.8), 0.375)
            parts.append(box(desk, (1.4, 0.7, 0.75), (0, 0, rng.uniform(0, math.pi))))
    files["cubicles/world.urdf"] = urdf("cubicles", parts)
    files["cubicles/robot.urdf"] = urdf("ell", [box((0, 0, 0), (1.0, 0.25, 0.25)), box((0.375, 0.375, 0), (0.25, 0.5, 0.25))])
    files["cubicles/cubicles.cfg"] = cfg(
        [("name", "cubicles"), ("robot", "robot.urdf"), ("world", "world.urdf")]
        + pose("start", (1.5, 1.5, 2.2)) + pose("goal", (18.5, 13.5, 2.2), (0, 1, 0), math.pi / 2)
        + volume((0, 0, 0), (20, 15, 3)),
        [("time_limit", "10.0"), ("mem_limit", "10000.0"), ("run_count", "20")],
        PLANNERS,
        """mddual benchmark config (made by scripts/make_configs.py): an office
of 4 x 3 cubicles (partitions with doorways, desks, floor and ceiling, all
boxes); an L-shaped robot of two boxes flies between opposite corners. SE(3).""")


# ---- mesh configs: OMPL.app's sizes and shapes, our own geometry -------------------
#
# Single-component, closed, non-convex triangle meshes (scripts/meshgen.py),
# written as OBJ, STL and COLLADA and read through the same loaders as
# OMPL.app's meshes. A mesh robot's frame is its mean vertex (OMPL.app's
# convention, applied by the loader): the robots below are written centred on
# the mean of their vertices. Each config comes with witness_path.txt, a
# collision-free path from start to goal (tests/configs checks it densely), so
# every problem is known to be solvable.

MESH_PLANNERS = [("rrtconnect", []), ("rrt", []), ("kpiece", [])]


def quat(axis, angle):
    """Unit quaternion (w, x, y, z) of a rotation by angle about axis."""
    n = math.sqrt(sum(c * c for c in axis))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


IDENTITY = (1.0, 0.0, 0.0, 0.0)


def axis_angle(q):
    """(axis, theta) of a unit quaternion, theta in [0, pi]."""
    w, x, y, z = q if q[0] >= 0 else tuple(-c for c in q)
    s = math.sqrt(x * x + y * y + z * z)
    if s < 1e-12:
        return (0.0, 0.0, 1.0), 0.0
    return (x / s, y / s, z / s), 2 * math.atan2(s, w)


def state_pose(prefix, state):
    """cfg keys of an SE(3) state (position, quaternion)."""
    axis, theta = axis_angle(state[1])
    return pose(prefix, state[0], axis, theta)


def witness_text(states, planar, name):
    """witness_path.txt: one state per line (SE(3): x y z axis.x axis.y axis.z
    theta; SE(2): x y theta), the robot frame as in the cfg."""
    lines = [
        "# A collision-free path of the %s config (made by scripts/make_configs.py), from start to goal." % name,
        "# One state per line, the robot's pose as in the cfg: " +
        ("x y theta (SE(2))." if planar else "x y z axis.x axis.y axis.z theta (SE(3))."),
        "# Between states: position linear, rotation along the shortest arc (OMPL's interpolation).",
    ]
    for st in states:
        if planar:
            lines.append(vec(st))
        else:
            axis, theta = axis_angle(st[1])
            lines.append(vec(tuple(st[0]) + tuple(axis) + (theta,)))
    return "\n".join(lines) + "\n"


def checked(mesh, label):
    """The mesh, after checking that it is closed, one component, non-convex."""
    if meshgen.validate(mesh, label):
        raise ValueError("%s: the mesh is convex" % label)
    return mesh


def centred(mesh, planar=False):
    """The mesh moved so that the mean of its vertices is the origin (for a
    planar robot in x and y only; its z is kept, as the loader does)."""
    c = mesh.mean()
    if planar:
        c = (c[0], c[1], 0.0)
    return mesh.mapped(lambda v: (v[0] - c[0], v[1] - c[1], v[2] - c[2]))


def mesh_comment(what, mesh):
    return "mddual benchmark mesh (made by scripts/make_configs.py): %s; %d vertices, %d triangles" % (
        what, len(mesh.vertices), len(mesh.triangles))


def mesh_cfg(name, robot, world, start, goal, lo, hi, budget, comment, planar=False):
    if planar:
        poses = pose("start", start, theta=start[2], planar=True) + pose("goal", goal, theta=goal[2], planar=True)
    else:
        poses = state_pose("start", start) + state_pose("goal", goal)
    return cfg([("name", name), ("robot", robot), ("world", world)] + poses + volume(lo, hi),
               [("time_limit", fmt(budget[0])), ("mem_limit", "10000.0"), ("run_count", str(budget[1]))],
               MESH_PLANNERS, comment)


def bugtrap(files):
    """OMPL.app's bugtrap: a spiky spindle (256 triangles) escapes a thick
    cup (about 5,000 triangles) through a funnel in its lid."""
    R, H, T = 5.0, 8.0, 0.5                  # outer radius, height, wall
    rim, neck, neck_z, lip = 3.2, 0.9, 5.5, 0.5  # funnel: top radius, neck radius and height, lip
    profile = meshgen.subdivide([(0, 0), (R, 0), (R, H), (rim, H), (neck, neck_z), (neck + lip, neck_z),
                                 (R - T, H - T), (R - T, T), (0, T)], 0.7)
    trap = checked(meshgen.revolve(profile, 48), "bugtrap world")

    def radius(theta, phi):  # a spindle 2.2 m long with four fins (0.6 m at most from its axis)
        spindle = 1 / math.sqrt((math.sin(theta) / 0.4) ** 2 + (math.cos(theta) / 1.1) ** 2)
        return spindle * (1 + 0.5 * math.cos(2 * phi) ** 4 * math.sin(theta) ** 2)

    bug = checked(centred(meshgen.lat_long_body(radius, 9, 16)), "bugtrap robot")
    files["bugtrap/robot.obj"] = meshgen.obj_text(bug, mesh_comment("bugtrap robot, a finned spindle", bug))
    files["bugtrap/world.obj"] = meshgen.obj_text(
        trap, mesh_comment("bugtrap world, a cup whose lid is a funnel (neck radius 0.9 m)", trap))
    upright = IDENTITY
    path = [((2.5, 0, 1.5), quat((1, 0, 0), math.pi / 2)), ((0, 0, 2.5), upright), ((0, 0, 9.5), upright),
            ((6.2, 0, 9.5), upright), ((6.2, 0, 4.0), upright)]
    files["bugtrap/witness_path.txt"] = witness_text(path, False, "bugtrap")
    files["bugtrap/bugtrap.cfg"] = mesh_cfg(
        "bugtrap", "robot.obj", "world.obj", path[0], path[-1], (-7, -7, -1), (7, 7, 11), (15.0, 10),
        """mddual benchmark config (made by scripts/make_configs.py), of the size and
shape of OMPL.app's bugtrap: a finned spindle (%d triangles, 2.2 m long, 0.6 m
from its axis at most) lies in a thick cup (%d triangles, radius 5 m, height
8 m, walls 0.5 m); the cup's lid is a funnel whose neck (radius 0.9 m) is the
only way out. The goal is outside, beside the cup. SE(3).""" % (len(bug.triangles), len(trap.triangles)))


def twistycool(files):
    """OMPL.app's twistycool: a bar twisted by 90 degrees (60 triangles) must
    screw through a slot of a wall (about 200 triangles)."""
    L, w, t, twist, n = 2.0, 1.0, 0.25, math.pi / 2, 7
    sections = []
    for i in range(n + 1):
        x, a = -L / 2 + L * i / n, -twist / 2 + twist * i / n
        sections.append([(x, cy * math.cos(a) - cz * math.sin(a), cy * math.sin(a) + cz * math.cos(a))
                         for cy, cz in ((w / 2, t / 2), (-w / 2, t / 2), (-w / 2, -t / 2), (w / 2, -t / 2))])
    bar = checked(centred(meshgen.swept_bar(sections)), "twistycool robot")
    u = meshgen.u
    tiles = [u(v) for v in (-7, -4, -1.5, -0.5, 0.5, 1.5, 4, 7)]
    boxes = [((u(-0.125), y0, z0), (u(0.125), y1, z1), meshgen.SOLID)
             for y0, y1 in zip(tiles, tiles[1:]) for z0, z1 in zip(tiles, tiles[1:])]
    # The slot: 1.5 x 0.8125 m (the bar needs 0.88 m unturned). Its height sets
    # the difficulty; 0.8125 m was chosen by FCL discrete's success with
    # KPIECE, near OMPL.app's Twistycool (40% of 15 s runs in the starting measurement): 2
    # valid of 6 10 s runs here; with the 0.6875 m slot of earlier rounds it
    # found none in 10 runs, nor did any planner with MDD (README).
    slot_h = 0.8125
    boxes.append(((u(-0.125), u(-0.75), u(-slot_h / 2)), (u(0.125), u(0.75), u(slot_h / 2)), meshgen.EMPTY))
    surface = meshgen.Surface()
    meshgen.blocks(surface, boxes, max_size=u(3.0))
    wall = checked(surface.mesh(), "twistycool world")
    files["twistycool/robot.dae"] = meshgen.dae_text(
        bar, "robot", mesh_comment("twistycool robot, a 2 x 1 x 0.25 m bar twisted by 90 degrees", bar))
    files["twistycool/world.dae"] = meshgen.dae_text(
        wall, "wall", mesh_comment("twistycool world, a wall 0.25 m thick with a 1.5 x 0.8125 m slot", wall))
    # The bar's cross-section at x along it is turned by twist * x / L. Turned
    # by beta about x at position p, its section in the wall (x = 0) is turned
    # by beta - twist * p / L: screwing with beta = twist * p / L keeps it
    # aligned with the slot. (Unturned, it would need a slot 0.88 m tall.)
    k = twist / L
    path = [((-2.5, 0, 0), IDENTITY), ((-1.5, 0, 0), IDENTITY), ((-1.5, 0, 0), quat((1, 0, 0), -1.5 * k)),
            ((1.5, 0, 0), quat((1, 0, 0), 1.5 * k)), ((1.5, 0, 0), IDENTITY), ((2.5, 0, 0), IDENTITY)]
    files["twistycool/witness_path.txt"] = witness_text(path, False, "twistycool")
    files["twistycool/twistycool.cfg"] = mesh_cfg(
        "twistycool", "robot.dae", "world.dae", path[0], path[-1], (-3.5, -1, -1), (3.5, 1, 1), (15.0, 10),
        """mddual benchmark config (made by scripts/make_configs.py), of the size and
shape of OMPL.app's Twistycool: a bar twisted by 90 degrees along its length
(%d triangles, 2 x 1 x 0.25 m) must screw through a 1.5 x 0.8125 m slot of a
wall 0.25 m thick (%d triangles; 14 m square, so that no pose within the
bounds reaches around it). COLLADA meshes. SE(3).""" % (len(bar.triangles), len(wall.triangles)))


def cubicles_mesh(files):
    """OMPL.app's cubicles: an office of 2 x 4 cubicles welded into one mesh
    (floor, ceiling, outer walls with an entrance, partitions, desks; about
    600 triangles) and a T-shaped robot (about 40 triangles)."""
    u, S, E = meshgen.u, meshgen.SOLID, meshgen.EMPTY
    X, Y, Z, ext, slab, wall, hp = 16.0, 12.0, 3.0, 0.25, 0.25, 0.125, 1.5

    def b(lo, hi, state=S):
        return (tuple(u(v) for v in lo), tuple(u(v) for v in hi), state)

    boxes = [b((-ext, -ext, -slab), (X + ext, Y + ext, 0)), b((-ext, -ext, Z), (X + ext, Y + ext, Z + slab)),
             b((-ext, -ext, 0), (0, Y + ext, Z)), b((X, -ext, 0), (X + ext, Y + ext, Z)),
             b((0, -ext, 0), (X, 0, Z)), b((0, Y, 0), (X, Y + ext, Z)),
             b((7.0, -ext, 0), (8.5, 0, 2.25), E)]  # the entrance
    for front, back in ((4.5, 0.0), (Y - 4.5, Y)):  # two rows of four cubicles, the aisle between them
        y0, y1 = min(front, back), max(front, back)
        boxes.append(b((0, front - wall / 2, 0), (X, front + wall / 2, hp)))
        for i in range(4):
            x0 = 4.0 * i
            if i > 0:
                boxes.append(b((x0 - wall / 2, y0, 0), (x0 + wall / 2, y1, hp)))
            boxes.append(b((x0 + 1.5, front - wall / 2, 0), (x0 + 2.75, front + wall / 2, hp), E))  # doorway
            desk_y = (back, back + 0.75) if back == 0.0 else (back - 0.75, back)
            boxes.append(b((x0 + 0.5, desk_y[0], 0), (x0 + 2.0, desk_y[1], 0.75)))
    surface = meshgen.Surface()
    meshgen.blocks(surface, boxes)
    office = checked(surface.mesh(), "cubicles_mesh world")
    surface = meshgen.Surface()
    meshgen.blocks(surface, [b((-0.5, 0, -0.125), (0.5, 0.25, 0.125)), b((-0.125, -0.5, -0.125), (0.125, 0, 0.125))],
                   max_size=u(0.5))
    tee = checked(centred(surface.mesh()), "cubicles_mesh robot")
    files["cubicles_mesh/robot.stl"] = meshgen.stl_text(tee, "tee")
    files["cubicles_mesh/world.stl"] = meshgen.stl_text(office, "office")
    turned = quat((0, 1, 0), math.pi / 2)
    path = [((2, 2.5, 1.0), IDENTITY), ((2, 2.5, 2.25), IDENTITY), ((14, 9.5, 2.25), IDENTITY),
            ((14, 9.5, 2.25), turned), ((14, 9.5, 1.0), turned)]
    files["cubicles_mesh/witness_path.txt"] = witness_text(path, False, "cubicles_mesh")
    files["cubicles_mesh/cubicles_mesh.cfg"] = mesh_cfg(
        "cubicles_mesh", "robot.stl", "world.stl", path[0], path[-1], (0, 0, 0), (X, Y, Z), (10.0, 20),
        """mddual benchmark config (made by scripts/make_configs.py), of the size and
shape of OMPL.app's cubicles: an office of 2 rows of 4 cubicles (partitions
1.5 m tall with doorways, desks, floor, ceiling, outer walls with an entrance)
welded into one mesh of %d triangles, and a T-shaped robot of %d triangles
flying from a cubicle of one row to one of the other. STL meshes. SE(3).""" % (
            len(office.triangles), len(tee.triangles)))


def smooth(e0, e1, x):
    """0 below e0, 1 above e1 (or the reverse when e1 < e0), smooth between."""
    t = min(1.0, max(0.0, (x - e0) / (e1 - e0)))
    return t * t * (3 - 2 * t)


def inset(x, y, w, d, r):
    """0 on the edge of the w x d rectangle, 1 deeper inside than r."""
    return smooth(0, r, min(x, w - x, y, d - y))


def sofa(w, d):
    """Height (m) of a sofa of w x d m over its footprint: seat with two
    cushions, a back along y = d, arms at both ends, rounded edges."""
    def h(x, y):
        back = smooth(d - 0.3, d - 0.2, y)
        arms = max(smooth(0.25, 0.15, x), smooth(w - 0.25, w - 0.15, x))
        cushion = 0.04 * math.sin(math.pi * ((2 * x / w) % 1.0)) * inset(x, y, w, d, 0.15)
        return 0.3 + 0.12 * inset(x, y, w, d, 0.08) + cushion + max(0.4 * back, 0.22 * arms)
    return h


def bed(w, d):
    """A bed: mattress with rounded edges, a headboard along y = 0, pillows."""
    def h(x, y):
        pillows = 0.08 * math.sin(math.pi * ((2 * x / w) % 1.0)) ** 2 * smooth(0.15, 0.25, y) * smooth(0.65, 0.5, y)
        return 0.35 + 0.2 * inset(x, y, w, d, 0.1) + pillows + 0.55 * smooth(0.15, 0.08, y)
    return h


def block(height, bevel=0.05):
    """A cabinet, table or wardrobe: a flat top with bevelled edges."""
    return lambda w, d: (lambda x, y: height * (0.92 + 0.08 * inset(x, y, w, d, bevel)))


def basin(rim, depth, margin):
    """A bathtub or a counter with a sink: a rim around a smooth basin."""
    return lambda w, d: (lambda x, y: rim * (0.9 + 0.1 * inset(x, y, w, d, 0.05))
                         - depth * inset(x - margin, y - margin, w - 2 * margin, d - 2 * margin, 0.1))


def ottoman(w, d):
    """A low dome on a square footprint."""
    return lambda x, y: 0.3 + 0.12 * math.sin(math.pi * x / w) * math.sin(math.pi * y / d)


def heightfield_cells(w, d, triangles):
    """Grid of a w x d height field with about `triangles` triangles."""
    cells = triangles / 2
    nx = max(2, round(math.sqrt(cells * w / d)))
    return nx, max(2, round(cells / nx))


def apartment(files):
    """OMPL.app's Apartment: a couch (about 3,000 triangles) carried through
    an apartment (about 40,000 triangles): large flat walls, floor and
    ceiling, and tessellated furniture (height fields) welded to the floor."""
    u, S, E = meshgen.u, meshgen.SOLID, meshgen.EMPTY
    X, Y, Z, ext, inner, slab, door = 14.0, 10.0, 2.625, 0.25, 0.125, 0.25, 2.125

    def b(lo, hi, state=S):
        return (tuple(u(v) for v in lo), tuple(u(v) for v in hi), state)

    boxes = [b((-ext, -ext, -slab), (X + ext, Y + ext, 0)), b((-ext, -ext, Z), (X + ext, Y + ext, Z + slab)),
             b((-ext, -ext, 0), (0, Y + ext, Z)), b((X, -ext, 0), (X + ext, Y + ext, Z)),
             b((0, -ext, 0), (X, 0, Z)), b((0, Y, 0), (X, Y + ext, Z)),
             b((0, 4.0, 0), (X, 4.0 + inner, Z)), b((0, 6.625, 0), (X, 6.625 + inner, Z)),  # the hall's walls
             b((7.9375, 0, 0), (7.9375 + inner, 4.0, Z)),  # living room | kitchen
             b((4.5, 6.75, 0), (4.5 + inner, Y, Z)), b((8.0, 6.75, 0), (8.0 + inner, Y, Z))]  # bedroom | bath | bedroom
    for x0, x1, y0, y1 in ((2.75, 4.25, 4.0, 4.125), (10.0, 11.5, 4.0, 4.125),     # living room, kitchen to hall
                           (7.9375, 8.0625, 1.0, 2.5),                             # living room to kitchen
                           (1.375, 2.875, 6.625, 6.75), (5.5, 6.5, 6.625, 6.75), (10.625, 12.125, 6.625, 6.75),
                           (-ext, 0, 4.75, 5.875)):                                # the front door
        boxes.append(b((x0, y0, 0), (x1, y1, door), E))
    furniture = [  # footprint x0, x1, y0, y1 and shape
        (5.0, 7.25, 0.25, 1.125, sofa), (5.5, 6.75, 1.75, 2.5, block(0.45)),
        (0.5, 1.5, 0.5, 1.5, ottoman), (0.25, 0.75, 2.0, 3.5, block(0.55)),                   # living room
        (10.0, 12.5, 1.5, 2.5, basin(0.9, 0.25, 0.5)), (13.25, 13.875, 0.25, 3.75, block(0.9, 0.02)),  # kitchen
        (0.25, 2.25, 7.75, 9.875, bed), (3.75, 4.375, 7.25, 9.75, block(2.0)),                  # bedroom
        (6.125, 7.875, 9.0, 9.875, basin(0.55, 0.4, 0.08)), (4.75, 5.75, 9.25, 9.875, basin(0.85, 0.15, 0.2)),
        (12.75, 13.875, 7.5, 9.75, bed), (8.375, 9.75, 9.25, 9.875, block(0.8))]               # bedroom
    for x0, x1, y0, y1, _ in furniture:
        boxes.append(b((x0, y0, 0), (x1, y1, 0.125), meshgen.CUSTOM))
    surface = meshgen.Surface()
    meshgen.blocks(surface, boxes)
    for x0, x1, y0, y1, shape in furniture:
        w, d = x1 - x0, y1 - y0
        nx, ny = heightfield_cells(w, d, 2800)
        local = shape(w, d)
        meshgen.heightfield(surface, u(x0), u(x1), u(y0), u(y1), 0, nx, ny,
                            lambda x, y, local=local, x0=x0, y0=y0: local(x - x0, y - y0))
    rooms = checked(surface.mesh(), "apartment world")
    surface = meshgen.Surface()
    meshgen.heightfield(surface, u(-1.0), u(1.0), u(-0.45), u(0.45), 0, 50, 26,
                        lambda x, y: sofa(2.0, 0.9)(x + 1.0, y + 0.45), bottom=True)
    couch = checked(centred(surface.mesh()), "apartment robot")
    files["apartment/robot.obj"] = meshgen.obj_text(couch, mesh_comment("apartment robot, a couch", couch))
    files["apartment/world.obj"] = meshgen.obj_text(rooms, mesh_comment("apartment world", rooms))
    z = 0.0625 - couch.box()[0][2]  # the couch's bottom 6.25 cm above the floor
    along_y = quat((0, 0, 1), math.pi / 2)
    path = [((3.5, 2.0, z), IDENTITY), ((3.5, 2.0, z), along_y), ((3.5, 5.375, z), along_y),
            ((3.5, 5.375, z), IDENTITY), ((11.375, 5.375, z), IDENTITY), ((11.375, 5.375, z), along_y),
            ((11.375, 8.375, z), along_y), ((11.375, 8.375, z), IDENTITY)]
    files["apartment/witness_path.txt"] = witness_text(path, False, "apartment")
    files["apartment/apartment.cfg"] = mesh_cfg(
        "apartment", "robot.obj", "world.obj", path[0], path[-1], (0, 0, 0), (X, Y, Z), (30.0, 5),
        """mddual benchmark config (made by scripts/make_configs.py), of the size and
shape of OMPL.app's Apartment: a couch (%d triangles, 2 x 0.9 x 0.85 m) is
carried from the living room through a hall to a bedroom of an apartment
(%d triangles: floor, ceiling and walls of large flat triangles, doors
1.5 x 2.125 m, and twelve pieces of furniture tessellated as height fields,
all welded into one mesh). OBJ meshes. SE(3).""" % (len(couch.triangles), len(rooms.triangles)))


def maze_planar(files):
    """OMPL.app's Maze_planar: a boomerang-shaped robot (68 triangles) in a
    maze of 10 x 10 cells welded into one mesh (about 2,000 triangles), SE(2)."""
    rng = random.Random(9)
    n, cell, t = 10, 2.0, 0.25
    right = [[True] * n for _ in range(n)]   # wall on the +x side of cell (i, j)
    up = [[True] * n for _ in range(n)]      # wall on the +y side
    seen = [[False] * n for _ in range(n)]
    parent = {(0, 0): None}
    stack = [(0, 0)]
    seen[0][0] = True
    while stack:
        i, j = stack[-1]
        options = [(i + di, j + dj, di, dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                   if 0 <= i + di < n and 0 <= j + dj < n and not seen[i + di][j + dj]]
        if not options:
            stack.pop()
            continue
        a, c, di, dj = rng.choice(options)
        if di == 1: right[i][j] = False
        if di == -1: right[a][c] = False
        if dj == 1: up[i][j] = False
        if dj == -1: up[a][c] = False
        seen[a][c] = True
        parent[(a, c)] = (i, j)
        stack.append((a, c))
    u, S = meshgen.u, meshgen.SOLID
    lo_z, hi_z = u(-0.5), u(0.5)

    def wall(x0, y0, x1, y1):
        return ((u(x0 * cell) - u(t / 2), u(y0 * cell) - u(t / 2), lo_z),
                (u(x1 * cell) + u(t / 2), u(y1 * cell) + u(t / 2), hi_z), S)

    boxes = [wall(0, 0, n, 0), wall(0, n, n, n), wall(0, 0, 0, n), wall(n, 0, n, n)]
    for i in range(n):
        for j in range(n):
            if right[i][j] and i < n - 1:
                boxes.append(wall(i + 1, j, i + 1, j + 1))
            if up[i][j] and j < n - 1:
                boxes.append(wall(i, j + 1, i + 1, j + 1))
    surface = meshgen.Surface()
    meshgen.blocks(surface, boxes, max_size=u(2.0))
    maze = checked(surface.mesh(), "maze_planar world")
    radius, half, width, height, steps = 0.8, math.radians(50), 0.3, 0.4, 8
    sections = []
    for k in range(steps + 1):
        a = -half + 2 * half * k / steps
        c, s_ = math.cos(a), math.sin(a)
        ri, ro = radius - width / 2, radius + width / 2
        sections.append([(ri * c, ri * s_, -height / 2), (ro * c, ro * s_, -height / 2),
                         (ro * c, ro * s_, height / 2), (ri * c, ri * s_, height / 2)])
    boomerang = checked(centred(meshgen.swept_bar(sections), planar=True), "maze_planar robot")
    files["maze_planar/robot.stl"] = meshgen.stl_text(boomerang, "boomerang")
    files["maze_planar/world.dae"] = meshgen.dae_text(maze, "maze", mesh_comment("maze_planar world", maze))
    cells = [(n - 1, n - 1)]
    while parent[cells[-1]] is not None:
        cells.append(parent[cells[-1]])
    path = [((i + 0.5) * cell, (j + 0.5) * cell, 0.0) for i, j in reversed(cells)]
    path.append(path[-1][:2] + (math.pi / 2,))
    files["maze_planar/witness_path.txt"] = witness_text(path, True, "maze_planar")
    files["maze_planar/maze_planar.cfg"] = mesh_cfg(
        "maze_planar", "robot.stl", "world.dae", path[0], path[-1], (0, 0, -1), (n * cell, n * cell, 1), (10.0, 20),
        """mddual benchmark config (made by scripts/make_configs.py), of the size and
shape of OMPL.app's Maze_planar: a maze of 10 x 10 cells of 2 m (walls 0.25 m
thick, 1 m tall across z = 0) welded into one mesh of %d triangles (COLLADA),
and a boomerang-shaped robot of %d triangles (STL, an arc 0.3 m wide and 0.4 m
tall) going from one corner to the opposite one. SE(2): theta is the yaw, the
pose lies at z = 0.""" % (len(maze.triangles), len(boomerang.triangles)), planar=True)


CONFIGS = {"thin_walls": thin_walls, "convex_field": convex_field, "narrow_passage": narrow_passage,
           "maze_se2": maze_se2, "cubicles": cubicles, "bugtrap": bugtrap, "twistycool": twistycool,
           "cubicles_mesh": cubicles_mesh, "apartment": apartment, "maze_planar": maze_planar,
           "arm7": arm_configs.arm7, "panda": panda_configs.panda}


def make(names):
    files = {}
    for name in names:
        CONFIGS[name](files)
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with configs/ instead of writing")
    parser.add_argument("--out", default=OUT, help="output folder (default: configs/)")
    parser.add_argument("--only", metavar="NAME[,NAME...]",
                        help="only these configs (default: all of them: %s)" % ", ".join(CONFIGS))
    args = parser.parse_args()
    names = list(CONFIGS) if args.only is None else [n.strip() for n in args.only.split(",") if n.strip()]
    unknown = [n for n in names if n not in CONFIGS]
    if unknown or not names:
        parser.error("--only: unknown config(s) %s (known: %s)" % (", ".join(unknown) or "(none)", ", ".join(CONFIGS)))
    files = make(names)
    stale = []
    for rel, text in sorted(files.items()):
        path = os.path.join(args.out, rel)
        if args.check:
            try:
                with open(path) as f:
                    if f.read() != text:
                        stale.append(rel)
            except OSError:
                stale.append(rel)
            continue
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
    if args.check:
        if stale:
            print("configs out of date (run scripts/make_configs.py): " + ", ".join(stale))
            return 1
        print("configs up to date (%d files)" % len(files))
    else:
        print("wrote %d files under %s" % (len(files), args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
