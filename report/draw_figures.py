#!/usr/bin/python3
"""Pictures of the grasps and the trees, drawn from the trajectory files that
`graspcd study` writes into OUT/trajectories/ (format: src/graspcd/study/trajectory.h).

    /usr/bin/python3 report/draw_figures.py TRAJECTORY [TRAJECTORY ...] FIGURES_DIR

Each TRAJECTORY is a trajectory file (`graspcd trajectory SCENE --out FILE.json`, any name) or a
folder whose *.json files are all trajectories. Writes into FIGURES_DIR what the files hold:
  fig18_<name>.png         each grasp at its first contact and at its last closing grasp step (the
                           grip), as the paper's Figure 18 (every trajectory but a box hand's); at
                           its start and its grip when the first contact is the grip (a gripper's
                           pads touch together). Gravity points down (the file's "gravity"), and
                           the frame is the object and the hand geoms touching it (frame_box)
  fig17_obb_depths.png     the first finger segment with OBB levels: its boxes at tree depths 0 to
                           3 (Figure 17), on one scale
  contacts_native.png      where graspcd's contacts and MuJoCo's native convex-hull ones differ
                           most: the trajectory and grasp step with the most of our contacts far
                           (> 5 mm) from every native one (a finger in a cavity or slot)
  fig12_box_hand.png       a box hand (every segment a box) with its segments labelled A, B, C
                           (Figure 12)
Each input that is missing or not a trajectory file is a one-line error naming it, exit code 2.
make_report.py calls insert_section(), which draws them when OUT/trajectories exists and adds their
section to REPORT.md.
"""
import json
import sys
from pathlib import Path

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

COLORS = {"segment": "#c8a878", "object": "#7090c0", "hand": "#999999", "support": "#d8d8d8"}
TOUCHING = "#e03030"
BOX_EDGES = [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5),
             (2, 6), (3, 7)]
# The grasp pictures' frame: the object and the hand geoms touching it, reaching at most this many
# of the object's largest extents beyond it on each side, plus a margin of this share of the frame.
FRAME_REACH = 1.0
FRAME_MARGIN = 0.08


class InputError(Exception):
    pass


def load(path):
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: cannot read the trajectory ({str(e).splitlines()[0]})")
    if data.get("schema") != 1 or not data.get("steps") or "geoms" not in data:
        raise InputError(f"{path}: not a trajectory file (schema 1 with steps and geoms expected)")
    return data


def pose(traj, step, g):
    s = traj["steps"][step]
    return np.array(s["rot"][9 * g:9 * g + 9]).reshape(3, 3), np.array(s["pos"][3 * g:3 * g + 3])


def box_corners(center, axes, half):
    """The 8 corners in the order of sign bits, x fastest (core/obb.h)."""
    out = []
    for k in range(8):
        u = np.array([1 if k & 1 else -1, 1 if k & 2 else -1, 1 if k & 4 else -1], float)
        out.append(center + axes @ (np.asarray(half) * u))
    return np.array(out)


def box_faces(corners):
    quads = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [corners[list(q)] for q in quads]


def grid_triangles(points):
    """The triangles of a (rows, columns, 3) grid of points, the columns closing around."""
    rows, cols = points.shape[:2]
    tris = []
    for i in range(rows - 1):
        for j in range(cols):
            a, b = points[i, j], points[i, (j + 1) % cols]
            c, d = points[i + 1, j], points[i + 1, (j + 1) % cols]
            tris += [(a, b, d), (a, d, c)]
    return np.array(tris)


