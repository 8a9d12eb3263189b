#!/usr/bin/python3
"""What graspcd hands MuJoCo's solver, per scene ("Contacts and the solver").

usage: contacts_solver.py GRASPCD OUT_DIR [--quick]

Runs `graspcd grasp SCENE --json` on each scene four ways: natively (MuJoCo's convex hulls),
served with the pair config as shipped with exact contacts every step (`--exact`; the contact
manifold: at most 4 points per patch and 8 per geom pair), served so with the budget raised to
mjMAXCONPAIR (50 per pair and per patch: every intersecting triangle pair's contact, up to MuJoCo's
cap, as before the manifold), and served as shipped with contacts reused across steps within REUSE
metres (`--contact-reuse`, the default). Writes
OUT_DIR/contacts.json: per scene and variant the finger-object contacts per physics step (mean,
max), the most one geom pair had, the wall time per physics step, held and the rise, the hold's
last second at rest (speed, penetration), and MuJoCo's buffer-full counters. The time ratios are
of runs made one after another on the same machine, not a benchmark (`./run perf` has those).
--quick: examples 1 and 3 only.
"""
import json
import os
import subprocess
import sys
import tempfile

SCENES = ["example1", "example2", "example3", "hand_triangles", "real_robotiq_cup"]
QUICK_SCENES = ["example1", "example3"]
BEFORE_BUDGET = 50  # mjMAXCONPAIR: what a pair could hand the solver before the manifold
REUSE = 2e-5  # metres: the drift of the reuse variant, as in BM_WholeGrasp and the hard scenes


def fail(message):
    print(f"contacts_solver.py: {message}", file=sys.stderr)
    sys.exit(2)


def grasp(graspcd, scene, extra):
    cmd = [graspcd, "grasp", scene, "--json"] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} exited with {r.returncode}: {r.stderr.strip()}")
    d = json.loads(r.stdout)
    return {
        "held": d["held"],
        "rise": d["object_z_final"] - d["object_z_initial"],
        "mean_contacts": d["mean_contacts"],
        "max_contacts": d["max_contacts"],
        "max_pair_contacts": d["max_pair_contacts"],
        "ms_per_physics_step": d["ms_per_physics_step"],
        "physics_steps": d["physics_steps"],
        "rest_max_speed": d["rest"]["max_speed"],
        "rest_max_penetration": d["rest"]["max_penetration"],
        "contact_buffer_full": d["contact_buffer_full"],
        "constraint_buffer_full": d["constraint_buffer_full"],
        "reused_calls": d["reused_calls"],
    }


def main():
    args = [a for a in sys.argv[1:] if a != "--quick"]
    if len(args) != 2:
        fail("usage: contacts_solver.py GRASPCD OUT_DIR [--quick]")
    graspcd, out_dir = args
    mjcf = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mjcf")
    scenes = QUICK_SCENES if "--quick" in sys.argv else SCENES
    out = {"before_budget": BEFORE_BUDGET, "reuse": REUSE, "scenes": {}}
    with tempfile.TemporaryDirectory(prefix="graspcd-contacts-") as tmp:
        for name in scenes:
            scene = os.path.normpath(os.path.join(mjcf, name + ".xml"))
            config_path = scene[:-4] + ".pairs.json"
            with open(config_path) as f:
                config = json.load(f)
            config["max_contacts"] = BEFORE_BUDGET
            config["max_patch_contacts"] = BEFORE_BUDGET
            for entry in config.get("pairs", []):
                entry.pop("max_contacts", None)
                entry.pop("max_patch_contacts", None)
            before = os.path.join(tmp, name + ".pairs.json")
            with open(before, "w") as f:
                json.dump(config, f)
            print(f"contacts_solver.py: {name}", file=sys.stderr)
            out["scenes"][name] = {
                "native": grasp(graspcd, scene, ["--native"]),
                "manifold": grasp(graspcd, scene, ["--exact"]),
                "before": grasp(graspcd, scene, ["--config", before, "--exact"]),
                "reuse": grasp(graspcd, scene, ["--contact-reuse", repr(REUSE)]),
            }
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "contacts.json"), "w") as f:
        json.dump(out, f, indent=1, sort_keys=True)
        f.write("\n")


if __name__ == "__main__":
    main()
