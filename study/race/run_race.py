#!/usr/bin/python3
"""The race: graspcd against the routes MuJoCo users are told to take, on the same grasps.

usage: run_race.py GRASPCD [--out FILE] [--work DIR] [--scenes S1,S2,...] [--pieces 4,8,16]
                   [--object "NAME=FILE [grasp --object options]"]... [--scene-pieces S=4,8 ...]
                   [--simplify-above FACES=F] [--merge OLD.json]

For each scene (default: examples 1-3; mjcf/S.xml) and each --object (a user's mesh through
`graspcd grasp --object FILE OPTIONS --write-scene WORK/scenes/NAME`, raced as that scene under
NAME), the object's mesh (the <mesh> asset of the geoms of body
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
Timings are single runs one after another on the same machine, not a benchmark. Each scene keeps
its own provenance (graspcd's version and commit from the grasp's JSON, the date, the load average
and the wall time of its race) and its piece counts (--scene-pieces S=4,8 races scene S with
fewer, or none with S=, where decompositions or grasps would take too long; --scene-note S=TEXT
says why in the data and the report). --simplify-above FACES=F decomposes every mesh of more than
FACES triangles with `decompose --simplify F` (HACD partitions a copy decimated to at most F faces;
the pieces are hulls of the original vertices), cached apart (WORK/STEM_N_simplifyF), and records
it per scene ("simplify": the threshold, F and the mesh's triangles; null when the mesh was
decomposed as it is) and per decomposition (faces after decimation, its time, and the commit of
the graspcd that made it). The file keeps the command, its wall time and the load at its end;
each row the phantom and missed contacts per hand geom (the judge leaves out the body the object
stands on, the pair config's "support": the Robotiq scenes' table).
--merge OLD.json keeps OLD's scenes that this run does not race, each with its own provenance.
"""
import argparse
import datetime
import json
import os
import platform
import shlex
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def fail(message):
    print(f"run_race.py: {message}", file=sys.stderr)
    sys.exit(2)


def object_mesh(scene):
    """The file of the mesh asset that the geoms of body "object" use (meshdir applied)."""
    return object_mesh_and_scale(scene)[0]


def object_mesh_and_scale(scene):
    """object_mesh and the asset's scale (3 numbers; 1 1 1 without one): the decompositions
    are in the file's units, the scene scales them."""
    root = ET.parse(scene).getroot()
    meshdir = ""
    for c in root.iter("compiler"):
        meshdir = c.get("meshdir", meshdir)
    files = {}
    scales = {}
    for m in root.iter("mesh"):
        if m.get("file"):
            name = m.get("name") or os.path.splitext(os.path.basename(m.get("file")))[0]
            files[name] = m.get("file")
            scales[name] = [float(x) for x in m.get("scale", "1 1 1").split()]
    for body in root.iter("body"):
        if body.get("name") != "object":
            continue
        for g in body.iter("geom"):
            if g.get("mesh") in files:
                return (os.path.normpath(os.path.join(os.path.dirname(scene), meshdir,
                                                      files[g.get("mesh")])),
                        scales[g.get("mesh")])
    fail(f"{scene}: no mesh geom in body 'object'")


