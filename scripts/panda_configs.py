"""A Franka Emika Panda for mddual (configs/panda/): URDF, SRDF, problem sets.

The kinematics are the Panda's published ones (franka_description): the
joint origins (xyz, rpy), axes and position limits of panda_joint1..7, the
flange panda_link8 0.107 m beyond joint 7, the hand turned by -45 degrees
about it, and the two fingers on prismatic joints 0.0584 m out of the hand
(0 to 0.04 m; the right finger mimics the left).

The collision geometry is an approximation made of primitives, NOT
Franka's meshes (their licence keeps them out of this repository, and they
are not needed offline): each link is covered by the capsules of
franka_description's coarse self-collision model (the `*_sc` links), each
capsule written as a cylinder and a sphere at either end, the hand by the
larger of its two capsules, and each finger by the five boxes of
franka_description's finger collision model. The volume is close to the
real arm's but not equal to it: a planner's result on it is not a result
on the meshed Panda.

The SRDF names the groups `panda_arm` (the chain panda_link0 to
panda_link8), `hand` (the hand and fingers) and `panda_arm_hand`, the group
state `ready`, and disables the link pairs in contact in every
configuration: the adjacent links (the hand counts as adjacent to
panda_link7, panda_link8 having no geometry) and ALWAYS below, found by
sampling the joint space with mddual's exact check
(tests/configs/test_arm_problems.cpp checks both halves: each disabled pair
that is not adjacent touches in every sample, each checked pair is free in
some).

Six problem sets of PROBLEMS problems in MotionBenchMaker's format are made
by scripts/arm_problems.py, arm7's scenes shrunk by SCALE for the Panda's
reach (about 0.85 m from the shoulder).

Used by scripts/make_configs.py (`make_configs.py --only panda`). Python
standard library only; deterministic output.
"""

import math

import arm_problems

fmt = arm_problems.fmt
HALF_PI = math.pi / 2

# Joint origin in the parent link (xyz, rpy) and position limits (rad); every
# axis is the child frame's z.
JOINTS = [
    ("panda_joint1", (0, 0, 0.333), (0, 0, 0), (-2.8973, 2.8973), 87, 2.175),
    ("panda_joint2", (0, 0, 0), (-HALF_PI, 0, 0), (-1.7628, 1.7628), 87, 2.175),
    ("panda_joint3", (0, -0.316, 0), (HALF_PI, 0, 0), (-2.8973, 2.8973), 87, 2.175),
    ("panda_joint4", (0.0825, 0, 0), (HALF_PI, 0, 0), (-3.0718, -0.0698), 87, 2.175),
    ("panda_joint5", (-0.0825, 0.384, 0), (-HALF_PI, 0, 0), (-2.8973, 2.8973), 12, 2.61),
    ("panda_joint6", (0, 0, 0), (HALF_PI, 0, 0), (-0.0175, 3.7525), 12, 2.61),
    ("panda_joint7", (0.088, 0, 0), (HALF_PI, 0, 0), (-2.8973, 2.8973), 12, 2.61),
]
FLANGE = 0.107  # panda_link8 along link7's z
HAND_YAW = -math.pi / 4  # panda_hand about panda_link8's z
FINGER_Z = 0.0584  # the fingers' joints in the hand frame
FINGER_TRAVEL = 0.04
READY = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]
PROBLEMS = 10
SCALE = 0.8
LINKS = ["panda_link%d" % i for i in range(9)] + ["panda_hand", "panda_leftfinger", "panda_rightfinger"]

# Capsules per link: centre, direction (a unit vector), radius, length of the
# cylinder (between the caps' centres), in the link frame.
_D45 = (math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0)
CAPSULES = {
    "panda_link0": [((-0.075, 0, 0.06), (1, 0, 0), 0.06, 0.03)],
    "panda_link1": [((0, 0, -0.1915), (0, 0, 1), 0.06, 0.283)],
    "panda_link2": [((0, 0, 0), (0, 0, 1), 0.06, 0.12)],
    "panda_link3": [((0, 0, -0.145), (0, 0, 1), 0.06, 0.15)],
    "panda_link4": [((0, 0, 0), (0, 0, 1), 0.06, 0.12)],
    "panda_link5": [((0, 0, -0.26), (0, 0, 1), 0.06, 0.1), ((0, 0.08, -0.13), (0, 0, 1), 0.025, 0.14)],
    "panda_link6": [((0, 0, -0.03), (0, 0, 1), 0.05, 0.08)],
    # franka_description turns link7's coarse model by 45 degrees about z.
    "panda_link7": [((0, 0, 0.01), (0, 0, 1), 0.04, 0.14),
                    ((0.06 * _D45[0], 0.06 * _D45[1], 0.082), _D45, 0.03, 0.01)],
    "panda_hand": [((0, 0, 0.04), (0, 1, 0), 0.04, 0.1)],
}
# The left finger's boxes (centre, size, roll about x), in its frame; the
# right finger's are their mirror images in y.
FINGER_BOXES = [
    ((0, 0.0015, 0.06), (0.018, 0.003, 0.015), 0.0),  # end of the fingertip
    ((0, 0.0185, 0.011), (0.022, 0.015, 0.02), 0.0),  # screw mount
    ((0, 0.0068, 0.0022), (0.022, 0.0088, 0.0038), 0.0),  # carriage sledge
    ((0, 0.0159, 0.02835), (0.0175, 0.007, 0.0235), math.pi / 6),  # diagonal part
    ((0, 0.00758, 0.04525), (0.0175, 0.0152, 0.0185), 0.0),  # rubber tip
]
# Non-adjacent pairs in contact in every configuration, found by sampling
# with mddual's exact check: none. In 2,000 uniform samples of the joint
# space every non-adjacent pair is free in most of them (the closest,
# panda_link1 and panda_link3, touch in 565); the test keeps this list true.
ALWAYS = []


