#!/usr/bin/python3
"""Generates graspcd's MuJoCo 2.2 scenes (mjcf/) reproducibly: the arm and hand of the paper
(sections 7-11, Figures 11, 12, 16-18) as parallelepipeds and as triangles, the objects, the three
grasp examples, and a pair config beside each scene.

Run with Debian's /usr/bin/python3 (standard library only):
    /usr/bin/python3 mjcf/generator/generate_scenes.py               # writes into mjcf/
    /usr/bin/python3 mjcf/generator/generate_scenes.py --out DIR     # writes into DIR
    /usr/bin/python3 mjcf/generator/generate_scenes.py --check DIR   # exit 1 if DIR differs
The output is deterministic (same bytes on every run). The files in mjcf/ are generated: do not
edit them by hand; change this script and rerun it (the test `scenes_up_to_date` compares them).

Units: metres, radians, kilograms. World: z up, the floor (the table) is the plane z = 0.

Kinematics (both hands, identical): a fixed pedestal at (-0.35, 0, 0); joint `arm1` (hinge about z,
base yaw) at height 0.14; joint `arm2` (hinge about y, shoulder) at the top of link1; link2 0.20 m
along +x to joint `arm3` (hinge about y, elbow); link3 0.15 m along +x to the wrist, which is at
(0, 0, WRIST_Z) when every arm joint is 0. The palm (box 0.09 x 0.08 x 0.02) hangs below the wrist.
Four fingers hang from the palm's lower face along -z: fingers 1-3 on the +x side at y = -0.025, 0,
0.025, finger 4 (the thumb) opposite on the -x side at y = 0. Each finger has three segments on
hinge joints, A proximal (0.040 m), B middle (0.030 m), C distal (0.025 m), each 0.016 x 0.016 in
cross-section. Segment bodies, geoms, joints and actuators share the names finger{1..4}_{A,B,C};
the arm's joints and actuators are arm1, arm2, arm3. Every joint has a <motor> actuator of gear 1
(torque control). Increasing a finger hinge angle closes the finger (curls it toward the palm's
centre); at qpos = 0 the fingers are open: segment A is tilted outward by FINGER_OPEN rad.

The box hand (hand_boxes.xml): every segment a box geom; the object (body `object`, free joint) is
made of three boxes (Figure 11). The triangle hand (hand_triangles.xml, example*.xml): every segment
a closed rounded-box mesh (meshes/finger_{A,B,C}.obj); objects are closed, outward-oriented,
consistently wound meshes: of revolution, a cup (non-convex: its cavity is inside MuJoCo's convex
hull), a can with rounded edges and a bowl (non-convex); and a C-block (the boundary of a union of
5 mm cubes, non-convex: a slot open toward fingers 1-3). Examples: 1 the cup, 2 the can, 3 the
C-block (finger 2 enters its slot, where MuJoCo's convex hull is solid), each as body `object`
centred under the hand, resting on the floor; hand_triangles.xml has the cup under the hand and the
other objects aside (bodies object_can, object_bowl, object_cblock). Concave grasps: the thumb
inside a thin-walled open box pinches its wall against fingers 1-3 (concave_project_thinbox.xml,
mesh thinbox.obj), and the can lifted off the floor of the plastic bowl of ../shared/models, used
by path (concave_bowl_lift.xml: no floor; the can against the bowl is a pair of the config too).

Contact filter: fingers and palm contype 2 conaffinity 0, objects contype 1 conaffinity 3, floor
contype 1 conaffinity 1, arm links 0/0: fingers touch objects but not each other, the palm or the
floor; objects touch each other and the floor.
"""

import argparse
import math
import os
import sys

# ---------------------------------------------------------------------------------------------
# Dimensions (metres, radians)

PEDESTAL_X = -0.35
ARM1_Z = 0.14  # height of joint arm1 (top of the pedestal)
LINK1 = 0.02  # arm1 -> arm2, along z
LINK2 = 0.20  # arm2 -> arm3, along +x
LINK3 = 0.15  # arm3 -> wrist, along +x
PALM_HALF = (0.045, 0.04, 0.01)
PALM_DROP = 0.02  # wrist -> palm top face, along -z
SEG_NAMES = ("A", "B", "C")
SEG_LEN = {"A": 0.040, "B": 0.030, "C": 0.025}
SEG_HALF_W = 0.008  # half cross-section of every segment
SEG_ROUND = 0.004  # rounding radius of the triangle segments' edges
FINGER_OPEN = 0.30  # segment A's outward tilt at qpos = 0
# (x, y, closing direction) of each finger's base on the palm's lower face; direction +1 means the
# tip moves toward -x when the hinge angle increases (fingers on the +x side).
FINGER_BASE = ((0.037, -0.025, 1), (0.037, 0.0, 1), (0.037, 0.025, 1), (-0.037, 0.0, -1))

