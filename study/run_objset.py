#!/usr/bin/python3
"""The object-set study: many seeded grasps per object and hand, in every collision route, against
an exact reference.

usage: run_objset.py GRASPCD (--objects DIR | --list FILE) [--grasps N] [--seed S]
                     [--hands robotiq,shadow,project] [--configurations PATTERNS]
                     [--shard I/N] [--workers N] [--out FILE] [--work DIR]
       run_objset.py --merge SHARD.json [SHARD.json ...] --out FILE

Objects. --objects DIR takes every NAME/textured.obj of DIR (the YCB layout; its NAME/pieces/
is the object's published decomposition) and every OBJ or STL file directly in DIR, in metres,
z up. --list FILE names them one a line, `PATH [scale=S] [up=AXIS] [pieces=DIR] [name=NAME]`
(PATH and DIR relative to FILE; '#' starts a comment; scale turns the file's units into metres,
up is the file axis that points up: x, y, z, -x, -y, -z; pieces defaults to PATH's folder's
pieces/ when there is one). Every object is read by `graspcd meshpair` before anything runs: a
list entry that is malformed, names a missing file, or a mesh graspcd refuses, is one line
`FILE:LINE: message` (or `FILE: message`) and exit code 2.

Placements. For each object, hand (--hands; the Robotiq grasps every object, the Shadow hand and
the project's hand those whose start is valid at true size: no --fit) and grasp k < --grasps, the
placement is drawn from a generator seeded by (--seed, object, hand, k): which side is up (the
entry's up axis or its opposite), a yaw uniform in [0, 360) degrees and an offset from the hand's
centre uniform in +-5 mm along each axis across gravity (`grasp --up --yaw --offset`). The plan
(every placement) is recorded, so a run is reproduced from its seed.

Each placement runs, in order (each its own `graspcd grasp` process; grasp() below is the one
place that runs one):
  reference       `grasp --object ... --write-scene WORK/scenes/... --exact --timestep-divisor 4`
                  (study/objset_rates.py: the reference rule); a start it refuses is a skipped
                  placement, counted, and nothing else runs on it; a reference that fails
                  otherwise is recorded with its message, and nothing else runs on it either;
  reference half  the written scene, `--exact --timestep-divisor 2`: the reference's convergence
                  (its held verdict only: the one run without the six-direction test);
  then, with --judge (CGAL's phantom and missed contacts at every closing step; --no-judge
  leaves it out, and the counts with it), each configuration --configurations selects
  (comma-separated names or fnmatch patterns; default every one but MuJoCo 3.14's):
  graspcd         graspcd's contacts as the pair config says (reusing a pair's within 20 um);
  graspcd exact   graspcd's exact contacts every step (--exact);
  native hull, native hull multiccd
                  MuJoCo 2.2 on the object's convex hull (--native), without and with multi-point
                  convex collision (--multiccd);
  published pieces  MuJoCo 2.2 on the object's published decomposition (its pieces/ folder,
                  --decomposed with a manifest the study writes under WORK/pieces/);
  vhacd-16        MuJoCo 2.2 on V-HACD's decomposition into at most 16 pieces (`graspcd decompose
                  --engine vhacd --pieces 16`, cached under WORK/decompositions/);
  3.14 hull, 3.14 sdf, 3.14 flex
                  MuJoCo 3.14 in WebAssembly (node, tools/mujoco3) on the written scene: its hull
                  (multiccd on), its mesh SDF and its rigid flex, as the race runs them
                  (study/race_judged.py); the record kept under WORK/mujoco3/ and judged by
                  `graspcd judge` on the true meshes. Only when --configurations names them (5-40 s
                  of CPU a grasp); a runner that stops with an error counts as cannot start.
Every other run ends with the six-direction test (`grasp --six-directions`: from the held state,
the support gone, the object pulled by its weight along each axis of the hand for 1 s). A run
records its verdict, the directions of the six it held in, the true meshes' penetration into the
hand, the judge's counts, the physics steps, their CPU cost per step, and its cost: the process's
CPU seconds (user + system) and wall seconds.

Scaling out. --shard I/N runs the placements whose index in the plan is I modulo N and writes
them with the plan; --merge joins the N shard files of one plan into one document and refuses,
with one line naming it and exit code 2, a shard missing or given twice, or shards of different
plans. --workers N runs N placements at once (default: the machine's cores). cluster/objset.sbatch
runs the shards as a Slurm array.

Output: --out (default report/out/objset.json): the plan, the machine (cores, load at the start and
the end), the command, the wall time, and one record per placement with its runs; rewritten after
every placement ("complete": false until the last, which --merge refuses). The rates are
study/objset_rates.py's; report/sections/objset.py draws them into REPORT.md. Progress goes to
stderr, one line per placement.
"""
import argparse
import concurrent.futures
import datetime
import fnmatch
import hashlib
import json
import os
import platform
import random
import shlex
import shutil
import subprocess
import sys
import threading
import time

