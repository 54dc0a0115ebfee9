"""mddual's own 7-joint arm (configs/arm7/): URDF, SRDF and link meshes.

A serial arm of Panda-like proportions, our own geometry: seven revolute
joints alternating about z and y, link meshes of a few hundred triangles
(revolved bodies, convex and non-convex with a waist), primitives (boxes,
cylinders) on the base, wrist and hand, and a two-finger gripper on
prismatic joints (the right finger mimics the left). The SRDF names the
groups `arm` (a chain), `hand` (the finger joint) and `arm_hand`
(subgroups), a group state `ready`, and disables the pairs that touch in
every configuration (adjacent links, the hand and its fingers).

Used by scripts/make_configs.py (`make_configs.py --only arm7`). Python
standard library only; deterministic output.
"""

import math

import arm_problems
import meshgen

# Joint name, axis, limits (rad), length of the link it carries (m), radius.
JOINTS = [
    ("joint1", (0, 0, 1), (-2.9, 2.9), 0.20, 0.060),
    ("joint2", (0, 1, 0), (-1.76, 1.76), 0.30, 0.055),
    ("joint3", (0, 0, 1), (-2.9, 2.9), 0.10, 0.050),
    ("joint4", (0, 1, 0), (-3.0, -0.07), 0.30, 0.050),
    ("joint5", (0, 0, 1), (-2.9, 2.9), 0.10, 0.045),
    ("joint6", (0, 1, 0), (-0.02, 3.75), 0.10, 0.045),
    ("joint7", (0, 0, 1), (-2.9, 2.9), 0.05, 0.040),
]
BASE_HEIGHT = 0.15
FINGER_TRAVEL = 0.04
# Links whose mesh has a waist (non-convex); the others are convex.
WAISTED = {"link2", "link4"}
READY = [0.0, -0.3, 0.0, -1.2, 0.0, 1.4, 0.8]


fmt = arm_problems.fmt


def vec(v):
    return " ".join(fmt(x) for x in v)


def link_mesh(length, radius, waisted):
    """A revolved body along +z from 0 to `length`, rounded ends; with a
    waist (70% of the radius at mid-length) when `waisted`."""
    return meshgen.revolve(link_profile(length, radius, waisted), 16)


def link_profile(length, radius, waisted):
    """The (r, z) profile of link_mesh, from the axis at z = 0 to the axis
    at z = length."""
    profile = [(0.0, 0.0)]
    caps = 4
    for k in range(1, caps + 1):  # lower cap, a quarter circle
        a = 0.5 * math.pi * k / caps
        profile.append((radius * math.sin(a), radius * (1 - math.cos(a)) * 0.5))
    body = 8
    for k in range(1, body):
        z = radius * 0.5 + (length - radius) * k / body
        r = radius
        if waisted:
            r = radius * (1.0 - 0.3 * math.sin(math.pi * k / body))
        profile.append((r, z))
    for k in range(caps, 0, -1):  # upper cap
        a = 0.5 * math.pi * k / caps
        profile.append((radius * math.sin(a), length - radius * (1 - math.cos(a)) * 0.5))
    profile.append((0.0, length))
    return profile


def collision(geometry, xyz=(0, 0, 0), rpy=(0, 0, 0)):
    return ('      <collision><origin xyz="%s" rpy="%s"/><geometry>%s</geometry></collision>'
            % (vec(xyz), vec(rpy), geometry))


def box(size, xyz=(0, 0, 0)):
    return collision('<box size="%s"/>' % vec(size), xyz)


def cylinder(radius, length, xyz=(0, 0, 0), rpy=(0, 0, 0)):
    return collision('<cylinder radius="%s" length="%s"/>' % (fmt(radius), fmt(length)), xyz, rpy)


def link(name, collisions):
    return ['  <link name="%s">' % name, *collisions, '  </link>']


def joint(name, kind, parent, child, xyz, axis=None, limits=None, mimic=None):
    lines = ['  <joint name="%s" type="%s">' % (name, kind),
             '    <parent link="%s"/><child link="%s"/>' % (parent, child),
             '    <origin xyz="%s" rpy="0 0 0"/>' % vec(xyz)]
    if axis is not None:
        lines.append('    <axis xyz="%s"/>' % vec(axis))
    if limits is not None:
        lines.append('    <limit lower="%s" upper="%s" effort="100" velocity="2"/>' % (fmt(limits[0]), fmt(limits[1])))
    if mimic is not None:
        lines.append('    <mimic joint="%s" multiplier="1" offset="0"/>' % mimic)
    lines.append('  </joint>')
    return lines


def urdf_text(files, folder):
    lines = ['<?xml version="1.0"?>', '<!-- mddual\'s own 7-joint arm (scripts/arm_configs.py) -->',
             '<robot name="arm7">']
    lines += link("base", [cylinder(0.1, BASE_HEIGHT, (0, 0, BASE_HEIGHT / 2))])
    parent, origin = "base", (0, 0, BASE_HEIGHT)
    for i, (name, axis, limits, length, radius) in enumerate(JOINTS, start=1):
        child = "link%d" % i
        mesh_name = "meshes/%s.obj" % child
        mesh = link_mesh(length, radius, child in WAISTED)
        meshgen.validate(mesh, child)
        files[folder + mesh_name] = meshgen.obj_text(mesh, "arm7 %s: %d triangles%s" % (
            child, len(mesh.triangles), ", non-convex (a waist)" if child in WAISTED else ", convex"))
        geometry = [collision('<mesh filename="package://arm7/%s"/>' % mesh_name)]
        if i == 6:  # a wrist housing: a box on the side
            geometry.append(box((0.06, 0.05, 0.06), (0.05, 0, 0.05)))
        lines += link(child, geometry)
        lines += joint(name, "revolute", parent, child, origin, axis, limits)
        parent, origin = child, (0, 0, length)
    lines += link("hand", [box((0.06, 0.2, 0.05), (0, 0, 0.035)),
                           cylinder(0.04, 0.02, (0, 0, 0.01))])
    lines += joint("hand_mount", "fixed", parent, "hand", origin)
    for side, sign in (("left", 1), ("right", -1)):
        lines += link("finger_" + side, [box((0.02, 0.015, 0.05), (0, sign * 0.0125, 0.025))])
        lines += joint("finger_" + side + "_joint", "prismatic", "hand", "finger_" + side, (0, sign * 0.0, 0.06),
                       (0, sign, 0), (0, FINGER_TRAVEL), "finger_left_joint" if side == "right" else None)
    lines.append('</robot>')
    return "\n".join(lines) + "\n"


