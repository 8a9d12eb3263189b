#!/usr/bin/python3
"""report/draw_figures.py's grasp pictures (fig18) on made-up trajectories shaped as a Robotiq
grasp: gravity along +z, a 37 mm object between two pads of a hand half a metre across, a support
beyond the object. Gravity is drawn down whatever its world direction; the frame is the object and
the geoms touching it (not the whole hand, not the support); the two panels show two different
steps, also when the pads touch together at the last closing step. Run by ctest as
figure_frame_test; exit 0 when every check holds."""

import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "report"))
import draw_figures  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


IDENTITY = [1, 0, 0, 0, 1, 0, 0, 0, 1]
OBJECT_HALF = 0.0185  # a 37 mm cube


def trajectory(gravity, first_touch, steps=4):
    """Geoms: the object at the origin, two pads closing on it along x (touching it from step
    `first_touch`, 0-based), the hand's base: a 0.5 m box 0.3 m away against gravity, the support
    (0.2 m square) just beyond the object along gravity."""
    up = -np.array(gravity, float) / np.linalg.norm(gravity)
    geoms = [
        {"name": "object", "type": "box", "size": [OBJECT_HALF] * 3, "role": "object",
         "segment": "", "collides": True},
        {"name": "left_pad", "type": "box", "size": [0.005, 0.01, 0.02], "role": "hand",
         "segment": "", "collides": True},
        {"name": "right_pad", "type": "box", "size": [0.005, 0.01, 0.02], "role": "hand",
         "segment": "", "collides": True},
        {"name": "base", "type": "box", "size": [0.25, 0.25, 0.05], "role": "hand", "segment": "",
         "collides": True},
        {"name": "table", "type": "box", "size": [0.1, 0.1, 0.01], "role": "support",
         "segment": "", "collides": True},
        {"name": "base_visual", "type": "box", "size": [0.4, 0.4, 0.4], "role": "hand",
         "segment": "", "collides": False},
    ]
    out = []
    for s in range(steps):
        # The pads' inner faces reach the object's faces at first_touch.
        gap = OBJECT_HALF + 0.005 + 0.004 * max(0, first_touch - s)
        pos = [[0, 0, 0], [-gap, 0, 0], [gap, 0, 0], list(0.3 * up), list(-0.03 * up),
               list(0.3 * up)]
        contacts = []
        if s >= first_touch:
            contacts = [{"geoms": [1, 0], "pos": [-OBJECT_HALF, 0, 0], "normal": [1, 0, 0]},
                        {"geoms": [0, 2], "pos": [OBJECT_HALF, 0, 0], "normal": [1, 0, 0]}]
        out.append({"pos": [x for p in pos for x in p], "rot": IDENTITY * len(geoms),
                    "contacts": contacts, "native_contacts": []})
    return {"schema": 1, "name": "made_up", "first_contact": [first_touch + 1, first_touch + 1],
            "held": True, "gravity": list(gravity), "meshes": [], "geoms": geoms, "steps": out}


# Gravity drawn down: the drawn frame's rows are the drawn x, y, z in world coordinates.
for gravity in ([0, 0, 9.81], [0, 0, -9.81], [9.81, 0, 0], [0, -3, 4]):
    q, labels = draw_figures.drawn_frame({"gravity": gravity})
    down = q @ (np.array(gravity) / np.linalg.norm(gravity))
    check(np.allclose(down, [0, 0, -1]), f"gravity {gravity} drawn as {down}, not down")
    check(np.allclose(q @ q.T, np.eye(3)) and np.isclose(np.linalg.det(q), 1),
          f"gravity {gravity}: the drawn frame is no rotation")
q, labels = draw_figures.drawn_frame({"gravity": [0, 0, 9.81]})
check(labels[2] == "\u2212z", f"gravity +z: the drawn up axis is labelled {labels[2]}, not -z")
check(draw_figures.drawn_frame({})[1] == ["x", "y", "z"], "no gravity in the file: MuJoCo's -z")

# The frame: the object and the pads touching it, not the 0.5 m base or the support.
for first_touch in (1, 3):
    t = trajectory([0, 0, 9.81], first_touch)
    q, _ = draw_figures.drawn_frame(t)
    shown = draw_figures.shown_steps(t)
    steps = [s for s, _ in shown]
    check(len(set(steps)) == 2, f"first touch at step {first_touch + 1}: panels show {steps}")
    if first_touch == 3:  # the pads touch at the last step: the start and the grip
        check(steps == [0, 3], f"pads touching at the last step: panels show {steps}, not 0 and 3")
    else:
        check(steps == [1, 3], f"first contact at step 2: panels show {steps}, not 1 and 3")
    lo, hi = draw_figures.frame_box(t, steps, q)
    extent = hi - lo
    size = 2 * OBJECT_HALF
    check(((lo <= -OBJECT_HALF) & (hi >= OBJECT_HALF)).all(),
          f"first touch {first_touch}: the object is not wholly in the frame {lo} {hi}")
    limit = size * (1 + 2 * draw_figures.FRAME_REACH) * (1 + 2 * draw_figures.FRAME_MARGIN)
    check(extent.max() <= limit + 1e-12,
          f"first touch {first_touch}: frame {extent.max():.3f} m across for a {size} m object "
          f"(at most {limit:.3f} m)")
    # Both pads (one touching, one as far out on the other side) within the frame across gravity.
    check(hi[0] >= OBJECT_HALF + 0.01 and lo[0] <= -OBJECT_HALF - 0.01,
          f"first touch {first_touch}: the pads are cut from the frame ({lo[0]:.3f}, {hi[0]:.3f})")

# The picture itself is drawn, and a trajectory whose pads never touch still shows two steps.
t = trajectory([0, 0, 9.81], 10)
t["first_contact"] = [0, 0]
check([s for s, _ in draw_figures.shown_steps(t)] == [0, 3], "no touch: the start and the end")
with tempfile.TemporaryDirectory() as d:
    out = Path(d) / "fig18_made_up.png"
    draw_figures.fig18(trajectory([0, 0, 9.81], 3), out)
    data = out.read_bytes()
    check(data[1:4] == b"PNG" and len(data) > 10000, "fig18 wrote no picture")

for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