def vec(v):
    return " ".join(fmt(x) for x in v)


def adjacent_pairs():
    """Each link with its parent; panda_link8 has no geometry, so the hand
    is paired with panda_link7 instead."""
    chain = ["panda_link%d" % i for i in range(8)]
    pairs = list(zip(chain, chain[1:]))
    return pairs + [("panda_link7", "panda_hand"), ("panda_hand", "panda_leftfinger"),
                    ("panda_hand", "panda_rightfinger")]


def disabled_pairs():
    return adjacent_pairs() + ALWAYS


def _axis_rpy(direction):
    """An rpy that turns z onto the unit `direction` (in the x-y plane or z)."""
    if direction[2] == 1:
        return (0, 0, 0)
    if direction[1] == 1:
        return (-HALF_PI, 0, 0)
    return (0, HALF_PI, math.atan2(direction[1], direction[0]))


def _collision(geometry, xyz, rpy=(0, 0, 0)):
    return ('      <collision><origin xyz="%s" rpy="%s"/><geometry>%s</geometry></collision>'
            % (vec(xyz), vec(rpy), geometry))


def capsule_collisions(centre, direction, radius, length):
    out = [_collision('<cylinder radius="%s" length="%s"/>' % (fmt(radius), fmt(length)), centre,
                      _axis_rpy(direction))]
    for t in (-length / 2, length / 2):
        out.append(_collision('<sphere radius="%s"/>' % fmt(radius),
                              tuple(centre[i] + t * direction[i] for i in range(3))))
    return out


def finger_boxes(sign):
    return [((c[0], sign * c[1], c[2]), size, sign * roll) for c, size, roll in FINGER_BOXES]


def urdf_text():
    lines = ['<?xml version="1.0"?>',
             '<!-- A Franka Emika Panda: the published kinematics and limits, collision geometry of primitives',
             '     approximating the links (not Franka\'s meshes). Made by scripts/panda_configs.py. -->',
             '<robot name="panda">']
    for link in LINKS:
        geometry = []
        for centre, direction, radius, length in CAPSULES.get(link, []):
            geometry += capsule_collisions(centre, direction, radius, length)
        if link.endswith("finger"):
            for c, size, roll in finger_boxes(1 if link == "panda_leftfinger" else -1):
                geometry.append(_collision('<box size="%s"/>' % vec(size), c, (roll, 0, 0)))
        lines += ['  <link name="%s">' % link, *geometry, '  </link>'] if geometry else ['  <link name="%s"/>' % link]
    parent = "panda_link0"
    for i, (name, xyz, rpy, (lo, hi), effort, velocity) in enumerate(JOINTS, start=1):
        child = "panda_link%d" % i
        lines += ['  <joint name="%s" type="revolute">' % name,
                  '    <parent link="%s"/><child link="%s"/>' % (parent, child),
                  '    <origin xyz="%s" rpy="%s"/>' % (vec(xyz), vec(rpy)), '    <axis xyz="0 0 1"/>',
                  '    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>' % (fmt(lo), fmt(hi), fmt(effort),
                                                                                    fmt(velocity)),
                  '  </joint>']
        parent = child
    lines += ['  <joint name="panda_joint8" type="fixed">',
              '    <parent link="panda_link7"/><child link="panda_link8"/>',
              '    <origin xyz="0 0 %s" rpy="0 0 0"/>' % fmt(FLANGE), '  </joint>',
              '  <joint name="panda_hand_joint" type="fixed">',
              '    <parent link="panda_link8"/><child link="panda_hand"/>',
              '    <origin xyz="0 0 0" rpy="0 0 %s"/>' % fmt(HAND_YAW), '  </joint>']
    for k, (side, sign) in enumerate((("left", 1), ("right", -1)), start=1):
        lines += ['  <joint name="panda_finger_joint%d" type="prismatic">' % k,
                  '    <parent link="panda_hand"/><child link="panda_%sfinger"/>' % side,
                  '    <origin xyz="0 0 %s" rpy="0 0 0"/>' % fmt(FINGER_Z), '    <axis xyz="0 %d 0"/>' % sign,
                  '    <limit lower="0" upper="%s" effort="20" velocity="0.2"/>' % fmt(FINGER_TRAVEL)]
        if side == "right":
            lines.append('    <mimic joint="panda_finger_joint1" multiplier="1" offset="0"/>')
        lines.append('  </joint>')
    lines.append('</robot>')
    return "\n".join(lines) + "\n"


