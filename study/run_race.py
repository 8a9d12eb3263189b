#!/usr/bin/python3
"""The race: graspcd against the routes MuJoCo users are told to take, on the same grasps.

usage: run_race.py GRASPCD [--out FILE] [--work DIR] [--scenes S1,S2,...] [--pieces 4,8,16]
                   [--object "NAME=FILE [grasp --object options]"]... [--scene-pieces S=4,8 ...]
                   [--simplify-above FACES=F] [--merge OLD.json] [--noslip 0,10]
                   [--engines hacd,vhacd] [--vhacd-pieces 16] [--multiccd 0,1]
                   [--configurations "native hull*,decomposed-*,3.14*"] [--node node]

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
the pieces are hulls of the original vertices; HACD only), cached apart (WORK/STEM_N_simplifyF), and records
it per scene ("simplify": the threshold, F and the mesh's triangles; null when the mesh was
decomposed as it is) and per decomposition (faces after decimation, its time, and the commit of
the graspcd that made it). The file keeps the command, its wall time and the load at its end;
each row the phantom and missed contacts per hand geom (the judge leaves out the body the object
stands on, the pair config's "support": the Robotiq scenes' table).
--merge OLD.json keeps OLD's scenes that this run does not race, each with its own provenance
(repeatable; `--scenes ""` races nothing and only merges: races run side by side, each into its
own file, joined afterwards); the file lists each merged file's command, wall time and load
("merged").

Every run writes a run record (docs/run-record.md) in WORK/records/SCENE/ and is judged from it by
`graspcd judge` (study/race_judged.py): graspcd's own configurations run `graspcd grasp ... --judge
--json --write-run RECORD --six-directions` (the grasp's JSON gives the step cost, the contacts
per step and the first contacts; the judge the outcome, the verdicts, the true penetration, the six
directions and the phantom and missed contacts). On the scenes whose pair config has a "grasp"
section, MuJoCo 3.14 (the WebAssembly build, node tools/mujoco3/grasp3.mjs; docs/mujoco3.md)
races four more configurations: "3.14 hull" (its hull, multiccd on: 3.14's default), "3.14 sdf"
and "3.14 sdf10" (the mesh SDF, sdf_initpoints 40 and 10) and "3.14 flex" (the rigid flex, radius
0.5 mm), each once per --noslip value with the six directions; its record is kept and a race that
finds it judges it again without running node (delete it to run it again); --mujoco3-kept-only
judges the kept records and runs node for none (records made ahead, or side by side, by the
runner; the scene's "mujoco3" entry lists the runs without one). Their step cost is
WebAssembly's, in its own field (ms_per_physics_step_wasm; ms_per_physics_step is null). A scene
3.14 cannot start is a row "cannot start" with the runner's message; a scene of the project's own
hand (no "grasp" section), or a machine without node or tools/mujoco3's npm packages, has no 3.14
rows and says why in its "mujoco3" entry.

The protocol (study/race_score.py): every configuration runs once per --noslip value
(MuJoCo's noslip iterations, `grasp --noslip N`; default 0 and 10), and each run is one row with
its outcome (held, held tilted, dropped, ejected, cannot start), the verdict's reason, the tilt,
the object's top speed and largest kinetic energy, the deepest penetration of the true meshes over
the run (`grasp`'s true_penetration: measured on the true meshes whatever collided, so a run that
threw the object out is not scored on the contacts it no longer has), the judge's phantom and
missed contacts per closing step and the step cost; the report scores it (outcome, then the true
penetration into the hand, then contact error). A run the grasp refuses at the start (exit code 2, "cannot start ..." or "the
start state is not valid ...") is a row "cannot start" with that message; any other failed run a
row "cannot start" with its message too; a decomposition that fails is recorded with its message
and raced no further.

--multiccd 0,1 (the default) races MuJoCo's native configurations, the hull and the pieces, once
without and once with MuJoCo's multi-point convex collision (`grasp --multiccd`: up to 5 contacts
per convex pair instead of 1); a configuration with it is named with " multiccd" after its name
("native hull multiccd", "decomposed-16 multiccd"), and every row records "multiccd". graspcd's
served pairs are not convex and are graspcd's own: its row runs without it ("graspcd", multiccd
false); "graspcd multiccd" (the pairs graspcd does not serve, the object on its table, with it) is
raced only when --configurations names it. "graspcd exact" is graspcd with exact contacts every
step (`grasp --exact`; "graspcd" is the scene's config, whose default reuses a touching pair's
contacts within 20 um). --configurations LIST (comma-separated names or
fnmatch patterns, e.g. "native hull*,decomposed-*") races only the configurations it matches, and
decomposes only for those: graspcd's rows can be raced apart from the baselines and the two files
joined with --merge, which keeps, for a scene raced in both, the merged file's rows of the
configurations and noslip values this run did not race (each with the provenance of the race
that ran it, in "merged_rows": a row the merged file had itself merged keeps the origin it had
there). --engines hacd,vhacd decomposes with each engine `graspcd decompose
--engine` offers (HACD always: configuration decomposed-N; V-HACD, when the executable has it:
vhacd-N, with --vhacd-pieces' counts when given, else the scene's), cached apart in --work.
"""
import argparse
import datetime
import fnmatch
import json
import os
import platform
import re
import shlex
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import race_judged  # study/race_judged.py, beside this script
import race_score  # study/race_score.py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(message):
    print(f"run_race.py: {message}", file=sys.stderr)
    sys.exit(2)


