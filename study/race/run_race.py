#!/usr/bin/python3
"""The race of issue 20: graspcd against the routes MuJoCo users are told to take, on the same grasps.

usage: run_race.py GRASPCD [--out FILE] [--work DIR] [--scenes S1,S2,...] [--pieces 4,8,16]

For each scene (default: examples 1-3), the object's mesh (the <mesh> asset of the geoms of body
"object") is decomposed with `graspcd decompose MESH --out DIR --pieces N` for each N (cached in
--work: a decomposition whose decomposition.json exists is not redone; HACD takes minutes on
meshes of thousands of faces), and the grasp `graspcd grasp SCENE --judge --json` runs in each
configuration: graspcd (the scene's pair config: the contact manifold), native (MuJoCo on the
convex hull, --native) and decomposed-N (MuJoCo natively on N convex pieces, --decomposed DIR).
Per configuration: the wall time per physics step over the whole grasp (ms), the hand-object
contacts per physics step, gripped and held, the first-contact grasp step of each finger segment
beside CGAL's on the true meshes, and the contact error per closing grasp step (phantom plus
missed contacts, `grasp --judge`). Writes --out (default report/data/race.json) with the
machine it ran on; report/make_report.py draws its table and Pareto figure from it.
Timings are single runs one after another on the same machine, not a benchmark.
"""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def fail(message):
    print(f"run_race.py: {message}", file=sys.stderr)
    sys.exit(2)


def object_mesh(scene):
    """The file of the mesh asset that the geoms of body "object" use (meshdir applied)."""
    root = ET.parse(scene).getroot()
    meshdir = ""
    for c in root.iter("compiler"):
        meshdir = c.get("meshdir", meshdir)
    files = {}
    for m in root.iter("mesh"):
        if m.get("file"):
            name = m.get("name") or os.path.splitext(os.path.basename(m.get("file")))[0]
            files[name] = m.get("file")
    for body in root.iter("body"):
        if body.get("name") != "object":
            continue
        for g in body.iter("geom"):
            if g.get("mesh") in files:
                return os.path.normpath(os.path.join(os.path.dirname(scene), meshdir,
                                                     files[g.get("mesh")]))
    fail(f"{scene}: no mesh geom in body 'object'")


def run_json(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"{' '.join(command)}: exit {done.returncode}: {done.stderr.strip()}")
    return json.loads(done.stdout)


def machine():
    model = "unknown"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {"cpu": model, "cores": os.cpu_count(), "load_average": list(os.getloadavg()),
            "platform": platform.platform(),
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}


def row(name, g):
    judge = g["judge"]
    return {"configuration": name,
            "ms_per_physics_step": g["ms_per_physics_step"],
            "contacts_per_step": g["mean_contacts"],
            "gripped": g["gripped"], "held": g["held"],
            "rise": g["object_z_final"] - g["object_z_initial"],
            "first_contact": g["first_contact"],
            "cgal_first_contact": judge["cgal_first_contact"],
            "cgal_first_contact_body": judge["cgal_first_contact_body"],
            "closing_steps": judge["steps"],
            "judged_contacts": judge["contacts"],
            "phantom": judge["phantom"], "missed": judge["missed"],
            "contact_error_per_step": judge["contact_error_per_step"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("graspcd")
    parser.add_argument("--out", default=os.path.join(ROOT, "report/data/race.json"))
    parser.add_argument("--work", default=os.path.join(ROOT, "report/out/race"))
    parser.add_argument("--scenes", default="example1,example2,example3")
    parser.add_argument("--pieces", default="4,8,16")
    args = parser.parse_args()
    pieces = [int(p) for p in args.pieces.split(",")]
    result = {"machine": machine(), "pieces": pieces, "scenes": {}}
    for scene_name in args.scenes.split(","):
        scene = os.path.join(ROOT, "mjcf", scene_name + ".xml")
        mesh = object_mesh(scene)
        stem = os.path.splitext(os.path.basename(mesh))[0]
        entry = {"mesh": os.path.relpath(mesh, ROOT), "decompositions": {}, "rows": []}
        base = [args.graspcd, "grasp", scene, "--judge", "--json"]
        print(f"[race] {scene_name}: graspcd, native", file=sys.stderr)
        entry["rows"].append(row("graspcd", run_json(base)))
        entry["rows"].append(row("native hull", run_json(base + ["--native"])))
        for n in pieces:
            out = os.path.join(args.work, f"{stem}_{n}")
            manifest = os.path.join(out, "decomposition.json")
            if not os.path.exists(manifest):
                print(f"[race] {scene_name}: decompose {stem} into at most {n}", file=sys.stderr)
                run_json([args.graspcd, "decompose", mesh, "--out", out, "--pieces", str(n),
                          "--json"])
            with open(manifest, encoding="utf-8") as f:
                d = json.load(f)
            entry["decompositions"][str(n)] = {
                "pieces": d["piece_count"], "slabs": d["slabs"], "seconds": d["seconds"],
                "hausdorff": d["hausdorff"]["distance"],
                "hausdorff_bound": d["hausdorff"]["error_bound"], "volume": d["volume"],
                "source_faces": d["source_faces"]}
            print(f"[race] {scene_name}: decomposed-{n}", file=sys.stderr)
            entry["rows"].append(row(f"decomposed-{n}", run_json(base + ["--decomposed", out])))
        result["scenes"][scene_name] = entry
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