import objset_rates  # study/objset_rates.py, beside this script
import race_judged  # study/race_judged.py
import race_score  # study/race_score.py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HANDS = ("robotiq", "shadow", "project")
AXES = ("x", "y", "z", "-x", "-y", "-z")
# MuJoCo 3.14's configurations (study/race_judged.py): run only when --configurations names them.
MUJOCO3 = ("3.14 hull", "3.14 sdf", "3.14 flex")
DEFAULT_CONFIGURATIONS = ("graspcd", "graspcd exact", "native hull", "native hull multiccd",
                          "published pieces", "vhacd-16")
CONFIGURATIONS = DEFAULT_CONFIGURATIONS + MUJOCO3
OFFSET_M = 0.005
VHACD_PIECES = 16
# Every run but the reference's convergence check ends with the six-direction test.
SIX = ["--six-directions"]


class Refusal(Exception):
    """Bad input: one line, exit code 2."""


def fail(message):
    print(f"run_objset.py: {message}", file=sys.stderr)
    sys.exit(2)


def machine():
    return {"cores": os.cpu_count(), "load_average": list(os.getloadavg()),
            "platform": platform.platform(),
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}


# ---- objects ----

def object_entry(path, name=None, scale=1.0, up="z", pieces=None, where=""):
    if not os.path.isfile(path):
        raise Refusal(f"{where}{path}: no such file")
    if up not in AXES:
        raise Refusal(f"{where}up={up}: give one of {', '.join(AXES)}")
    if not (scale > 0 and scale < 1e3):
        raise Refusal(f"{where}scale={scale}: give a number in (0, 1000)")
    if pieces is None:
        guess = os.path.join(os.path.dirname(path), "pieces")
        pieces = guess if os.path.isdir(guess) else None
    elif not os.path.isdir(pieces):
        raise Refusal(f"{where}pieces={pieces}: no such folder")
    if name is None:
        stem = os.path.splitext(os.path.basename(path))[0]
        name = os.path.basename(os.path.dirname(path)) if stem == "textured" else stem
    return {"name": name, "file": os.path.abspath(path), "scale": scale, "up": up,
            "pieces": None if pieces is None else os.path.abspath(pieces)}


def objects_of_folder(folder):
    if not os.path.isdir(folder):
        raise Refusal(f"{folder}: no such folder")
    found = []
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if os.path.isfile(os.path.join(path, "textured.obj")):
            found.append(object_entry(os.path.join(path, "textured.obj")))
        elif os.path.isfile(path) and name.lower().endswith((".obj", ".stl")):
            found.append(object_entry(path))
    if not found:
        raise Refusal(f"{folder}: no NAME/textured.obj, OBJ or STL file")
    return found