WRIST_Z = ARM1_Z + LINK1
PALM_CENTRE_Z = WRIST_Z - PALM_DROP - PALM_HALF[2]
PALM_BOTTOM_Z = PALM_CENTRE_Z - PALM_HALF[2]

TIMESTEP = 0.002
SIZE = '<size nconmax="300" njmax="900"/>'

CONTACT_FINGER = 'contype="2" conaffinity="0"'
CONTACT_OBJECT = 'contype="1" conaffinity="3"'
CONTACT_FLOOR = 'contype="1" conaffinity="1"'
CONTACT_NONE = 'contype="0" conaffinity="0"'


def fmt(x):
    """A fixed, platform-independent text form of a coordinate (micrometre resolution)."""
    s = "%.6f" % x
    if s.startswith("-") and float(s) == 0.0:
        s = s[1:]
    return s


def vec(*xs):
    return " ".join(fmt(x) for x in xs)


# ---------------------------------------------------------------------------------------------
# Meshes: vertices welded by their text form, faces as index triples.


class Mesh:
    def __init__(self):
        self.verts = []  # text triples
        self.index = {}
        self.faces = []

    def vert(self, p):
        key = tuple(fmt(c) for c in p)
        i = self.index.get(key)
        if i is None:
            i = len(self.verts)
            self.index[key] = i
            self.verts.append(key)
        return i

    def tri(self, a, b, c):
        if a != b and b != c and a != c:
            self.faces.append((a, b, c))

    def quad(self, a, b, c, d, outward):
        """The quad a b c d as two triangles, counter-clockwise seen from outside when `outward`
        (a b c d turns so), else the other way."""
        if outward:
            self.tri(a, b, c)
            self.tri(a, c, d)
        else:
            self.tri(a, c, b)
            self.tri(a, d, c)

    def point(self, i):
        return tuple(float(c) for c in self.verts[i])

    def volume(self):
        v = 0.0
        for a, b, c in self.faces:
            p, q, r = self.point(a), self.point(b), self.point(c)
            v += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
                  p[2] * (q[0] * r[1] - q[1] * r[0]))
        return v / 6.0

    def flip(self):
        self.faces = [(a, c, b) for a, b, c in self.faces]

    def check_closed(self, name):
        edges = {}
        for f in self.faces:
            for k in range(3):
                e = (f[k], f[(k + 1) % 3])
                edges[e] = edges.get(e, 0) + 1
        for (a, b), n in edges.items():
            if n != 1 or edges.get((b, a), 0) != 1:
                raise RuntimeError("%s: edge %d-%d is not used once per direction" % (name, a, b))
        if self.volume() <= 0:
            raise RuntimeError("%s: not outward-oriented" % name)

    def obj_text(self, comment):
        lines = ["# %s" % line for line in comment]
        lines.append("# %d vertices, %d faces; closed, outward-oriented, counter-clockwise seen "
                     "from outside" % (len(self.verts), len(self.faces)))
        lines.append("o mesh")
        lines.extend("v %s %s %s" % v for v in self.verts)
        lines.extend("f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in self.faces)
        return "\n".join(lines) + "\n"


def axis_stops(half, radius, step):
    """Grid coordinates along one axis of a rounded box: the rounding zone at 15 degree steps of
    the rounded edge, the flat part in pieces of at most `step`."""
    inner = half - radius
    n = max(1, int(math.ceil(2 * inner / step - 1e-9)))
    flat = [-inner + 2 * inner * k / n for k in range(n + 1)]
    zone = [inner + radius * math.tan(math.radians(a)) for a in (15.0, 30.0)]
    return [-half] + [-z for z in reversed(zone)] + flat + zone + [half]


def rounded_box(hx, hy, hz, radius, step):
    """A closed box of half-extents (hx, hy, hz) with edges and corners rounded to `radius`,
    centred at the origin: a grid on the box's faces pushed onto the rounded surface."""
    m = Mesh()
    half = (hx, hy, hz)
    stops = [axis_stops(h, radius, step) for h in half]
    inner = [h - radius for h in half]

    def place(s):
        c = [max(-inner[k], min(inner[k], s[k])) for k in range(3)]
        d = [s[k] - c[k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        return tuple(c[k] + radius * d[k] / n for k in range(3))

    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3  # (u, v, axis) is right-handed
        for sign in (-1.0, 1.0):
            grid = []
            for su in stops[u]:
                row = []
                for sv in stops[v]:
                    s = [0.0, 0.0, 0.0]
                    s[axis], s[u], s[v] = sign * half[axis], su, sv
                    row.append(m.vert(place(s)))
                grid.append(row)
            for i in range(len(stops[u]) - 1):
                for j in range(len(stops[v]) - 1):
                    a, b, c, d = grid[i][j], grid[i + 1][j], grid[i + 1][j + 1], grid[i][j + 1]
                    m.quad(a, b, c, d, sign > 0)  # u x v = +axis: counter-clockwise outside
    return m


def subdivide(profile, step):
    out = [profile[0]]
    for (r0, z0), (r1, z1) in zip(profile, profile[1:]):
        n = max(1, int(math.ceil(math.hypot(r1 - r0, z1 - z0) / step - 1e-9)))
        out.extend((r0 + (r1 - r0) * k / n, z0 + (z1 - z0) * k / n) for k in range(1, n + 1))
    return out


def revolve(profile, segments):
    """A closed surface of revolution about z of a profile (r, z) that starts and ends on the
    axis (r = 0); faces wound outward."""
    m = Mesh()
    rings = []
    for r, z in profile:
        ring = []
        for j in range(segments):
            a = 2.0 * math.pi * j / segments
            ring.append(m.vert((r * math.cos(a), r * math.sin(a), z)) if r > 0 else m.vert(
                (0.0, 0.0, z)))
        rings.append(ring)
    for k in range(len(rings) - 1):
        for j in range(segments):
            jn = (j + 1) % segments
            a, b, c, d = rings[k][j], rings[k][jn], rings[k + 1][jn], rings[k + 1][j]
            m.tri(a, b, c)
            m.tri(a, c, d)
    if m.volume() < 0:
        m.flip()
    return m


def fillet(corner, before, after, radius, n):
    """Points replacing a profile corner by a circular arc of `radius` tangent to both edges."""
    cx, cz = corner
    d0 = (before[0] - cx, before[1] - cz)
    d1 = (after[0] - cx, after[1] - cz)
    l0, l1 = math.hypot(*d0), math.hypot(*d1)
    d0, d1 = (d0[0] / l0, d0[1] / l0), (d1[0] / l1, d1[1] / l1)
    half = math.acos(max(-1.0, min(1.0, d0[0] * d1[0] + d0[1] * d1[1]))) / 2.0
    t = radius / math.tan(half)
    p0 = (cx + d0[0] * t, cz + d0[1] * t)
    p1 = (cx + d1[0] * t, cz + d1[1] * t)
    bis = (d0[0] + d1[0], d0[1] + d1[1])
    lb = math.hypot(*bis)
    centre = (cx + bis[0] / lb * radius / math.sin(half), cz + bis[1] / lb * radius / math.sin(half))
    a0 = math.atan2(p0[1] - centre[1], p0[0] - centre[0])
    a1 = math.atan2(p1[1] - centre[1], p1[0] - centre[0])
    while a1 - a0 > math.pi:
        a1 -= 2 * math.pi
    while a0 - a1 > math.pi:
        a1 += 2 * math.pi
    return [(centre[0] + radius * math.cos(a0 + (a1 - a0) * k / n),
             centre[1] + radius * math.sin(a0 + (a1 - a0) * k / n)) for k in range(n + 1)]


def rounded_profile(points, radii, n=4):
    """The polyline `points` with each interior corner i rounded by radii[i] (0 keeps it)."""
    out = [points[0]]
    for i in range(1, len(points) - 1):
        if radii[i] > 0:
            out.extend(fillet(points[i], points[i - 1], points[i + 1], radii[i], n))
        else:
            out.append(points[i])
    out.append(points[-1])
    return out


# Objects (profiles in metres; z from 0 at the bottom, which rests on the floor)
CUP = dict(radius=0.035, height=0.080, wall=0.005, bottom=0.006)
CAN = dict(radius=0.028, height=0.085, edge=0.006)
BOWL = dict(radius=0.045, height=0.045, wall=0.005, foot=0.022)
REVOLVE_SEGMENTS = 48
PROFILE_STEP = 0.008


def cup_mesh():
    R, H, t, b = CUP["radius"], CUP["height"], CUP["wall"], CUP["bottom"]
    pts = [(0.0, 0.0), (R, 0.0), (R, H), (R - t, H), (R - t, b), (0.0, b)]
    prof = rounded_profile(pts, [0, 0.003, 0.002, 0.002, 0.003, 0])
    return revolve(subdivide(prof, PROFILE_STEP), REVOLVE_SEGMENTS)


def can_mesh():
    R, H, e = CAN["radius"], CAN["height"], CAN["edge"]
    pts = [(0.0, 0.0), (R, 0.0), (R, H), (0.0, H)]
    prof = rounded_profile(pts, [0, e, e, 0])
    return revolve(subdivide(prof, PROFILE_STEP), REVOLVE_SEGMENTS)


def bowl_mesh():
    R, H, t, f = BOWL["radius"], BOWL["height"], BOWL["wall"], BOWL["foot"]
    outer = [(0.0, 0.0), (f, 0.0), (0.8 * R, 0.35 * H), (R, H)]
    inner = [(R - t, H), (0.8 * R - t, 0.42 * H), (f - 0.004, t), (0.0, t)]
    prof = rounded_profile(outer + inner, [0, 0.004, 0.01, 0.002, 0.002, 0.01, 0.004, 0])
    return revolve(subdivide(prof, PROFILE_STEP), REVOLVE_SEGMENTS)


# The C-block: a prism whose cross-section is a C (a back wall on the -x side, two arms along x),
# open toward +x, where finger 2 enters: (x, y, z) extents in cells of VOXEL metres.
VOXEL = 0.005
CBLOCK = dict(size=12, wall=2, height=12)  # 0.06 x 0.06 x 0.06, walls 0.01


def voxel_mesh(cells, size, grid=None):
    """The boundary of a union of cubes (integer cells, edge `size`), as a closed outward mesh:
    every exposed cube face becomes two triangles. Cells must not touch along an edge only.
    grid: per axis, the coordinates of the cell boundaries (cell k spans grid[axis][k] ..
    grid[axis][k + 1]) instead of multiples of `size`: a union of boxes of a rectilinear grid."""
    m = Mesh()
    for c in sorted(cells):
        for axis in range(3):
            for sign in (-1, 1):
                n = list(c)
                n[axis] += sign
                if tuple(n) in cells:
                    continue
                u, v = (axis + 1) % 3, (axis + 2) % 3  # (u, v, axis) right-handed
                base = list(c)
                if sign > 0:
                    base[axis] += 1
                quad = []
                for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    q = list(base)
                    q[u] += du
                    q[v] += dv
                    if grid is None:
                        quad.append(m.vert(tuple(k * size for k in q)))
                    else:
                        quad.append(m.vert(tuple(grid[a][k] for a, k in enumerate(q))))
                a, b, cc, d = quad
                m.quad(a, b, cc, d, sign > 0)
    return m


def cblock_mesh():
    n, w, h = CBLOCK["size"], CBLOCK["wall"], CBLOCK["height"]
    cells = set()
    for i in range(n):
        for j in range(n):
            if i < w or j < w or j >= n - w:  # back wall (x low) or one of the two arms
                for k in range(h):
                    cells.add((i - n // 2, j - n // 2, k))
    return voxel_mesh(cells, VOXEL)


# The thin-walled box: an open box (no lid), outer extents (x, y, z) in metres, walls and bottom
# `wall` thick. Its cavity is open upward; its hull is solid. Built as the 3 x 3 x 2 grid of boxes
# whose centre top box (the cavity) is left out: large faces, few triangles.
THINBOX = dict(size=(0.09, 0.07, 0.095), wall=0.005)


def thinbox_mesh():
    (sx, sy, sz), w = THINBOX["size"], THINBOX["wall"]
    grid = ((-sx / 2, -sx / 2 + w, sx / 2 - w, sx / 2), (-sy / 2, -sy / 2 + w, sy / 2 - w, sy / 2),
            (0.0, w, sz))
    cells = {(i, j, k) for i in range(3) for j in range(3) for k in range(2)} - {(1, 1, 1)}
    return voxel_mesh(cells, None, grid)


def thinbox_desc():
    (sx, sy, sz), w = THINBOX["size"], THINBOX["wall"]
    return ("thin-walled box: %.3f x %.3f x %.3f, open at the top, walls and bottom %.3f, centred "
            "on x = y = 0; non-convex (open cavity)" % (sx, sy, sz, w))


OBJECT_MESHES = (
    ("cup", cup_mesh, "cup: outer radius %.3f, height %.3f, wall %.3f, bottom %.3f; non-convex "
     "(open cavity)" % (CUP["radius"], CUP["height"], CUP["wall"], CUP["bottom"])),
    ("can", can_mesh, "can: radius %.3f, height %.3f, edges rounded %.3f; convex" %
     (CAN["radius"], CAN["height"], CAN["edge"])),
    ("bowl", bowl_mesh, "bowl: rim radius %.3f, height %.3f, wall %.3f, foot radius %.3f; "
     "non-convex (open cavity)" % (BOWL["radius"], BOWL["height"], BOWL["wall"], BOWL["foot"])),
    ("cblock", cblock_mesh, "C-block: %.3f x %.3f x %.3f prism with a C cross-section, walls %.3f, "
     "the slot (|y| < %.3f, x > %.3f) open toward +x; non-convex" %
     (CBLOCK["size"] * VOXEL, CBLOCK["size"] * VOXEL, CBLOCK["height"] * VOXEL,
      CBLOCK["wall"] * VOXEL, (CBLOCK["size"] / 2 - CBLOCK["wall"]) * VOXEL,
      (CBLOCK["wall"] - CBLOCK["size"] / 2) * VOXEL)),
    ("thinbox", thinbox_mesh, thinbox_desc()),
)


def segment_mesh(seg):
    return rounded_box(SEG_HALF_W, SEG_HALF_W, SEG_LEN[seg] / 2.0, SEG_ROUND, 0.004)


# ---------------------------------------------------------------------------------------------
# MJCF

GENERATED = ("Generated by mjcf/generator/generate_scenes.py: do not edit by hand; change the "
             "script and rerun it.")


def header(title, lines):
    out = ['<mujoco model="%s">' % title, "  <!--", "    " + GENERATED]
    out.extend(("    " + x).rstrip() for x in lines)
    out.append("  -->")
    return out


def geometry_comment(kind, floor=True):
    seg = ", ".join("%s %.3f" % (s, SEG_LEN[s]) for s in SEG_NAMES)
    lines = [
        "",
        "Units: metres, radians. z up; %s" % ("the floor (table) is the plane z = 0." if floor else
                                             "no floor (the object's support is named below)."),
        "Arm: pedestal at (%.2f, 0, 0); arm1 (hinge z) at height %.3f; arm2 (hinge y) %.3f above;"
        % (PEDESTAL_X, ARM1_Z, LINK1),
        "  link2 %.3f along +x to arm3 (hinge y); link3 %.3f along +x to the wrist at (0, 0, %.3f)."
        % (LINK2, LINK3, WRIST_Z),
        "Palm: box half-extents %s, centre at (0, 0, %.3f), lower face at z = %.3f."
        % (vec(*PALM_HALF), PALM_CENTRE_Z, PALM_BOTTOM_Z),
        "Fingers 1-3 at x = %.3f, y = -0.025 / 0 / 0.025; finger 4 (thumb) at x = %.3f, y = 0;"
        % (FINGER_BASE[0][0], FINGER_BASE[3][0]),
        "  segments %s long, %.3f x %.3f cross-section (%s)." %
        (seg, 2 * SEG_HALF_W, 2 * SEG_HALF_W, kind),
        "Initial pose (qpos = 0): arm straight, hand above the object, fingers open (segment A",
        "  tilted %.2f rad outward). Increasing a finger hinge angle closes the finger; the grasp"
        % FINGER_OPEN,
        "  closes in steps of 0.003 rad. Actuators: <motor> gear 1 per joint, named after it.",
        "Contacts: fingers and palm contype 2 / conaffinity 0, objects 1 / 3, floor 1 / 1, arm 0 / 0.",
    ]
    return lines


def common_head(model, extra_comment, meshes, meshdir="meshes", option_extra=""):
    out = header(model, extra_comment)
    out.append('  <compiler angle="radian" meshdir="%s" autolimits="true"/>' % meshdir)
    out.append('  <option timestep="%s" gravity="0 0 -9.81"%s/>' % (TIMESTEP, option_extra))
    out.append("  " + SIZE)
    out.append("  <default>")
    out.append('    <joint damping="0.05" armature="0.001"/>')
    out.append('    <geom friction="1 0.005 0.0001"/>')
    out.append("  </default>")
    if meshes:
        out.append("  <asset>")
        for name in meshes:
            out.append('    <mesh name="%s" file="%s.obj"/>' % (name, name))
        out.append("  </asset>")
    return out


def arm_and_hand(kind, floor=True):
    """The worldbody lines of the arm and hand; kind is 'box' or 'mesh'; floor=False leaves the
    floor out (a scene whose object rests on another support)."""
    o = []
    if floor:
        o.append('    <geom name="floor" type="plane" size="1 1 0.05" %s/>' % CONTACT_FLOOR)
    o.append('    <body name="pedestal" pos="%s">' % vec(PEDESTAL_X, 0, 0))
    o.append('      <geom name="pedestal" type="cylinder" size="0.04 %s" pos="%s" %s/>' %
             (fmt(ARM1_Z / 2), vec(0, 0, ARM1_Z / 2), CONTACT_NONE))
    o.append('      <body name="link1" pos="%s">' % vec(0, 0, ARM1_Z))
    o.append('        <joint name="arm1" type="hinge" axis="0 0 1" range="-3.14 3.14" '
             'damping="1"/>')
    o.append('        <geom name="link1" type="cylinder" size="0.03 %s" pos="%s" %s/>' %
             (fmt(LINK1 / 2), vec(0, 0, LINK1 / 2), CONTACT_NONE))
    o.append('        <body name="link2" pos="%s">' % vec(0, 0, LINK1))
    o.append('          <joint name="arm2" type="hinge" axis="0 1 0" range="-1.57 1.57" '
             'damping="1"/>')
    o.append('          <geom name="link2" type="capsule" size="0.02" fromto="0 0 0 %s 0 0" %s/>' %
             (fmt(LINK2), CONTACT_NONE))
    o.append('          <body name="link3" pos="%s">' % vec(LINK2, 0, 0))
    o.append('            <joint name="arm3" type="hinge" axis="0 1 0" range="-2 2" damping="1"/>')
    o.append('            <geom name="link3" type="capsule" size="0.018" fromto="0 0 0 %s 0 0" '
             '%s/>' % (fmt(LINK3), CONTACT_NONE))
    o.append('            <body name="palm" pos="%s">' % vec(LINK3, 0, -PALM_DROP - PALM_HALF[2]))
    o.append('              <geom name="wrist" type="cylinder" size="0.015 %s" pos="%s" %s/>' %
             (fmt(PALM_DROP / 2), vec(0, 0, PALM_HALF[2] + PALM_DROP / 2), CONTACT_NONE))
    o.append('              <geom name="palm" type="box" size="%s" %s/>' %
             (vec(*PALM_HALF), CONTACT_FINGER))
    indent = "              "
    for i, (fx, fy, direction) in enumerate(FINGER_BASE, start=1):
        axis = "0 1 0" if direction > 0 else "0 -1 0"
        pos = vec(fx, fy, -PALM_HALF[2])
        ind = indent
        closers = []
        for k, seg in enumerate(SEG_NAMES):
            name = "finger%d_%s" % (i, seg)
            if k == 0:
                # Tilted outward: rotation about y by -open (+x side) or +open (thumb side).
                o.append('%s<body name="%s" pos="%s" euler="%s">' %
                         (ind, name, pos, vec(0, -direction * FINGER_OPEN, 0)))
            else:
                o.append('%s<body name="%s" pos="%s">' %
                         (ind, name, vec(0, 0, -SEG_LEN[SEG_NAMES[k - 1]])))
            o.append('%s  <joint name="%s" type="hinge" axis="%s" range="-0.3 1.6"/>' %
                     (ind, name, axis))
            if kind == "box":
                o.append('%s  <geom name="%s" type="box" size="%s" pos="%s" %s/>' %
                         (ind, name, vec(SEG_HALF_W, SEG_HALF_W, SEG_LEN[seg] / 2),
                          vec(0, 0, -SEG_LEN[seg] / 2), CONTACT_FINGER))
            else:
                o.append('%s  <geom name="%s" type="mesh" mesh="finger_%s" pos="%s" %s/>' %
                         (ind, name, seg, vec(0, 0, -SEG_LEN[seg] / 2), CONTACT_FINGER))
            closers.append(ind + "</body>")
            ind += "  "
        o.extend(reversed(closers))
    o.append("            </body>")
    o.append("          </body>")
    o.append("        </body>")
    o.append("      </body>")
    o.append("    </body>")
    return o


def actuators():
    o = ["  <actuator>"]
    for j in ("arm1", "arm2", "arm3"):
        o.append('    <motor name="%s" joint="%s" gear="1" ctrlrange="-200 200"/>' % (j, j))
    for i in range(1, 5):
        for seg in SEG_NAMES:
            n = "finger%d_%s" % (i, seg)
            o.append('    <motor name="%s" joint="%s" gear="1" ctrlrange="-20 20"/>' % (n, n))
    o.append("  </actuator>")
    return o


# The box object of Figure 11: (geom name, half-extents, centre above the floor)
BOX_OBJECT = (
    ("object_base", (0.030, 0.030, 0.010), (0.0, 0.0, 0.010)),
    ("object_column", (0.022, 0.022, 0.025), (0.0, 0.0, 0.045)),
    ("object_cap", (0.032, 0.018, 0.008), (0.0, 0.0, 0.078)),
)


def box_scene():
    dims = ["", "Object (body `object`, free joint) made of boxes (Figure 11), centred at x = y = 0 "
            "on the floor:"]
    for name, h, c in BOX_OBJECT:
        dims.append("  %s half-extents %s, centre z %.3f" % (name, vec(*h), c[2]))
    o = common_head("graspcd hand_boxes", geometry_comment("boxes") + dims, [])
    o.append("  <worldbody>")
    o.extend(arm_and_hand("box"))
    o.append('    <body name="object" pos="0 0 0">')
    o.append("      <freejoint/>")
    for name, h, c in BOX_OBJECT:
        o.append('      <geom name="%s" type="box" size="%s" pos="%s" %s/>' %
                 (name, vec(*h), vec(*c), CONTACT_OBJECT))
    o.append("    </body>")
    o.append("  </worldbody>")
    o.extend(actuators())
    o.append("</mujoco>")
    return "\n".join(o) + "\n"


def object_lines(body, mesh, x, y):
    mass = ' mass="%s"' % fmt(OBJECT_MASS[mesh]) if mesh in OBJECT_MASS else ""
    return [
        '    <body name="%s" pos="%s">' % (body, vec(x, y, 0)),
        "      <freejoint/>",
        '      <geom name="%s" type="mesh" mesh="%s"%s %s/>' % (body, mesh, mass, CONTACT_OBJECT),
        "    </body>",
    ]


def triangle_scene(model, objects, extra, meshdir="meshes", option_extra=""):
    """objects: (body name, mesh, x, y) resting on the floor; meshdir and option_extra (attributes
    added to <option>) for the scenes of mjcf/hard/."""
    meshes = ["finger_%s" % s for s in SEG_NAMES] + sorted({m for _, m, _, _ in objects})
    lines = geometry_comment("closed rounded-box meshes, edge radius %.3f" % SEG_ROUND) + extra
    lines.append("Objects (closed meshes, bottom on the floor):")
    for body, mesh, x, y in objects:
        desc = [d for n, _, d in OBJECT_MESHES if n == mesh][0]
        lines.append("  body %s at (%s): %s" % (body, vec(x, y), desc))
    o = common_head(model, lines, meshes, meshdir, option_extra)
    o.append("  <worldbody>")
    o.extend(arm_and_hand("mesh"))
    for body, mesh, x, y in objects:
        o.extend(object_lines(body, mesh, x, y))
    o.append("  </worldbody>")
    o.extend(actuators())
    o.append("</mujoco>")
    return "\n".join(o) + "\n"


# Object masses set in the scenes (kg); the others take MuJoCo's density of water. The thin-walled
# box is light plastic: its grip is on one wall, 4 cm from its centre of mass.
OBJECT_MASS = {"thinbox": 0.035}

# The thin-walled box's body x: its +x wall centred under the palm (x = 0).
THINBOX_X = -(THINBOX["size"][0] / 2 - THINBOX["wall"] / 2)

# The bowl-lift scene: the can stands in a real bowl (../shared/models, used by path) that is the
# scene's only support, sunk so that the open fingers clear its wall.
BOWL_LIFT_MESH = "../../../shared/models/objects/prl_assets/plastic_bowl_visual.obj"
BOWL_LIFT_Z = -0.030  # the bowl's bottom (no floor: the bowl is the support)
BOWL_LIFT_CAN_Z = 0.0105  # the can's bottom above the bowl's bottom (its inner floor is a cone)
CONTACT_BOWL = 'contype="4" conaffinity="4"'
CONTACT_IN_BOWL = 'contype="6" conaffinity="6"'
BOWL_LIFT_PAIRS = ('{\n  "method": "sat",\n  "pairs": [\n'
                   '    {"a": "geom:finger*", "b": "body:object"},\n'
                   '    {"a": "body:object", "b": "geom:bowl"}\n  ]\n}\n')


def bowl_lift_scene():
    lines = geometry_comment("closed rounded-box meshes, edge radius %.3f" % SEG_ROUND,
                             floor=False) + [
        "",
        "Concave support: the can (body object) stands inside the plastic bowl of ../shared/models",
        "  (objects/prl_assets/plastic_bowl_visual.obj, 17.2 cm wide, 7.6 cm tall, 720 faces; used",
        "  by path, never copied), a fixed geom of the world. There is no floor: the bowl is the",
        "  support, its bottom at z = %.3f so that the open fingers clear its wall; the can's"
        % BOWL_LIFT_Z,
        "  bottom %.4f above it (the bowl's inner floor is a shallow cone). The fingers close on"
        % BOWL_LIFT_CAN_Z,
        "  the can and lift it off the bowl's floor. Contact filter: the bowl 4 / 4 and the can",
        "  6 / 6: the can touches the bowl and the fingers, the fingers and palm never the bowl.",
        "  The pair config serves the can against the bowl too (exact contacts): MuJoCo's convex",
        "  hull of the bowl is solid where the can stands.",
        "Object: %s." % [d for n, _, d in OBJECT_MESHES if n == "can"][0],
    ]
    o = common_head("graspcd concave_bowl_lift", lines,
                    ["finger_%s" % x for x in SEG_NAMES] + ["can"])
    o.insert(o.index("  </asset>"), '    <mesh name="bowl" file="%s"/>' % BOWL_LIFT_MESH)
    o.append("  <worldbody>")
    o.extend(arm_and_hand("mesh", floor=False))
    o.append('    <geom name="bowl" type="mesh" mesh="bowl" pos="%s" %s/>' %
             (vec(0, 0, BOWL_LIFT_Z), CONTACT_BOWL))
    o.append('    <body name="object" pos="%s">' % vec(0, 0, BOWL_LIFT_Z + BOWL_LIFT_CAN_Z))
    o.append("      <freejoint/>")
    o.append('      <geom name="object" type="mesh" mesh="can" %s/>' % CONTACT_IN_BOWL)
    o.append("    </body>")
    o.append("  </worldbody>")
    o.extend(actuators())
    o.append("</mujoco>")
    return "\n".join(o) + "\n"


def pairs_json(b_pattern):
    return ('{\n  "method": "sat",\n  "pairs": [\n    {"a": "geom:finger*", "b": "%s"}\n  ]\n}\n' %
            b_pattern)


# Iterations of MuJoCo's noslip solver in the hold scenes (mjcf/hard/hold_*.xml): a
# post-processing pass over the friction rows that removes the slip MuJoCo's soft constraints
# allow under a sustained tangential load. More: slower steps, no less slip once converged; fewer:
# some creep remains.
HOLD_NOSLIP_ITERATIONS = 10

EXAMPLES = (
    ("example1", "cup", "Example 1: the cup (non-convex) centred under the hand; the fingers close "
     "around its wall."),
    ("example2", "can", "Example 2: the can (convex) centred under the hand."),
    ("example3", "cblock", "Example 3: the C-block (non-convex) centred under the hand, its slot "
     "facing fingers 1-3: finger 2 enters the slot, inside MuJoCo's convex hull."),
)


def generate():
    """Every generated file: relative path -> text."""
    files = {}
    for seg in SEG_NAMES:
        m = segment_mesh(seg)
        name = "finger_%s" % seg
        m.check_closed(name)
        files["meshes/%s.obj" % name] = m.obj_text([
            GENERATED,
            "Finger segment %s: rounded box %.3f x %.3f x %.3f (edge radius %.3f), centred at the "
            "origin, long axis z." % (seg, 2 * SEG_HALF_W, 2 * SEG_HALF_W, SEG_LEN[seg],
                                      SEG_ROUND)])
    for name, make, desc in OBJECT_MESHES:
        m = make()
        m.check_closed(name)
        files["meshes/%s.obj" % name] = m.obj_text(
            [GENERATED, desc + "; axis z, bottom at z = 0."])
    files["hand_boxes.xml"] = box_scene()
    files["hand_boxes.pairs.json"] = pairs_json("body:object")
    files["hand_triangles.xml"] = triangle_scene(
        "graspcd hand_triangles",
        (("object", "cup", 0.0, 0.0), ("object_can", "can", 0.0, 0.25),
         ("object_bowl", "bowl", 0.0, -0.25), ("object_cblock", "cblock", 0.25, 0.25)),
        ["", "The cup is the object under the hand; the can, the bowl and the C-block stand aside."])
    files["hand_triangles.pairs.json"] = pairs_json("body:object*")
    for name, mesh, desc in EXAMPLES:
        files[name + ".xml"] = triangle_scene("graspcd " + name, (("object", mesh, 0.0, 0.0),),
                                              ["", desc])
        files[name + ".pairs.json"] = pairs_json("body:object")
    # The hold scenes of the hard-scene tests (tests/scenes/hard_scenes_test.cpp): examples 1 and 3
    # with MuJoCo's noslip solver, which removes the slow slip (creep) of its soft friction under a
    # sustained load, so that an object can rest in the hand for seconds (docs/design.md,
    # "Holding longer").
    for name, mesh, desc in EXAMPLES:
        if name == "example2":
            continue
        files["hard/hold_%s.xml" % name] = triangle_scene(
            "graspcd hold_" + name, (("object", mesh, 0.0, 0.0),),
            ["", desc, "Hold scene: %s.xml with noslip_iterations=\"%d\" (MuJoCo's noslip solver)."
             % (name, HOLD_NOSLIP_ITERATIONS)],
            meshdir="../meshes", option_extra=' noslip_iterations="%d"' % HOLD_NOSLIP_ITERATIONS)
        files["hard/hold_%s.pairs.json" % name] = pairs_json("body:object")
    # Concave grasps (tests/scenes/concave_hands_test.cpp): the thumb inside the thin-walled box
    # pinches its wall against fingers 1-3; MuJoCo's hull of the box holds the thumb.
    files["concave_project_thinbox.xml"] = triangle_scene(
        "graspcd concave_project_thinbox", (("object", "thinbox", THINBOX_X, 0.0),),
        ["", "Concave grasp: the thin-walled box stands with its +x wall (x = %.4f .. %.4f) between"
         % (THINBOX_X + THINBOX["size"][0] / 2 - THINBOX["wall"],
            THINBOX_X + THINBOX["size"][0] / 2),
         "  the thumb, which hangs inside its cavity, and fingers 1-3 outside: the thumb presses the",
         "  wall's inner face, the fingers its outer face, and the pinch lifts the box. MuJoCo's",
         "  convex hull of the box is solid where the thumb hangs. Its mass is set (%.0f g, light"
         % (1000 * OBJECT_MASS["thinbox"]),
         "  plastic): the grip is on one wall, 4 cm from its centre of mass, and the box tilts."])
    files["concave_project_thinbox.pairs.json"] = pairs_json("body:object")
    files["concave_bowl_lift.xml"] = bowl_lift_scene()
    files["concave_bowl_lift.pairs.json"] = BOWL_LIFT_PAIRS
    return files


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.normpath(os.path.join(here, "..", "..", "mjcf"))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    g = p.add_mutually_exclusive_group()
    g.add_argument("--out", default=default_out, help="folder to write (default: mjcf/)")
    g.add_argument("--check", metavar="DIR", help="compare with DIR; exit 1 on any difference")
    args = p.parse_args(argv)
    files = generate()
    if args.check:
        bad = 0
        for rel in sorted(files):
            path = os.path.join(args.check, rel)
            try:
                with open(path, "rb") as f:
                    same = f.read() == files[rel].encode("utf-8")
            except OSError:
                print("missing: %s" % path)
                bad += 1
                continue
            if not same:
                print("differs: %s (rerun mjcf/generator/generate_scenes.py)" % path)
                bad += 1
        if bad:
            return 1
        print("%d generated files up to date in %s" % (len(files), args.check))
        return 0
    for rel in sorted(files):
        path = os.path.join(args.out, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(files[rel].encode("utf-8"))
    print("wrote %d files into %s" % (len(files), args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