def triangle_count(mesh):
    """The triangles of an OBJ (a polygon of n vertices is n - 2 of them, as graspcd reads it) or
    of a binary STL (its header's count)."""
    if mesh.lower().endswith(".stl"):
        with open(mesh, "rb") as f:
            f.seek(80)
            return int.from_bytes(f.read(4), "little")
    count = 0
    with open(mesh, encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith("f "):
                count += len(line.split()) - 3
    return count


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


def provenance(g, started):
    """Where one scene's race ran: graspcd's version and commit (the grasp's JSON), when, the
    load average after it and its wall time."""
    return {"graspcd": g.get("graspcd", {}), "load_average": list(os.getloadavg()),
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "wall_seconds": round(time.time() - started, 1)}


def object_scene(graspcd, spec, work):
    """--object "NAME=FILE [options]": the scene `graspcd grasp --object` writes, kept in
    WORK/scenes/NAME (its .pairs.json beside it)."""
    name, _, rest = spec.partition("=")
    words = shlex.split(rest)
    if not name or not words:
        fail(f"--object {spec!r}: give NAME=FILE [grasp --object options]")
    folder = os.path.join(work, "scenes", name)
    run_json([graspcd, "grasp", "--object", words[0], *words[1:], "--write-scene", folder,
              "--max-steps", "1", "--json"])
    stem = os.path.splitext(os.path.basename(words[0]))[0]
    return name, os.path.join(folder, stem + ".xml"), {"file": words[0], "options": words[1:]}


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
            "phantom_by_geom": judge["phantom_by_geom"], "missed_by_geom": judge["missed_by_geom"],
            "contact_error_per_step": judge["contact_error_per_step"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("graspcd")
    parser.add_argument("--out", default=os.path.join(ROOT, "report/data/race.json"))
    parser.add_argument("--work", default=os.path.join(ROOT, "report/out/race"))
    parser.add_argument("--scenes", default="example1,example2,example3")
    parser.add_argument("--pieces", default="4,8,16")
    parser.add_argument("--object", action="append", default=[],
                        help='"NAME=FILE [grasp --object options]": race a user\'s mesh as NAME')
    parser.add_argument("--scene-pieces", action="append", default=[],
                        help="S=4,8: race scene S with these piece counts only")
    parser.add_argument("--scene-note", action="append", default=[],
                        help="S=TEXT: a note on scene S for the report (e.g. why fewer pieces)")
    parser.add_argument("--simplify-above", metavar="FACES=F",
                        help="decompose meshes of more than FACES triangles with --simplify F")
    parser.add_argument("--merge", help="keep this race.json's scenes that are not raced now")
    args = parser.parse_args()
    simplify_above = None
    if args.simplify_above:
        above, _, target = args.simplify_above.partition("=")
        try:
            simplify_above = (int(above), int(target))
        except ValueError:
            fail(f"--simplify-above {args.simplify_above!r}: give FACES=F, two integers")
    pieces = [int(p) for p in args.pieces.split(",")]
    scene_pieces = {}
    for spec in args.scene_pieces:
        name, _, counts = spec.partition("=")
        scene_pieces[name] = [int(p) for p in counts.split(",") if p]
    notes = dict(spec.partition("=")[::2] for spec in args.scene_note)
    result = {"machine": machine(), "pieces": pieces,
              "command": [os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:], "scenes": {}}
    race_started = time.time()
    scenes = [(s, os.path.join(ROOT, "mjcf", s + ".xml"), None)
              for s in args.scenes.split(",") if s]
    scenes += [object_scene(args.graspcd, spec, args.work) for spec in args.object]
    for scene_name, scene, user_object in scenes:
        started = time.time()
        mesh, scale = object_mesh_and_scale(scene)
        stem = os.path.splitext(os.path.basename(mesh))[0]
        entry = {"mesh": os.path.relpath(mesh, ROOT), "mesh_scale": scale, "decompositions": {},
                 "rows": []}
        if user_object:
            entry["object"] = user_object
        counts = scene_pieces.get(scene_name, pieces)
        entry["pieces"] = counts
        if scene_name in notes:
            entry["note"] = notes[scene_name]
        faces = triangle_count(mesh)
        simplify = None
        if simplify_above and faces > simplify_above[0]:
            simplify = simplify_above[1]
        entry["simplify"] = (None if simplify is None else
                             {"above": simplify_above[0], "max_faces": simplify,
                              "source_faces": faces})
        base = [args.graspcd, "grasp", scene, "--judge", "--json"]
        print(f"[race] {scene_name}: graspcd, native", file=sys.stderr)
        first = run_json(base)
        entry["rows"].append(row("graspcd", first))
        entry["rows"].append(row("native hull", run_json(base + ["--native"])))
        for n in counts:
            suffix = "" if simplify is None else f"_simplify{simplify}"
            out = os.path.join(args.work, f"{stem}_{n}{suffix}")
            manifest = os.path.join(out, "decomposition.json")
            if not os.path.exists(manifest):
                print(f"[race] {scene_name}: decompose {stem} into at most {n}"
                      + ("" if simplify is None else f" (--simplify {simplify})"), file=sys.stderr)
                run_json([args.graspcd, "decompose", mesh, "--out", out, "--pieces", str(n),
                          "--json"] + ([] if simplify is None else ["--simplify", str(simplify)]))
            with open(manifest, encoding="utf-8") as f:
                d = json.load(f)
            entry["decompositions"][str(n)] = {
                "pieces": d["piece_count"], "slabs": d["slabs"], "seconds": d["seconds"],
                "hausdorff": d["hausdorff"]["distance"],
                "hausdorff_bound": d["hausdorff"]["error_bound"], "volume": d["volume"],
                "source_faces": d["source_faces"], "simplify": d.get("simplify"),
                "graspcd": d.get("graspcd", {}).get("commit")}
            print(f"[race] {scene_name}: decomposed-{n}", file=sys.stderr)
            entry["rows"].append(row(f"decomposed-{n}", run_json(base + ["--decomposed", out])))
        entry["provenance"] = provenance(first, started)
        result["scenes"][scene_name] = entry
    if args.merge:
        with open(args.merge, encoding="utf-8") as f:
            old = json.load(f)
        for scene_name, entry in old["scenes"].items():
            if scene_name in result["scenes"]:
                continue
            entry.setdefault("pieces", old["pieces"])
            # A scene of a run before per-scene provenance: the old run's machine and date.
            entry.setdefault("provenance", {"machine": old["machine"]})
            result["scenes"][scene_name] = entry
    result["wall_seconds"] = round(time.time() - race_started, 1)
    result["load_average_end"] = list(os.getloadavg())
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