def srdf_text():
    lines = ['<?xml version="1.0"?>', '<!-- A Franka Emika Panda (scripts/panda_configs.py) -->',
             '<robot name="panda">',
             '  <virtual_joint name="virtual_joint" type="fixed" parent_frame="world" child_link="panda_link0"/>',
             '  <group name="panda_arm"><chain base_link="panda_link0" tip_link="panda_link8"/></group>',
             '  <group name="hand"><link name="panda_hand"/><link name="panda_leftfinger"/>'
             '<link name="panda_rightfinger"/></group>',
             '  <group name="panda_arm_hand"><group name="panda_arm"/><group name="hand"/></group>',
             '  <group_state name="ready" group="panda_arm">']
    lines += ['    <joint name="%s" value="%s"/>' % (JOINTS[i][0], fmt(v)) for i, v in enumerate(READY)]
    lines += ['  </group_state>']
    for a, b in adjacent_pairs():
        lines.append('  <disable_collisions link1="%s" link2="%s" reason="Adjacent"/>' % (a, b))
    for a, b in ALWAYS:
        lines.append('  <disable_collisions link1="%s" link2="%s" reason="Default"/>' % (a, b))
    lines.append('</robot>')
    return "\n".join(lines) + "\n"


# ---- forward kinematics and bounding spheres, for scripts/arm_problems.py ------------

def _rpy(r, p, y):
    """URDF's fixed-axis roll, pitch, yaw: Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


def link_poses(q, finger=0.0):
    """(R, p) of every link in panda_link0's frame for the 7 arm angles q."""
    mul, apply = arm_problems.mul, arm_problems.apply
    R, p = ((1, 0, 0), (0, 1, 0), (0, 0, 1)), (0.0, 0.0, 0.0)
    poses = {"panda_link0": (R, p)}
    for i, (_, xyz, rpy, _, _, _) in enumerate(JOINTS, start=1):
        p = apply(R, p, xyz)
        R = mul(mul(R, _rpy(*rpy)), _rpy(0, 0, q[i - 1]))
        poses["panda_link%d" % i] = (R, p)
    p = apply(R, p, (0, 0, FLANGE))
    poses["panda_link8"] = (R, p)
    hand = (mul(R, _rpy(0, 0, HAND_YAW)), p)
    poses["panda_hand"] = hand
    poses["panda_leftfinger"] = (hand[0], apply(hand[0], hand[1], (0, finger, FINGER_Z)))
    poses["panda_rightfinger"] = (hand[0], apply(hand[0], hand[1], (0, -finger, FINGER_Z)))
    return poses


def link_spheres():
    """Per link, spheres (centre, radius) in the link frame that contain it
    (the primitives grown by 2 mm for their circumscribed polytopes)."""
    spheres = {}
    for link, capsules in CAPSULES.items():
        spheres[link] = []
        for centre, direction, radius, length in capsules:
            spheres[link] += arm_problems.capsule_spheres(centre, direction, radius, length, 0.002)
    for link, sign in (("panda_leftfinger", 1), ("panda_rightfinger", -1)):
        spheres[link] = [(c, 0.5 * math.sqrt(sum(s * s for s in size)) + 0.002) for c, size, _ in finger_boxes(sign)]
    return spheres


PANDA = arm_problems.ArmSpec(
    name="panda", group="panda_arm", joints=[j[0] for j in JOINTS], limits=[j[3] for j in JOINTS], ready=READY,
    finger_joint="panda_finger_joint1", finger=0.02, link_poses=link_poses, spheres=link_spheres(),
    disabled=disabled_pairs(), hand=("panda_hand", (0, 0, 0.1034)), scale=SCALE, problems=PROBLEMS, seed=2000)


def panda(files):
    folder = "panda/"
    files[folder + "panda.urdf"] = urdf_text()
    files[folder + "panda.srdf"] = srdf_text()
    arm_problems.problems(files, folder, PANDA)