def object_mesh(scene):
    """The file of the mesh asset that the geoms of body "object" use (meshdir applied)."""
    return object_mesh_and_scale(scene)[0]


def object_mesh_and_scale(scene):
    """object_mesh and the asset's scale (3 numbers; 1 1 1 without one): the decompositions
    are in the file's units, the scene scales them."""
    # Comments left out before parsing: MuJoCo's parser takes "--" inside a comment (a scene's
    # header naming `grasp --native`), Python's does not.
    with open(scene, encoding="utf-8") as f:
        root = ET.fromstring(re.sub(r"<!--.*?-->", "", f.read(), flags=re.DOTALL))
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


def grasp_run(command):
    """One grasp: (its JSON, None), or (None, the message) when it exited with an error (a start
    it refused, exit code 2 with one line)."""
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        lines = [x for x in done.stderr.strip().splitlines() if not x.startswith("warning:")]
        return None, (lines[-1] if lines else f"exit {done.returncode}")
    return json.loads(done.stdout), None


# The keys of `graspcd grasp --json` that are verdicts and judged contacts: `graspcd judge --json`
# computes them from the run record with the same library code (docs/run-record.md), and
# judged_run takes them from it.
JUDGED_KEYS = ("gripped", "held", "reason", "evidence", "notes", "outcome", "closing",
               "object_z_initial", "object_z_gripped", "object_z_final", "object_rise",
               "hand_travel", "grip_rise", "hold_min_z", "hold_drift", "lowest_z", "tilt_deg",
               "tilt_final_deg", "tilt_before_lift_deg", "max_speed", "kinetic_energy_max",
               "ejected", "fell", "dropped_at", "drop", "pushed", "pushed_during_squeeze",
               "pushed_over", "release_time", "slip_time", "touching_at_lift",
               "support_warning", "true_penetration", "true_penetration_max",
               "true_penetration_step", "six_directions", "judge")


def judged_run(graspcd, scene, command, record):
    """One grasp judged through `graspcd judge` (docs/run-record.md): `command` (a `graspcd grasp
    SCENE ... --json` command line, with --judge for the contact counts) runs with --write-run
    RECORD, then `graspcd judge SCENE RECORD --json` judges the record. Returns (the grasp's JSON
    with its verdict keys, JUDGED_KEYS, replaced by the judge's, None), or (None, the message)
    for a run that cannot start: a start refused (by graspcd or, from the record's contacts, by
    the simulator's geometry), a run gone non-finite, or a grasp that failed before it could
    write its record."""
    g, message = grasp_run(command + ["--write-run", record])
    if not os.path.exists(record):
        return None, message
    done = subprocess.run([graspcd, "judge", scene, record, "--json"], capture_output=True,
                          text=True)
    if done.returncode != 0:
        lines = [x for x in done.stderr.strip().splitlines() if not x.startswith("warning:")]
        return None, (lines[-1] if lines else f"graspcd judge: exit {done.returncode}")
    j = json.loads(done.stdout)
    if j["outcome"] == "cannot start":
        return None, j.get("message") or message
    if g is None:
        return None, message
    out = dict(g)
    for key in JUDGED_KEYS:
        if key in j:
            out[key] = j[key]
    return out, None