def disabled_pairs():
    """The link pairs the SRDF exempts from the self check: those that touch
    in every configuration (adjacent links, the hand and its fingers)."""
    names = ["base"] + ["link%d" % i for i in range(1, 8)] + ["hand", "finger_left", "finger_right"]
    pairs = [(names[i], names[i + 1]) for i in range(8)]
    return pairs + [("hand", "finger_left"), ("hand", "finger_right"), ("link7", "finger_left"),
                    ("link7", "finger_right"), ("link6", "hand")]


def srdf_text():
    adjacent = disabled_pairs()
    lines = ['<?xml version="1.0"?>', '<!-- mddual\'s own 7-joint arm (scripts/arm_configs.py) -->',
             '<robot name="arm7">',
             '  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base"/>',
             '  <group name="arm"><chain base_link="base" tip_link="link7"/></group>',
             '  <group name="hand"><joint name="finger_left_joint"/><joint name="finger_right_joint"/></group>',
             '  <group name="arm_hand"><group name="arm"/><group name="hand"/></group>',
             '  <group_state name="ready" group="arm">']
    lines += ['    <joint name="joint%d" value="%s"/>' % (i + 1, fmt(v)) for i, v in enumerate(READY)]
    lines += ['  </group_state>']
    seen = set()
    for a, b in adjacent:
        if (a, b) in seen:
            continue
        seen.add((a, b))
        lines.append('  <disable_collisions link1="%s" link2="%s" reason="Adjacent"/>' % (a, b))
    lines.append('</robot>')
    return "\n".join(lines) + "\n"


# ---- forward kinematics and bounding spheres, for scripts/arm_problems.py ------------

def _rot(axis, a):
    c, s = math.cos(a), math.sin(a)
    if axis == (0, 0, 1):
        return ((c, -s, 0), (s, c, 0), (0, 0, 1))
    return ((c, 0, s), (0, 1, 0), (-s, 0, c))  # about y


def link_spheres():
    """Per link, spheres (centre, radius) in the link frame that contain it
    (the URDF's primitives grown by 2 mm for their circumscribed polygons)."""
    h = BASE_HEIGHT
    spheres = {"base": [((0, 0, z), math.hypot(0.102, h / 6)) for z in (h / 6, h / 2, 5 * h / 6)]}
    for i, (_, _, _, length, radius) in enumerate(JOINTS, start=1):
        spheres["link%d" % i] = arm_problems.slab_spheres(link_profile(length, radius, "link%d" % i in WAISTED))
    spheres["link6"] += arm_problems.box_spheres((0.05, 0, 0.05), (0.06, 0.05, 0.06), 2, 1)
    spheres["hand"] = (arm_problems.box_spheres((0, 0, 0.035), (0.06, 0.2, 0.05), 1, 4)
                       + [((0, 0, 0.01), math.hypot(0.042, 0.01))])
    for side, sign in (("left", 1), ("right", -1)):
        spheres["finger_" + side] = arm_problems.box_spheres((0, sign * 0.0125, 0.025), (0.02, 0.015, 0.05), 2, 2)
    return spheres


def link_poses(q, finger=0.0):
    """(R, p) of every link in the base frame for the 7 arm angles q."""
    apply = arm_problems.apply
    poses = {"base": (((1, 0, 0), (0, 1, 0), (0, 0, 1)), (0.0, 0.0, 0.0))}
    R, p = poses["base"]
    origin = (0, 0, BASE_HEIGHT)
    for i, (_, axis, _, length, _) in enumerate(JOINTS, start=1):
        p = apply(R, p, origin)
        R = arm_problems.mul(R, _rot(axis, q[i - 1]))
        poses["link%d" % i] = (R, p)
        origin = (0, 0, length)
    hand = (R, apply(R, p, origin))
    poses["hand"] = hand
    poses["finger_left"] = (hand[0], apply(hand[0], hand[1], (0, finger, 0.06)))
    poses["finger_right"] = (hand[0], apply(hand[0], hand[1], (0, -finger, 0.06)))
    return poses


ARM7 = arm_problems.ArmSpec(
    name="arm7", group="arm", joints=[name for name, _, _, _, _ in JOINTS],
    limits=[limits for _, _, limits, _, _ in JOINTS], ready=READY, finger_joint="finger_left_joint", finger=0.02,
    link_poses=link_poses, spheres=link_spheres(), disabled=disabled_pairs(), hand=("hand", (0, 0, 0.08)),
    scale=1.0, problems=20, seed=1000)


def arm7(files):
    folder = "arm7/"
    files[folder + "arm7.urdf"] = urdf_text(files, folder)
    files[folder + "arm7.srdf"] = srdf_text()
    arm_problems.problems(files, folder, ARM7)