def objects_of_list(list_file):
    try:
        with open(list_file, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise Refusal(f"{list_file}: {e.strerror}") from None
    base = os.path.dirname(os.path.abspath(list_file))
    found = []
    for number, line in enumerate(lines, 1):
        where = f"{list_file}:{number}: "
        words = shlex.split(line, comments=True)
        if not words:
            continue
        fields = {}
        for word in words[1:]:
            key, eq, value = word.partition("=")
            if not eq or key not in ("scale", "up", "pieces", "name") or not value:
                raise Refusal(f"{where}{word!r}: give scale=S, up=AXIS, pieces=DIR or name=NAME")
            fields[key] = value
        try:
            scale = float(fields.get("scale", "1"))
        except ValueError:
            raise Refusal(f"{where}scale={fields['scale']}: not a number") from None
        pieces = fields.get("pieces")
        found.append(object_entry(os.path.join(base, words[0]), fields.get("name"), scale,
                                  fields.get("up", "z"),
                                  None if pieces is None else os.path.join(base, pieces), where))
    if not found:
        raise Refusal(f"{list_file}: no object listed")
    names = [o["name"] for o in found]
    for n in names:
        if names.count(n) > 1:
            raise Refusal(f"{list_file}: object name {n!r} given twice (name=NAME tells apart)")
    return found


def check_meshes(graspcd, objects):
    """Every object read as graspcd reads it (`meshpair` of the mesh with itself, no pose): a
    mesh it refuses is that one line, exit code 2."""
    for o in objects:
        done = subprocess.run([graspcd, "meshpair", o["file"], o["file"], "--scale",
                               repr(o["scale"]), "--poses", "-"], input="", capture_output=True,
                              text=True)
        if done.returncode != 0:
            lines = [x for x in done.stderr.strip().splitlines() if not x.startswith("warning:")]
            raise Refusal(lines[-1] if lines else f"{o['file']}: exit {done.returncode}")


# ---- the plan ----

def opposite(axis):
    return axis[1:] if axis.startswith("-") else "-" + axis


def placement(seed, obj, hand, k):
    """Placement k of obj in hand: drawn from a generator seeded by (seed, object, hand, k)."""
    digest = hashlib.sha256(f"{seed}/{obj['name']}/{hand}/{k}".encode()).digest()
    rng = random.Random(int.from_bytes(digest[:8], "little"))
    up = obj["up"] if rng.random() < 0.5 else opposite(obj["up"])
    yaw = round(rng.uniform(0, 360), 3)
    offset = [round(rng.uniform(-OFFSET_M, OFFSET_M), 5) for _ in range(2)]
    return {"object": obj["name"], "hand": hand, "k": k, "up": up, "yaw": yaw, "offset": offset}


def make_plan(objects, hands, grasps, seed, configurations, judge=True):
    placements = [placement(seed, o, h, k) for o in objects for h in hands for k in range(grasps)]
    for i, p in enumerate(placements):
        p["index"] = i
    plan = {"seed": seed, "grasps": grasps, "hands": hands, "configurations": configurations,
            "judge": judge, "objects": objects, "placements": placements}
    key = json.dumps({k: plan[k] for k in ("seed", "grasps", "hands", "configurations", "judge")}
                     | {"objects": [o["name"] for o in objects], "placements": placements},
                     sort_keys=True)
    plan["id"] = hashlib.sha256(key.encode()).hexdigest()[:16]
    return plan


def parse_shard(text):
    try:
        i, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise Refusal(f"--shard {text!r}: give I/N, e.g. 0/4") from None
    if n < 1 or not 0 <= i < n:
        raise Refusal(f"--shard {text!r}: I runs from 0 to N-1")
    return i, n


def shard_of(placements, shard):
    i, n = shard
    return [p for p in placements if p["index"] % n == i]


# ---- one grasp ----

def grasp(graspcd, args):
    """One `graspcd grasp` process (the one place the study runs a grasp): (its JSON, None, cost)
    or (None, the refusal's line, cost); cost is {cpu_s, wall_s} of the process."""
    code, stdout, stderr, cost = race_judged.run_measured([graspcd, "grasp", *args, "--json"])
    if code != 0:
        lines = [x for x in stderr.strip().splitlines() if not x.startswith("warning:")]
        return None, (lines[-1] if lines else f"exit {code}"), cost
    return json.loads(stdout), None, cost


def run_record(g, cost):
    tp = g.get("true_penetration") or {}
    judge = g.get("judge") or {}
    return {"outcome": race_score.outcome(g), "held": g["held"], "gripped": g["gripped"],
            "reason": g.get("reason"), "tilt_final_deg": g.get("tilt_final_deg"),
            "hand_penetration": tp.get("hand_max"), "penetration": tp.get("max"),
            # The object's mesh not closed (an open hand mesh is the hand's, in every run).
            "partial": any("(the object)" in x for x in tp.get("partial") or []),
            "phantom": judge.get("phantom"), "missed": judge.get("missed"),
            "closing_steps": judge.get("steps"),
            "physics_steps": g.get("physics_steps"), "timestep": g.get("timestep"),
            "ms_per_physics_step": g.get("ms_per_physics_step"),
            "cpu_ms_per_physics_step": g.get("cpu_ms_per_physics_step"),
            # The directions of the six-direction test the object held in (of 6; None when the
            # run had no test).
            "six_directions": (g.get("six_directions") or {}).get("held"), **cost}


def mujoco3_run(graspcd, name, scene, record):
    """MuJoCo 3.14's run of a placement's written scene in configuration `name`: the node runner's
    record (kept at `record`, and judged again, not run again, when it exists), judged by `graspcd
    judge` on the true meshes (study/race_judged.py, as the race's rows). Its cost is the node
    process's (the judge's is the measure's, not the simulator's); its step cost WebAssembly's
    CPU ms per mj_step, in its own field. A runner that stops without a record (an error MuJoCo
    3.14 raises, as "collision function returned 11 contacts") counts as cannot start, its
    message kept."""
    row, message, _ = race_judged.mujoco3_row(graspcd, name, scene, record, 0)
    summary = race_judged.summary_of(record) or {}
    cost = summary.get("process") or {"cpu_s": None, "wall_s": None}
    if row is None:
        return refused_record(message, cost)
    if row["outcome"] == "cannot start":
        return refused_record(row.get("message") or "MuJoCo 3.14 cannot start", cost)
    tp = row.get("true_penetration") or {}
    return {"outcome": row["outcome"], "held": row["held"], "gripped": row["gripped"],
            "reason": row.get("reason"), "tilt_final_deg": row.get("tilt_final_deg"),
            "hand_penetration": tp.get("hand_max"), "penetration": tp.get("max"),
            "partial": any("(the object)" in x for x in tp.get("partial") or []),
            "phantom": row.get("phantom"), "missed": row.get("missed"),
            "closing_steps": row.get("closing_steps"),
            "physics_steps": summary.get("physics_steps"), "timestep": None,
            "ms_per_physics_step": None, "cpu_ms_per_physics_step": None,
            "wasm_cpu_ms_per_physics_step": row.get("ms_per_physics_step_wasm"),
            "six_directions": (row.get("six_directions") or {}).get("held"), **cost}


def refused_record(message, cost):
    """A run that did not end: it could not start, or it went non-finite after the start (an
    error that stops the grasp: objset_rates.NON_FINITE, started and not held)."""
    return {"outcome": (objset_rates.NON_FINITE if "went non-finite" in message else
                        "cannot start"), "message": message, "held": False, **cost}


def is_start_refusal(message):
    return "the start state is not valid" in message or "cannot start" in message


# ---- decompositions ----

_locks = {}
_locks_guard = threading.Lock()


def lock_for(key):
    with _locks_guard:
        return _locks.setdefault(key, threading.Lock())


def published_pieces(obj, work):
    """A decomposition folder for the object's published pieces: a manifest naming them (the
    format `graspcd decompose` writes, grasp --decomposed reads), written under WORK/pieces/."""
    folder = os.path.join(work, "pieces", obj["name"])
    manifest = os.path.join(folder, "decomposition.json")
    with lock_for(manifest):
        if not os.path.exists(manifest):
            os.makedirs(folder, exist_ok=True)
            files = sorted((f for f in os.listdir(obj["pieces"])
                            if f.lower().endswith((".stl", ".obj"))),
                           key=lambda f: (len(f), f))
            doc = {"source": os.path.basename(obj["file"]), "engine": "published",
                   "piece_count": len(files),
                   "pieces": [{"file": os.path.join(obj["pieces"], f)} for f in files]}
            with open(manifest + ".tmp", "w", encoding="utf-8") as f:
                json.dump(doc, f, indent=1)
            os.replace(manifest + ".tmp", manifest)
    return folder


def vhacd(graspcd, obj, work):
    """V-HACD's decomposition of the object into at most 16 pieces, cached under WORK."""
    folder = os.path.join(work, "decompositions", f"{obj['name']}_vhacd_{VHACD_PIECES}")
    manifest = os.path.join(folder, "decomposition.json")
    with lock_for(manifest):
        if not os.path.exists(manifest):
            tmp = folder + f".tmp{os.getpid()}"
            done = subprocess.run([graspcd, "decompose", obj["file"], "--out", tmp, "--pieces",
                                   str(VHACD_PIECES), "--engine", "vhacd", "--scale",
                                   repr(obj["scale"]), "--json"], capture_output=True, text=True)
            if done.returncode != 0:
                lines = done.stderr.strip().splitlines()
                return None, lines[-1] if lines else f"exit {done.returncode}"
            if os.path.exists(manifest):  # made meanwhile by another process: keep that one
                shutil.rmtree(tmp)
            else:
                shutil.rmtree(folder, ignore_errors=True)  # a decomposition left unfinished
                os.rename(tmp, folder)
    return folder, None


# ---- one placement ----

def selected(name, patterns):
    return patterns is None or any(fnmatch.fnmatchcase(name, p) for p in patterns)


def run_placement(graspcd, plan, p, work, judge=True):
    obj = next(o for o in plan["objects"] if o["name"] == p["object"])
    scene_dir = os.path.join(work, "scenes", f"{p['object']}-{p['hand']}-{p['k']}")
    object_args = ["--object", obj["file"], "--hand", p["hand"], "--up", p["up"], "--yaw",
                   repr(p["yaw"]), "--offset", *(repr(x) for x in p["offset"])]
    if obj["scale"] != 1:
        object_args += ["--scale", repr(obj["scale"])]
    record = dict(p, runs={})
    g, message, cost = grasp(graspcd, object_args + ["--write-scene", scene_dir, "--force",
                                                     *objset_rates.reference_options(), *SIX])
    if g is None:
        if is_start_refusal(message):
            record.update(skipped=True, message=message)
        else:
            # The reference failed (e.g. the simulation went non-finite): recorded with its
            # message, and nothing to compare the configurations with.
            record["runs"][objset_rates.REFERENCE] = refused_record(message, cost)
        return record
    record["runs"][objset_rates.REFERENCE] = run_record(g, cost)
    stem = os.path.splitext(os.path.basename(obj["file"]))[0]
    scene = os.path.join(scene_dir, stem + ".xml")
    routes = [(objset_rates.REFERENCE_HALF,
               objset_rates.reference_options(objset_rates.REFERENCE_HALF_DIVISOR))]
    judged = SIX + (["--judge"] if judge else [])
    routes += [("graspcd", judged), ("graspcd exact", judged + ["--exact"]),
               ("native hull", judged + ["--native"]),
               ("native hull multiccd", judged + ["--native", "--multiccd"])]
    chosen = plan["configurations"]
    for name, extra in routes:
        if name == objset_rates.REFERENCE_HALF or name in chosen:
            record["runs"][name] = one_run(graspcd, [scene, *extra])
    if "published pieces" in chosen and obj["pieces"]:
        folder = published_pieces(obj, work)
        record["runs"]["published pieces"] = one_run(
            graspcd, [scene, *judged, "--decomposed", folder])
    if f"vhacd-{VHACD_PIECES}" in chosen:
        folder, message = vhacd(graspcd, obj, work)
        record["runs"][f"vhacd-{VHACD_PIECES}"] = (
            refused_record(message, {"cpu_s": None, "wall_s": None}) if folder is None else
            one_run(graspcd, [scene, *judged, "--decomposed", folder]))
    for name in MUJOCO3:
        if name in chosen:
            record["runs"][name] = mujoco3_run(
                graspcd, name, scene,
                os.path.join(work, "mujoco3", f"{p['object']}-{p['hand']}-{p['k']}-"
                             f"{race_judged.MUJOCO3[name]}.jsonl"))
    return record


def one_run(graspcd, args):
    g, message, cost = grasp(graspcd, args)
    return refused_record(message, cost) if g is None else run_record(g, cost)


# ---- merge ----

def merge(files):
    docs = []
    for path in files:
        try:
            with open(path, encoding="utf-8") as f:
                docs.append((path, json.load(f)))
        except (OSError, json.JSONDecodeError) as e:
            raise Refusal(f"{path}: {getattr(e, 'strerror', None) or e}") from None
    first = docs[0][1]
    n = first["shard"][1]
    seen = {}
    for path, d in docs:
        if d["plan"]["id"] != first["plan"]["id"] or d["shard"][1] != n:
            raise Refusal(f"{path}: a shard of another plan or split (plan {d['plan']['id']}, "
                          f"{d['shard'][1]} shards; {docs[0][0]}: plan {first['plan']['id']}, "
                          f"{n} shards)")
        i = d["shard"][0]
        if i in seen:
            raise Refusal(f"{path}: shard {i} of {n} given twice (also {seen[i]})")
        seen[i] = path
        if not d.get("complete", False):
            raise Refusal(f"{path}: shard {i} of {n} is not complete "
                          f"({len(d['placements'])} of {d.get('planned')} placements)")
    for i in range(n):
        if i not in seen:
            raise Refusal(f"shard {i} of {n} (objset.shard-{i}-of-{n}.json) is missing")
    placements = sorted((p for _, d in docs for p in d["placements"]), key=lambda p: p["index"])
    if [p["index"] for p in placements] != list(range(len(first["plan"]["placements"]))):
        raise Refusal(f"{docs[0][0]}: the shards do not hold every placement of the plan once")
    out = dict(first, shard=[0, 1], placements=placements, merged_from=n,
               shards=[{"file": os.path.basename(p), "machine": d["machine"],
                        "wall_s": d["wall_s"], "cpu_s": d["cpu_s"], "workers": d["workers"]}
                       for p, d in docs])
    out["wall_s"] = max(d["wall_s"] for _, d in docs)
    out["cpu_s"] = round(sum(d["cpu_s"] for _, d in docs), 1)
    return out


def write(path, doc):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(path + ".tmp", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="\n".join(__doc__.split("\n")[6:]))
    parser.add_argument("graspcd", nargs="?")
    parser.add_argument("--objects", help="a folder of objects (NAME/textured.obj, OBJ, STL)")
    parser.add_argument("--list", help="a list of objects: PATH [scale=S] [up=AXIS] [pieces=DIR]")
    parser.add_argument("--only", help="comma-separated object names: these of the set only"
                        " (their placements are those of the whole set's plan)")
    parser.add_argument("--grasps", type=int, default=20, help="placements per object and hand")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--hands", default=",".join(HANDS))
    parser.add_argument("--configurations", help="names or fnmatch patterns of "
                        + ", ".join(CONFIGURATIONS) + " (default: all but MuJoCo 3.14's, which"
                        " node runs at 5-40 s of CPU a grasp; '*' adds them)")
    parser.add_argument("--no-judge", action="store_true",
                        help="the configurations without --judge: no phantom and missed contacts"
                        " (the judge is about 0.3 s of CPU of a grasp of a 16k-face mesh)")
    parser.add_argument("--shard", help="I/N: the placements whose index is I modulo N")
    parser.add_argument("--workers", type=int, default=os.cpu_count())
    parser.add_argument("--merge", nargs="+", metavar="SHARD", help="join shard files")
    parser.add_argument("--out", default=os.path.join(ROOT, "report/out/objset.json"))
    parser.add_argument("--work", help="scenes and decompositions (default: OUT's folder/objset)")
    args = parser.parse_args()
    started = time.time()
    try:
        if args.merge:
            doc = merge(args.merge)
            write(args.out, doc)
            print(f"wrote {args.out} ({len(doc['placements'])} placements from "
                  f"{doc['merged_from']} shards)", file=sys.stderr)
            return
        if not args.graspcd:
            raise Refusal("give the graspcd executable (or --merge)")
        if bool(args.objects) == bool(args.list):
            raise Refusal("give --objects DIR or --list FILE")
        hands = [h for h in args.hands.split(",") if h]
        for h in hands:
            if h not in HANDS:
                raise Refusal(f"--hands: {h!r} is not one of {', '.join(HANDS)}")
        if args.grasps < 1 or args.workers < 1:
            raise Refusal("--grasps and --workers take a positive number")
        patterns = (None if args.configurations is None else
                    [p.strip() for p in args.configurations.split(",") if p.strip()])
        configurations = ([c for c in CONFIGURATIONS if selected(c, patterns)] if patterns
                          is not None else list(DEFAULT_CONFIGURATIONS))
        if not configurations:
            raise Refusal(f"--configurations {args.configurations!r}: selects none of "
                          + ", ".join(CONFIGURATIONS))
        if any(c in MUJOCO3 for c in configurations):
            why = race_judged.mujoco3_missing()
            if why is not None:
                raise Refusal(f"--configurations {args.configurations!r}: MuJoCo 3.14's runs"
                              f" cannot run here: {why}")
        shard = parse_shard(args.shard) if args.shard else (0, 1)
        objects = objects_of_folder(args.objects) if args.objects else objects_of_list(args.list)
        if args.only:
            names = [n for n in args.only.split(",") if n]
            for n in names:
                if n not in [o["name"] for o in objects]:
                    raise Refusal(f"--only: no object {n!r} in the set")
            objects = [o for o in objects if o["name"] in names]
        check_meshes(args.graspcd, objects)
        plan = make_plan(objects, hands, args.grasps, args.seed, configurations,
                         not args.no_judge)
        mine = shard_of(plan["placements"], shard)
        out = args.out
        if args.shard:
            base, ext = os.path.splitext(out)
            out = f"{base}.shard-{shard[0]}-of-{shard[1]}{ext}"
        work = args.work or os.path.join(os.path.dirname(os.path.abspath(args.out)), "objset")
        doc = {"plan": plan, "configurations": [objset_rates.REFERENCE,
                                                objset_rates.REFERENCE_HALF, *configurations],
               "shard": list(shard), "workers": args.workers, "machine": machine(),
               "command": [os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:]}
        cpu0 = os.times()
        records = []
        doc["complete"] = False
        doc["planned"] = len(mine)
        with concurrent.futures.ThreadPoolExecutor(args.workers) as pool:
            futures = [pool.submit(run_placement, args.graspcd, plan, p, work,
                                   not args.no_judge) for p in mine]
            for n, future in enumerate(concurrent.futures.as_completed(futures), 1):
                try:
                    r = future.result()
                except Refusal:
                    pool.shutdown(cancel_futures=True)
                    raise
                records.append(r)
                verdicts = ("skipped: " + r["message"] if r.get("skipped") else ", ".join(
                    f"{k} {v['outcome']}" for k, v in r["runs"].items()))
                print(f"[objset] {n}/{len(mine)} {r['object']} {r['hand']} #{r['k']} "
                      f"({time.time() - started:.0f} s): {verdicts}", file=sys.stderr,
                      flush=True)
                # The document so far, after every placement (complete: false until the end).
                doc["placements"] = sorted(records, key=lambda r: r["index"])
                doc["wall_s"] = round(time.time() - started, 1)
                write(out, doc)
        cpu1 = os.times()
        doc["placements"] = sorted(records, key=lambda r: r["index"])
        doc["wall_s"] = round(time.time() - started, 1)
        doc["cpu_s"] = round(cpu1.children_user + cpu1.children_system
                             - cpu0.children_user - cpu0.children_system, 1)
        doc["load_average_end"] = list(os.getloadavg())
        doc["complete"] = True
        write(out, doc)
        print(f"wrote {out}", file=sys.stderr)
    except Refusal as e:
        fail(str(e))


if __name__ == "__main__":
    main()