def refused_row(name, noslip, message, multiccd=False):
    """The row of a run that did not start (or failed): no measures."""
    return {"configuration": name, "noslip": noslip, "outcome": "cannot start",
            "message": message, "gripped": False, "held": False, "reason": None,
            "tilt_deg": None, "tilt_final_deg": None, "max_speed": None,
            "kinetic_energy_max": None, "true_penetration_max": None, "true_penetration": None,
            "multiccd": multiccd, "ms_per_physics_step": None, "ms_per_physics_step_wasm": None,
            "contacts_per_step": None, "six_directions": None,
            "phantom": None,
            "missed": None, "contact_error_per_step": None, "first_contact": {},
            "cgal_first_contact": {}, "cgal_first_contact_body": {}}


def row(name, g, noslip=None):
    judge = g["judge"]
    tp = g.get("true_penetration")
    return {"configuration": name,
            "noslip": g.get("noslip_iterations", noslip),
            "multiccd": g.get("multiccd", False),
            "outcome": race_score.outcome(g),
            "reason": g.get("reason"),
            "ejected": g.get("ejected"),
            "tilt_deg": g.get("tilt_deg"), "tilt_final_deg": g.get("tilt_final_deg"),
            "max_speed": g.get("max_speed"),
            "kinetic_energy_max": g.get("kinetic_energy_max"),
            "true_penetration_max": g.get("true_penetration_max"),
            "true_penetration": tp,
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


def configuration_names(name, multiccds):
    """The configurations of one collision route: `name` without MuJoCo's multiccd, and
    "`name` multiccd" with it, for the values in `multiccds` (0, 1)."""
    return [(name + (" multiccd" if m else ""), bool(m)) for m in multiccds]


def selected(name, patterns):
    """Whether --configurations' patterns (None: the default) race configuration `name`. The
    default races every configuration but "graspcd multiccd", which only a pattern naming it
    races."""
    if patterns is None:
        return name != "graspcd multiccd"
    return any(fnmatch.fnmatchcase(name, p) for p in patterns)


def record_name(configuration, noslip):
    """A run's record's file name: its configuration (spaces as "_") and noslip value."""
    return f"{configuration.replace(' ', '_')}_noslip{noslip}.jsonl"


def race_rows(graspcd, name, command, scene, records, noslips, multiccd=False):
    """The rows of one of graspcd's configurations, one per noslip value, each run writing its
    record in `records` and judged from it (race_judged.grasp_row), and the first run's
    provenance (its graspcd version and commit) or None."""
    rows, first = [], None
    if multiccd:
        command = command + ["--multiccd"]
    for n in noslips:
        record = os.path.join(records, record_name(name, n))
        r, message, version = race_judged.grasp_row(graspcd, name, command + ["--noslip", str(n)],
                                                    scene, record, n, multiccd)
        if r is None:
            print(f"[race]   {name} noslip {n}: cannot start: {message}", file=sys.stderr)
            rows.append(refused_row(name, n, message, multiccd))
            continue
        first = first or {"graspcd": version}
        log_row(r)
        rows.append(r)
    return rows, first


def log_row(r):
    """The progress line of one judged row."""
    if r["outcome"] == "cannot start":
        print(f"[race]   {r['configuration']} noslip {r['noslip']}: cannot start:"
              f" {r.get('message')}", file=sys.stderr)
        return
    native, wasm = r.get("ms_per_physics_step"), r.get("ms_per_physics_step_wasm")
    cost = (f"{native:.3f} ms per step" if native is not None else
            "no step cost" if wasm is None else f"{wasm:.3f} ms per step (WebAssembly)")
    six = r.get("six_directions") or {}
    tp = r.get("true_penetration_max")
    print(f"[race]   {r['configuration']} noslip {r['noslip']}: {r['outcome']},"
          f" six directions {six.get('held', '-')} of {six.get('of', 6)}, true penetration"
          f" {'-' if tp is None else f'{1000 * tp:.2f}'} mm, {cost}", file=sys.stderr)


def mujoco3_rows(graspcd, name, scene, records, noslips, node, kept_only=False, not_run=None):
    """The rows of one of MuJoCo 3.14's configurations, one per noslip value: the node runner's
    record (made unless it exists in `records`) judged by graspcd judge. With `kept_only`, a
    record not made yet is not made: its configuration and noslip value go to `not_run`. Returns
    the rows and the first judged record's provenance (the judge's graspcd) or None."""
    rows, first = [], None
    for n in noslips:
        record = os.path.join(records, record_name(name, n))
        if kept_only and not (os.path.exists(record)
                              or os.path.exists(race_judged.failed_file(record))):
            print(f"[race]   {name} noslip {n}: no kept record, not run", file=sys.stderr)
            not_run.append({"configuration": name, "noslip": n})
            continue
        r, message, version = race_judged.mujoco3_row(graspcd, name, scene, record, n, node)
        if r is None:
            r = refused_row(name, n, message, True)
            r["simulator"] = race_judged.SIMULATOR
        first = first or version
        log_row(r)
        rows.append(r)
    return rows, first


def row_key(r):
    """What one row races: its configuration and noslip value."""
    return (r["configuration"], r.get("noslip"))


def merge_rows(entry, old_entry, old, file):
    """--merge for a scene raced now and in the merged file `old` (its entry `old_entry`): the
    old rows of configurations and noslip values not raced now are kept, after the new ones, and
    "merged_rows" says where they came from: for each origin, the file, its configurations, its
    rows ([configuration, noslip]) and the provenance of the race that ran them. A row the merged
    file had itself merged keeps the origin that file gave it (its "merged_rows" part: by the
    part's rows, or by configuration for a part written before parts named their rows); the
    others were raced by the merged file's scene (its provenance). So are the old
    decompositions not made now."""
    raced = {row_key(r) for r in entry["rows"]}
    kept = [r for r in old_entry["rows"] if row_key(r) not in raced]
    if not kept:
        return
    entry["rows"].extend(kept)
    # 3.14's rows taken from the merged file bring its note of them (the runs it did not make).
    if any(r["configuration"] in race_judged.MUJOCO3 for r in kept):
        entry["mujoco3"] = old_entry.get("mujoco3")
    for key, d in old_entry.get("decompositions", {}).items():
        entry["decompositions"].setdefault(key, d)

    def origin(r):
        for part in old_entry.get("merged_rows", []):
            if "rows" in part:
                if [r["configuration"], r.get("noslip")] in part["rows"]:
                    return part["file"], part["provenance"]
            elif r["configuration"] in part["configurations"]:
                return part["file"], part["provenance"]
        return (os.path.basename(file),
                old_entry.get("provenance", {"machine": old.get("machine")}))

    parts = {}
    for r in kept:
        where, provenance = origin(r)
        key = (where, json.dumps(provenance, sort_keys=True))
        parts.setdefault(key, {"file": where, "configurations": [], "rows": [],
                               "provenance": provenance})
        parts[key]["rows"].append([r["configuration"], r.get("noslip")])
    for part in parts.values():
        part["configurations"] = sorted({c for c, _ in part["rows"]})
        entry.setdefault("merged_rows", []).append(part)


def engines_available(graspcd):
    """The decomposition engines the executable offers: always "hacd", "vhacd" when `decompose
    --help` names it."""
    done = subprocess.run([graspcd, "decompose", "--help"], capture_output=True, text=True)
    return ["hacd"] + (["vhacd"] if "vhacd" in done.stdout.lower() else [])


def race_mujoco3(args, scene_name, scene, records, noslips, patterns, rows):
    """MuJoCo 3.14's configurations of one scene (those --configurations selects), their rows
    added to `rows`; returns why the scene has none (None when raced) and the first judged
    record's provenance (None without one)."""
    names = [n for n in race_judged.MUJOCO3 if selected(n, patterns)]
    if not names:
        return "not selected (--configurations)", None
    if not race_judged.driven(scene):
        return ("not raced: the scene's hand runs on graspcd's C++ controllers (its pair config"
                " has no \"grasp\" section for the node runner to drive)"), None
    missing = race_judged.mujoco3_missing(args.node)
    if missing:
        print(f"[race] {scene_name}: MuJoCo 3.14 not raced: {missing}", file=sys.stderr)
        return f"not raced: {missing}", None
    not_run, first = [], None
    for name in names:
        print(f"[race] {scene_name}: {name} ({race_judged.SIMULATOR})", file=sys.stderr)
        judged, version = mujoco3_rows(args.graspcd, name, scene, records, noslips, args.node,
                                       args.mujoco3_kept_only, not_run)
        rows.extend(judged)
        first = first or version
    if not_run:
        return {"not_run": not_run,
                "why": "--mujoco3-kept-only: no record of these was kept in --work"}, first
    return None, first


# An absolute path in a command or message: "/" then a name, then at least one more "/NAME",
# starting a word (not the "m/s" of a speed).
ABSOLUTE_PATH = re.compile(r"(?<![\w./])/[A-Za-z0-9_.+-]+(?:/[A-Za-z0-9_.+-]+)+")


def without_machine_paths(value):
    """race.json's strings without this machine's paths: a path inside a checkout of the
    repository from the checkout on ("mjcf/S.xml"), any other absolute path its file's name
    alone (a work folder, an executable, a merged file). Applied to everything written."""
    if isinstance(value, dict):
        return {k: without_machine_paths(v) for k, v in value.items()}
    if isinstance(value, list):
        return [without_machine_paths(v) for v in value]
    if not isinstance(value, str):
        return value

    def short(m):
        path = m.group(0)
        if path.startswith(ROOT + "/"):
            return os.path.relpath(path, ROOT)
        for folder in ("/mjcf/", "/tools/", "/examples/", "/data/"):
            at = path.find(folder)
            if at >= 0:
                return path[at + 1:]
        return os.path.basename(path)
    return ABSOLUTE_PATH.sub(short, value)


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
    parser.add_argument("--merge", action="append", default=[],
                        help="keep this race.json's scenes that are not raced now (repeatable: "
                             "the first file's scene first)")
    parser.add_argument("--noslip", default="0,10",
                        help="MuJoCo's noslip iterations: one run per value (grasp --noslip)")
    parser.add_argument("--engines", default="hacd,vhacd",
                        help="decomposition engines, those the executable offers (hacd, vhacd)")
    parser.add_argument("--vhacd-pieces",
                        help="V-HACD's piece counts for every scene (default: HACD's)")
    parser.add_argument("--multiccd", default="0,1",
                        help="MuJoCo's multi-point convex collision for the native and decomposed"
                             " configurations: 0 without, 1 with (grasp --multiccd), one run each")
    parser.add_argument("--node", default="node",
                        help="node, which runs MuJoCo 3.14's configurations (tools/mujoco3)")
    parser.add_argument("--mujoco3-kept-only", action="store_true",
                        help="judge only MuJoCo 3.14's records kept in --work, run node for none"
                             " (the scene's \"mujoco3\" entry lists those not run)")
    parser.add_argument("--configurations",
                        help="comma-separated configuration names or fnmatch patterns to race"
                             " (default: all but \"graspcd multiccd\")")
    args = parser.parse_args()
    noslips = [int(n) for n in args.noslip.split(",") if n]
    try:
        multiccds = [int(m) for m in args.multiccd.split(",") if m]
    except ValueError:
        multiccds = None
    if not multiccds or any(m not in (0, 1) for m in multiccds):
        fail(f"--multiccd {args.multiccd!r}: give 0, 1 or 0,1")
    patterns = (None if args.configurations is None else
                [p.strip() for p in args.configurations.split(",") if p.strip()])
    offered = engines_available(args.graspcd)
    engines = [e for e in args.engines.split(",") if e in offered]
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
    result = {"machine": machine(), "pieces": pieces, "noslip": noslips, "engines": engines,
              "engines_asked": args.engines.split(","), "protocol": "outcome",
              "multiccd": multiccds, "configurations": patterns,
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
        # Every run's record (graspcd's, rewritten each race; 3.14's, kept and reused).
        records = os.path.join(args.work, "records", scene_name)
        first = None

        def race(route, command):
            # Each configuration of one route (with and without multiccd) that --configurations
            # selects, its rows added to the scene's; the first run's JSON kept for provenance.
            nonlocal first
            multis = [0, 1] if route == "graspcd" else multiccds
            if route == "graspcd" and 1 not in multiccds or route == "graspcd exact":
                multis = [0]
            for name, multiccd in configuration_names(route, multis):
                if not selected(name, patterns):
                    continue
                print(f"[race] {scene_name}: {name}", file=sys.stderr)
                rows, g = race_rows(args.graspcd, name, command, scene, records, noslips,
                                    multiccd)
                entry["rows"].extend(rows)
                first = first or g

        race("graspcd", base)
        race("graspcd exact", base + ["--exact"])
        race("native hull", base + ["--native"])
        entry["mujoco3"], judged = race_mujoco3(args, scene_name, scene, records, noslips,
                                                patterns, entry["rows"])
        # A scene raced only in MuJoCo 3.14: the provenance of the graspcd that judged it.
        first = first or judged
        vhacd_counts = counts if args.vhacd_pieces is None else \
            [int(p) for p in args.vhacd_pieces.split(",") if p]
        if "vhacd" in engines:
            entry["vhacd_pieces"] = vhacd_counts
        for engine in engines:
            for n in (counts if engine == "hacd" else vhacd_counts):
                # --simplify is HACD's (V-HACD voxelizes: its time follows the voxels, not the
                # faces).
                simplified = simplify if engine == "hacd" else None
                suffix = "" if simplified is None else f"_simplify{simplified}"
                tag = "" if engine == "hacd" else f"_{engine}"
                out = os.path.join(args.work, f"{stem}{tag}_{n}{suffix}")
                manifest = os.path.join(out, "decomposition.json")
                name = f"{'decomposed' if engine == 'hacd' else engine}-{n}"
                key = str(n) if engine == "hacd" else f"{engine}-{n}"
                if not any(selected(c, patterns)
                           for c, _ in configuration_names(name, multiccds)):
                    continue
                if not os.path.exists(manifest):
                    print(f"[race] {scene_name}: decompose {stem} into at most {n} with {engine}"
                          + ("" if simplified is None else f" (--simplify {simplified})"),
                          file=sys.stderr)
                    command = [args.graspcd, "decompose", mesh, "--out", out, "--pieces", str(n),
                               "--json"]
                    if engine != "hacd":
                        command += ["--engine", engine]
                    if simplified is not None:
                        command += ["--simplify", str(simplified)]
                    done = subprocess.run(command, capture_output=True, text=True)
                    if done.returncode != 0:
                        lines = done.stderr.strip().splitlines()
                        message = lines[-1] if lines else f"exit {done.returncode}"
                        print(f"[race] {scene_name}: {name}: {message}", file=sys.stderr)
                        entry["decompositions"][key] = {"engine": engine, "error": message}
                        continue
                with open(manifest, encoding="utf-8") as f:
                    d = json.load(f)
                entry["decompositions"][key] = {
                    "engine": engine,
                    "pieces": d["piece_count"], "slabs": d.get("slabs"), "seconds": d["seconds"],
                    "hausdorff": (d.get("hausdorff") or {}).get("distance"),
                    "hausdorff_bound": (d.get("hausdorff") or {}).get("error_bound"),
                    "volume": d.get("volume"),
                    "source_faces": d.get("source_faces"), "simplify": d.get("simplify"),
                    "graspcd": d.get("graspcd", {}).get("commit")}
                race(name, base + ["--decomposed", out])
        if first is None:
            first = {}
        entry["provenance"] = provenance(first, started)
        result["scenes"][scene_name] = entry
    # --merge, first file first: a scene raced now, or in an earlier file, is kept from there.
    for merged in args.merge:
        with open(merged, encoding="utf-8") as f:
            old = json.load(f)
        # Where the scenes taken from it were raced: its command, wall time and load.
        result.setdefault("merged", []).append(
            {"file": os.path.basename(merged), "command": old.get("command"),
             "wall_seconds": old.get("wall_seconds"),
             "load_average": old.get("machine", {}).get("load_average"),
             "load_average_end": old.get("load_average_end"),
             "scenes": [s for s in old["scenes"] if s not in result["scenes"]]})
        for scene_name, entry in old["scenes"].items():
            if scene_name in result["scenes"]:
                merge_rows(result["scenes"][scene_name], entry, old, merged)
                continue
            entry.setdefault("pieces", old["pieces"])
            # A scene of a run before per-scene provenance: the old run's machine and date.
            entry.setdefault("provenance", {"machine": old["machine"]})
            result["scenes"][scene_name] = entry
    result["wall_seconds"] = round(time.time() - race_started, 1)
    result["load_average_end"] = list(os.getloadavg())
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(without_machine_paths(result), f, indent=1)
        f.write("\n")
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
