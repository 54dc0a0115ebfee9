#!/usr/bin/env python3
"""Writes mddual's benchmark configs and their assets into configs/.

Every config is an OMPL.app benchmark file (.cfg, INI) with its robot and
world: URDF files of primitives, and OBJ meshes written here. The output is
deterministic (seeded), so `make_configs.py --check` can verify that the
committed files are what this script makes. Python standard library only.

    scripts/make_configs.py            # (re)write configs/
    scripts/make_configs.py --check    # exit 1 if configs/ differs

The configs (see configs/README.md for what each one exercises):
  thin_walls      walls 1 cm thick, thinner than OMPL's default motion-check
                  resolution, with one door each; translation only (R^3)
  convex_field    a 3D field of random convex obstacles (OBJ meshes);
                  translation only (R^3)
  narrow_passage  a bar that must turn to pass a slot in a wall, SE(3)
  maze_se2        a planar maze, car-like polygonal robot, SE(2)
  cubicles        an office of cubicles made of boxes, SE(3)
"""

import argparse
import math
import os
import random
import sys

import meshgen

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


def make():
    files = {}
    for build in (thin_walls, convex_field, narrow_passage, maze_se2, cubicles):
        build(files)
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with configs/ instead of writing")
    parser.add_argument("--out", default=OUT, help="output folder (default: configs/)")
    args = parser.parse_args()
    files = make()
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