def primitive_triangles(geom, sides=16):
    """A sphere, capsule, cylinder or ellipsoid as triangles in its geom frame (MuJoCo's sizes:
    radius and half-length along z; an ellipsoid's three radii)."""
    size = geom["size"]
    turn = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    ring = np.stack([np.cos(turn), np.sin(turn), np.zeros(sides)], axis=1)
    if geom["type"] == "cylinder":
        r, h = size[0], size[1]
        side = np.stack([r * ring + [0, 0, -h], r * ring + [0, 0, h]])
        caps = [np.stack([np.tile([0.0, 0.0, z], (sides, 1)), r * ring + [0, 0, z],
                          np.roll(r * ring, -1, axis=0) + [0, 0, z]], axis=1) for z in (-h, h)]
        return np.concatenate([grid_triangles(side)] + caps)
    # Latitude rings from the bottom pole to the top; a capsule's halves apart by its length.
    lat = np.linspace(-np.pi / 2, np.pi / 2, sides // 2 + 1)
    radii = np.array([size[0]] * 3) if geom["type"] != "ellipsoid" else np.array(size[:3])
    rows = []
    for a in lat:
        p = np.stack([np.cos(a) * ring[:, 0], np.cos(a) * ring[:, 1],
                      np.full(sides, np.sin(a))], axis=1) * radii
        if geom["type"] == "capsule":
            shift = size[1] if a > 0 else -size[1] if a < 0 else 0.0
            if a == 0:  # the cylinder between the halves: the equator twice
                rows += [p + [0, 0, -size[1]], p + [0, 0, size[1]]]
                continue
            p = p + [0, 0, shift]
        rows.append(p)
    return grid_triangles(np.array(rows))


def geom_polygons(traj, step, g):
    """The triangles (or box faces) of geom g at `step`, in world coordinates."""
    geom = traj["geoms"][g]
    rot, pos = pose(traj, step, g)
    if geom["type"] == "mesh":
        mesh = traj["meshes"][geom["mesh"]]
        v = np.array(mesh["vertices"]).reshape(-1, 3) @ rot.T + pos
        return v[np.array(mesh["faces"]).reshape(-1, 3)]
    if geom["type"] == "box":
        return np.array(box_faces(box_corners(pos, rot, geom["size"])))
    return primitive_triangles(geom) @ rot.T + pos


ALL_TYPES = ("mesh", "box", "capsule", "cylinder", "sphere", "ellipsoid")


def drawn(geom, types=ALL_TYPES):
    """Whether a geom is drawn: one of `types`, and colliding (a hand's visual meshes double its
    collision geoms; in files before the "collides" key, every geom)."""
    return geom["type"] in types and geom.get("collides", True)


LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def shaded(polys, color, alpha):
    """Per-face RGBA: `color` lit by a fixed light from above (|cos| of the face normal: the
    meshes' faces may face either way once drawn from both sides)."""
    polys = np.asarray(polys)
    n = np.cross(polys[:, 1] - polys[:, 0], polys[:, 2] - polys[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    light = 0.45 + 0.55 * np.abs(n @ LIGHT)
    rgb = np.array(matplotlib.colors.to_rgb(color))
    rgba = np.empty((len(polys), 4))
    rgba[:, :3] = np.clip(light[:, None] * rgb, 0, 1)
    rgba[:, 3] = alpha
    return rgba


def axis_name(row):
    """A drawn axis by the world axis it is ("x", "-y"), or None when it is none of them."""
    k = int(np.argmax(np.abs(row)))
    if abs(abs(row[k]) - 1) > 1e-9:
        return None
    return ("" if row[k] > 0 else "\u2212") + "xyz"[k]


def drawn_frame(traj):
    """The rotation Q (rows: the drawn x, y, z in world coordinates) that puts gravity down, and
    the axes' labels. Drawn z is against gravity (the trajectory's "gravity", MuJoCo's default
    -z in files without it); gravity along a world axis keeps the other axes as world axes, named
    with their sign ("x", "-y", "-z" for gravity along +z)."""
    g = np.array(traj.get("gravity", [0, 0, -9.81]), float)
    up = -g / np.linalg.norm(g) if np.linalg.norm(g) > 0 else np.array([0.0, 0.0, 1.0])
    k = int(np.argmax(np.abs(up)))
    if abs(abs(up[k]) - 1) <= 1e-9:
        up = np.sign(up[k]) * np.eye(3)[k]
        across = np.eye(3)[0 if k != 0 else 1]
    else:
        across = np.eye(3)[0] if abs(up[0]) < 0.9 else np.eye(3)[1]
        across = across - (across @ up) * up
        across /= np.linalg.norm(across)
    q = np.array([across, np.cross(up, across), up])
    names = [axis_name(r) for r in q]
    labels = [names[i] if names[i] else ("across 1", "across 2", "up")[i] for i in range(3)]
    return q, labels


def object_geoms(traj):
    return {g for g, geom in enumerate(traj["geoms"]) if geom["role"] == "object"}


def touching_geoms(traj, step):
    """The hand geoms (finger segments and other hand parts, not the support) that touch the
    object at `step`, by our contacts."""
    objects = object_geoms(traj)
    out = set()
    for c in traj["steps"][step]["contacts"]:
        a, b = c["geoms"]
        for mine, other in ((a, b), (b, a)):
            if mine in objects and traj["geoms"][other]["role"] in ("segment", "hand"):
                out.add(other)
    return out


def frame_box(traj, steps, q):
    """The drawn box (lo, hi, in the drawn frame of q) of a grasp picture over `steps`: the object
    and the hand geoms touching it at any of them, each at every step (the fingers that will touch
    also before they do), these reaching at most FRAME_REACH of the object's largest extent beyond
    it, centred on the object across gravity (a gripper's other pad shows as far out as the one
    touching), with a margin of FRAME_MARGIN of the box."""
    objects = object_geoms(traj)
    obj = np.concatenate([geom_polygons(traj, s, g).reshape(-1, 3) for s in steps
                          for g in objects]) @ q.T
    olo, ohi = obj.min(axis=0), obj.max(axis=0)
    reach = FRAME_REACH * (ohi - olo).max()
    touching = set().union(*(touching_geoms(traj, s) for s in steps))
    pts = np.concatenate([obj] + [geom_polygons(traj, s, g).reshape(-1, 3) @ q.T for s in steps
                                  for g in touching])
    lo = np.maximum(pts.min(axis=0), olo - reach)
    hi = np.minimum(pts.max(axis=0), ohi + reach)
    centre = 0.5 * (olo + ohi)
    half = np.maximum(centre - lo, hi - centre)
    lo[:2], hi[:2] = centre[:2] - half[:2], centre[:2] + half[:2]
    margin = FRAME_MARGIN * (hi - lo).max()
    return lo - margin, hi + margin


def clip_polygon(poly, lo, hi):
    """Sutherland-Hodgman: the part of a convex polygon (K, 3) inside the box [lo, hi]."""
    for axis in range(3):
        for bound, inside in ((lo[axis], lambda v: v >= lo[axis]), (hi[axis],
                                                                    lambda v: v <= hi[axis])):
            out = []
            for i in range(len(poly)):
                a, b = poly[i - 1], poly[i]
                ia, ib = inside(a[axis]), inside(b[axis])
                if ia != ib:
                    t = (bound - a[axis]) / (b[axis] - a[axis])
                    out.append(a + t * (b - a))
                if ib:
                    out.append(b)
            poly = np.array(out)
            if len(poly) < 3:
                return None
    return poly


def clipped(polys, colors, lo, hi):
    """The polygons (N, K, 3) cut to the box [lo, hi], with their colours: those wholly outside
    dropped, those across its faces cut (matplotlib's 3D axes do not clip)."""
    below = (polys < lo).all(axis=1).any(axis=1)
    above = (polys > hi).all(axis=1).any(axis=1)
    inside = ((polys >= lo) & (polys <= hi)).all(axis=(1, 2))
    out = list(polys[inside])
    rgba = list(colors[inside])
    for i in np.flatnonzero(~inside & ~below & ~above):
        p = clip_polygon(polys[i], lo, hi)
        if p is not None:
            out.append(p)
            rgba.append(colors[i])
    return out, rgba


def draw_scene(ax, traj, step, q, box=None, roles=("segment", "object", "hand", "support"),
               alpha=None, types=ALL_TYPES):
    """Draws the geoms of `roles` and `types` at `step` in the drawn frame of q, cut to `box`
    (lo, hi) when given; returns every drawn point (for the limits). Hand geoms touching the
    object are red."""
    touched = touching_geoms(traj, step)
    points = []
    for g, geom in enumerate(traj["geoms"]):
        if not drawn(geom, types) or geom["role"] not in roles:
            continue
        polys = geom_polygons(traj, step, g) @ q.T
        color = TOUCHING if g in touched else COLORS[geom["role"]]
        a = alpha if alpha is not None else {"object": 0.45, "support": 0.3}.get(geom["role"], 1.0)
        colors = shaded(polys, color, a)
        if box is not None:
            polys, colors = clipped(polys, colors, *box)
            if not polys:
                continue
        ax.add_collection3d(Poly3DCollection(polys, facecolors=colors, edgecolor="none"))
        points.append(np.concatenate(polys).reshape(-1, 3))
    return np.concatenate(points) if points else np.zeros((0, 3))


def first_contact_step(traj):
    steps = [s for s in traj["first_contact"] if s > 0]
    return (min(steps) if steps else 1) - 1  # 0-based


def shown_steps(traj):
    """The two grasp steps of a grasp picture (0-based) and their names: the first contact and
    the grip (the last closing step); the start and the grip when the first contact is the grip
    (a gripper whose pads touch together) or when nothing touched. One step: that one."""
    last = len(traj["steps"]) - 1
    touched = any(s > 0 for s in traj["first_contact"])
    first = first_contact_step(traj)
    if last == 0:
        return [(0, "the only closing step")]
    if touched and first < last:
        return [(first, "first contact"), (last, "grip (last closing step)")]
    return [(0, "start"), (last, "first contact and grip (last closing step)" if touched
                           else "last closing step")]


def set_equal(ax, points, margin=0.05, unit="m", labels=("x", "y", "z"), box=None):
    """Equal scales on the three axes over `points` (with a margin of their span), or over `box`
    (lo, hi) as given."""
    if box is None:
        lo, hi = points.min(axis=0), points.max(axis=0)
        span = hi - lo
        lo, hi = lo - margin * span.max(), hi + margin * span.max()
    else:
        lo, hi = box
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.set_xlabel(f"{labels[0]} ({unit})", fontsize=7)
    ax.set_ylabel(f"{labels[1]} ({unit})", fontsize=7)
    ax.set_zlabel(f"{labels[2]} ({unit})", fontsize=7)
    ax.tick_params(labelsize=6)


def fig18(traj, out):
    """A grasp at two steps (shown_steps), gravity down, framed on the object and the hand geoms
    touching it (frame_box), one frame for both panels."""
    q, labels = drawn_frame(traj)
    shown = shown_steps(traj)
    box = frame_box(traj, [step for step, _ in shown], q)
    fig = plt.figure(figsize=(5 * len(shown), 5.3))
    for k, (step, title) in enumerate(shown):
        ax = fig.add_subplot(1, len(shown), k + 1, projection="3d")
        draw_scene(ax, traj, step, q, box)
        set_equal(ax, None, labels=labels, box=box)
        ax.set_box_aspect(box[1] - box[0], zoom=0.9)  # room for the axis labels
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):  # four ticks: a few centimetres' frame
            axis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
        ax.view_init(elev=20, azim=-60)
        n = len(traj["steps"][step]["contacts"])
        ax.set_title(f"{traj['name']}: {title}, grasp step {step + 1}\n{n} contacts "
                     "(hand geoms touching the object red)", fontsize=9)
    fig.text(0.5, 0.012, "Gravity points down; axes are the world's (a minus sign: reversed). "
             "Framed on the object and the hand geoms touching it, cut at the frame.",
             ha="center", fontsize=8, style="italic")
    fig.tight_layout(rect=(0, 0.06, 1, 0.96))
    fig.savefig(out, dpi=110)
    plt.close(fig)


def boxes_text(n):
    return f"{n} box" if n == 1 else f"{n} boxes"


def obb_finger(traj):
    """The geom of a finger segment whose mesh has OBB levels (the distal segment C first)."""
    for letter in ("C", "B", "A"):
        for g, geom in enumerate(traj["geoms"]):
            if geom["segment"] == letter and geom["type"] == "mesh" and \
                    "obb_levels" in traj["meshes"][geom["mesh"]]:
                return g
    raise InputError(f"{traj['file']}: no finger segment with OBB levels")


def fig17(traj, out):
    g = obb_finger(traj)
    mesh = traj["meshes"][traj["geoms"][g]["mesh"]]
    v = np.array(mesh["vertices"]).reshape(-1, 3)
    tris = v[np.array(mesh["faces"]).reshape(-1, 3)]
    levels = mesh["obb_levels"]
    corners = [[box_corners(np.array(b["center"]), np.array(b["axes"]).reshape(3, 3), b["half"])
                for b in boxes] for boxes in levels]
    # One scale for every panel (in mm): the union of the mesh and every level's boxes.
    everything = 1e3 * np.concatenate([v] + [c for level in corners for c in level])
    fig = plt.figure(figsize=(13, 4.6))
    for depth, boxes in enumerate(levels):
        ax = fig.add_subplot(1, len(levels), depth + 1, projection="3d")
        ax.add_collection3d(Poly3DCollection(1e3 * tris, edgecolor="none",
                                             facecolors=shaded(tris, COLORS["segment"], 0.35)))
        segments = [(1e3 * c[i], 1e3 * c[j]) for c in corners[depth] for i, j in BOX_EDGES]
        ax.add_collection3d(Line3DCollection(segments, colors="#202060", linewidths=0.8))
        set_equal(ax, everything, unit="mm")
        # Three ticks an axis: the default crowds the labels of a 2 cm segment.
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.set_major_locator(matplotlib.ticker.MaxNLocator(3))
        ax.view_init(elev=15, azim=-50)
        ax.set_title(f"depth {depth}: {boxes_text(len(boxes))}", fontsize=9)
    fig.suptitle(f"OBB tree of {traj['geoms'][g]['name']} (mesh {mesh['name']}, "
                 f"{len(mesh['faces']) // 3} triangles), in its geom frame, every panel at the "
                 "same scale (mm)", fontsize=10)
    fig.text(0.5, 0.02, "Each box is fitted to its own triangles (covariance fit, paper eq. 1-3), "
             "not cut out of its parent: a child turned to its triangles' axes can stick out of "
             "its parent's box, and so look larger, though it bounds fewer triangles.",
             ha="center", fontsize=8.5, style="italic")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(out, dpi=110)
    plt.close(fig)


# Our contacts farther than this from every native one show where the two answers differ, m.
APART = 0.005


def contacts_apart(step):
    """How many of our contacts at a trajectory step lie farther than APART from every native."""
    ours = np.array([c["pos"] for c in step["contacts"]]).reshape(-1, 3)
    native = np.array([c["pos"] for c in step.get("native_contacts", [])]).reshape(-1, 3)
    if len(ours) == 0:
        return 0
    if len(native) == 0:
        return len(ours)
    d = np.linalg.norm(ours[:, None, :] - native[None, :, :], axis=2).min(axis=1)
    return int((d > APART).sum())


def most_different(trajs):
    """The (trajectory, 0-based step) whose contacts differ most from MuJoCo's native ones (the
    most of ours apart from every native contact; the later step on ties), or None."""
    best = None
    for t in trajs:
        if not any("native_contacts" in s for s in t["steps"]):
            continue
        for k, s in enumerate(t["steps"]):
            score = (contacts_apart(s), k)
            if best is None or score > best[0]:
                best = (score, t, k)
    return None if best is None else (best[1], best[2])


def contacts_figure(traj, out, step=None):
    step = len(traj["steps"]) - 1 if step is None else step
    data = traj["steps"][step]
    q, labels = drawn_frame(traj)
    fig = plt.figure(figsize=(10, 5))
    # The normal drawn with a length of a fifth of the object's size.
    objects = object_geoms(traj)
    object_points = np.concatenate([geom_polygons(traj, step, g).reshape(-1, 3) for g in objects])
    scale = 0.2 * np.ptp(object_points, axis=0).max()
    for k, (key, title, color) in enumerate([
            ("contacts", "ours (graspcd, triangle meshes)", "#d00000"),
            ("native_contacts", "MuJoCo native (convex hulls)", "#0030d0")]):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        points = draw_scene(ax, traj, step, q, roles=("object",), alpha=0.25)
        contacts = data[key]
        if contacts:
            p = np.array([c["pos"] for c in contacts]) @ q.T
            n = np.array([c["normal"] for c in contacts]) @ q.T
            ax.scatter(p[:, 0], p[:, 1], p[:, 2], color=color, s=8, depthshade=False)
            ax.quiver(p[:, 0], p[:, 1], p[:, 2], n[:, 0], n[:, 1], n[:, 2], length=scale,
                      color=color, linewidth=0.7)
            points = np.concatenate([points, p])
        set_equal(ax, points, labels=labels)
        ax.view_init(elev=25, azim=-60)
        ax.set_title(f"{title}\n{len(contacts)} contacts", fontsize=9)
    fig.suptitle(f"{traj['name']}, grasp step {step + 1}: contact points and normals on the object; "
                 f"{contacts_apart(data)} of ours lie more than {APART * 1e3:.0f} mm from every "
                 "native one", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def fig12(traj, out):
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d")
    ax.computed_zorder = False  # the labels stay on top of the boxes
    q, labels = drawn_frame(traj)
    points = draw_scene(ax, traj, 0, q, types=("mesh", "box"))  # the arm's cylinders left out
    elev, azim = 15, -70
    ax.view_init(elev=elev, azim=azim)
    toward_camera = np.array([np.cos(np.radians(azim)), np.sin(np.radians(azim)), 0.0])
    # The finger nearest the camera gets its segments labelled, each label pushed sideways.
    fingers = {}
    for g, geom in enumerate(traj["geoms"]):
        if geom["segment"]:
            fingers.setdefault(geom["name"].split("_")[0], []).append(g)
    near = max(fingers, key=lambda f: np.mean([q @ pose(traj, 0, g)[1] @ toward_camera
                                                for g in fingers[f]]))
    centre = points.mean(axis=0)
    for g in fingers[near]:
        pos = q @ pose(traj, 0, g)[1]
        side = pos - centre
        side[2] = 0
        side = side / (np.linalg.norm(side) or 1) * 0.035
        p = pos + side
        ax.plot(*zip(pos, p), color="#b00000", linewidth=1.0, zorder=10)
        ax.text(p[0], p[1], p[2], " " + traj["geoms"][g]["segment"], fontsize=15, color="#b00000",
                fontweight="bold", zorder=11)
    set_equal(ax, points, labels=labels)
    ax.set_title(f"The box hand ({traj['name']}): segments A, B, C of {near}", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def is_box_hand(traj):
    """A box hand: finger segments, every one a box (Figure 12's hand)."""
    kinds = {geom["type"] for geom in traj["geoms"] if geom.get("segment")}
    return kinds == {"box"}


def has_obb_finger(traj):
    try:
        obb_finger(traj)
        return True
    except InputError:
        return False


def trajectory_files(sources):
    """The files of `sources` (files, or folders of *.json); an empty folder is an error."""
    files = []
    for s in map(Path, sources):
        if s.is_dir():
            found = sorted(s.glob("*.json"))
            if not found:
                raise InputError(f"{s}: no *.json trajectory files")
            files += found
        else:
            files.append(s)
    return files


def draw_all(sources, dst):
    """Draws every picture the trajectory files of `sources` (files or folders) hold into `dst`;
    returns what the report says about them. Raises InputError naming the file that is missing
    or bad."""
    if isinstance(sources, (str, Path)):
        sources = [sources]
    trajs = []
    for p in trajectory_files(sources):
        trajs.append(load(p))
        trajs[-1]["file"] = str(p)
    dst = Path(dst)
    dst.mkdir(parents=True, exist_ok=True)
    grasps = [t for t in trajs if not is_box_hand(t)]
    boxes = [t for t in trajs if is_box_hand(t)]
    info = {"fig18": [], "examples": grasps, "files": [], "obb": None, "contacts": None,
            "box_hand": None}
    for t in grasps:
        name = f"fig18_{t['name']}.png"
        fig18(t, dst / name)
        info["fig18"].append((t, name))
        info["files"].append(name)
    with_obb = [t for t in trajs if has_obb_finger(t)]
    if with_obb:
        fig17(with_obb[0], dst / "fig17_obb_depths.png")
        info["obb"] = with_obb[0]
        info["files"].append("fig17_obb_depths.png")
    choice = most_different(grasps)
    if choice is not None:
        contacts_figure(choice[0], dst / "contacts_native.png", choice[1])
        info["contacts"] = choice
        info["files"].append("contacts_native.png")
    if boxes:
        fig12(boxes[0], dst / "fig12_box_hand.png")
        info["box_hand"] = boxes[0]
        info["files"].append("fig12_box_hand.png")
    return info


def section(info, fig_rel):
    """The report's section on the pictures (Markdown lines)."""
    lines = ["## Pictures of the grasps and the trees", "",
             "Drawn by `report/draw_figures.py` from the trajectory files `graspcd study` writes "
             "into `trajectories/` (one per grasp: meshes, poses per closing grasp step, contacts, "
             "per-step detection times, OBB levels; `graspcd trajectory --help`). "
             "`./run study` also bundles them into the interactive viewer "
             "`report/out/viewer/index.html`, one self-contained page that opens from the file "
             "system: a step slider, play and pause, OBB depths 0-3, our and MuJoCo's contacts, "
             "segments in contact coloured, and the detection time per grasp step of each method.",
             "", "### Each example at first contact and at the grip (the paper's Figure 18)", ""]
    for t, name in info["fig18"]:
        first = first_contact_step(t)
        lines += [f"{t['name']}: first contact at grasp step {first + 1} "
                  f"({len(t['steps'][first]['contacts'])} contacts), the grip at step "
                  f"{len(t['steps'])} ({len(t['steps'][-1]['contacts'])} contacts); "
                  f"{'held' if t['held'] else 'not held'} after the lift.", "",
                  f"![{name}]({fig_rel}/{name})", ""]
    if info["obb"] is not None:
        t = info["obb"]
        g = obb_finger(t)
        levels = t["meshes"][t["geoms"][g]["mesh"]]["obb_levels"]
        lines += ["### One finger's OBBs at tree depths 0 to 3 (Figure 17)", "",
                  f"{t['geoms'][g]['name']} of {t['name']}: " +
                  ", ".join(f"depth {d}: {boxes_text(len(b))}" for d, b in enumerate(levels)) +
                  ". Every panel at the same scale; a child box is fitted to its own triangles, "
                  "so it can stick out of its parent.", "",
                  f"![fig17_obb_depths.png]({fig_rel}/fig17_obb_depths.png)", ""]
    if info["contacts"] is not None:
        t, k = info["contacts"]
        step = t["steps"][k]
        lines += ["### Contacts on the non-convex object: ours and MuJoCo's convex hulls", "",
                  f"{t['name']} at grasp step {k + 1}, the step of all trajectories where the two "
                  f"differ most: {contacts_apart(step)} of graspcd's {len(step['contacts'])} "
                  f"contacts from the intersecting triangles lie more than {APART * 1e3:.0f} mm "
                  f"from every one of MuJoCo's {len(step['native_contacts'])} native contacts from "
                  "the convex hulls at the same joint positions. Over all closing grasp steps: "
                  f"{sum(len(s['contacts']) for s in t['steps'])} of ours, "
                  f"{sum(len(s['native_contacts']) for s in t['steps'])} native.", "",
                  f"![contacts_native.png]({fig_rel}/contacts_native.png)", ""]
    if info["box_hand"] is not None:
        lines += ["### The box hand and its segments A, B, C (Figure 12)", "",
                  f"![fig12_box_hand.png]({fig_rel}/fig12_box_hand.png)", ""]
    return lines


def insert_section(text, out_dir, fig_dir, fig_rel):
    """make_report.py's hook: draws the pictures when OUT_DIR/trajectories exists and puts their
    section before "## Reproduce" (at the end when there is none)."""
    src = Path(out_dir) / "trajectories"
    if not src.is_dir():
        return text
    try:
        info = draw_all(src, fig_dir)
    except InputError as e:
        print(e, file=sys.stderr)
        sys.exit(2)
    block = "\n".join(section(info, fig_rel)) + "\n"
    at = text.find("## Reproduce")
    return text + "\n" + block if at < 0 else text[:at] + block + text[at:]


def main(argv):
    if len(argv) < 3:
        print("usage: draw_figures.py TRAJECTORY [TRAJECTORY ...] FIGURES_DIR", file=sys.stderr)
        return 2
    try:
        info = draw_all(argv[1:-1], argv[-1])
    except InputError as e:
        print(e, file=sys.stderr)
        return 2
    for name in info["files"]:
        print(f"wrote {Path(argv[-1]) / name}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
