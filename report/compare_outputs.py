#!/usr/bin/python3
"""Are two runs' answers the same? Compares the JSON that graspcd wrote in two folders (or two
files), after removing what a run may change without changing an answer: timings, the machine, the
build and the provenance envelope.

    /usr/bin/python3 report/compare_outputs.py BEFORE AFTER
    /usr/bin/python3 report/compare_outputs.py --run GRASPCD OUT

--run writes the answers a change must keep into OUT with the executable GRASPCD: `study --quick`
(OUT/study/), `stress --quick --json` (OUT/stress.json), `validate --json` of example1,
example3, hand_boxes and hand_triangles (OUT/validate_SCENE.json) and `grasp --json` of
example1-3, hand_triangles and real_robotiq_cup (OUT/grasp_SCENE.json; the Robotiq scene includes
the hand of ../shared/models). Then the object workflow on meshes of its own, written into
OUT/objects/ (the README's block, 60 x 30 x 30 mm, and a 30 mm cube whose faces point inward,
which a warning names), each command run from OUT/objects/ with relative paths, so that its
messages name the files alike in every run:
  - `grasp --object block.obj --scale 0.001 --up x --json` in the project's hand and with
    `--hand robotiq` (OUT/grasp_object_project.json, OUT/grasp_object_robotiq.json; both hold it);
  - `validate --objects set --scale 0.001 --up x --json` on the folder of both meshes
    (OUT/validate_objects.json);
  - two refusals: a missing mesh file, and the block at three times its size, which penetrates a
    finger of the project's hand at the start (exit code 2, one line on stderr);
each with its command, exit code and stderr in OUT/NAME.run.json (the JSON of stdout only when the
command succeeded). Run it with the executable before and after a change, then compare the two
folders. --run's exit code is 2 when a command of the first group fails, 1 when a case of the
object workflow exits otherwise than expected (its files are written all the same), else 0.

BEFORE and AFTER are folders (every *.json below BEFORE is compared with the file of the same
relative path below AFTER; a file missing from AFTER is a difference) or two JSON files. Removed
before comparing, at any depth:
  - timings: keys ending in _ms, _ns, _us, seconds or _wall_ms, keys starting with ms_per_
    (grasp's ms_per_physics_step), and lists named repeats_ms or step_ns_median;
    "detection_ns"-style counters of time; a grasp's "cost" (CPU and wall seconds per part);
  - where and when it ran: "created", "machine", "build", "jobs";
  - provenance: the envelope's "graspcd" object and its "warnings" array when empty (docs/design.md,
    "The command line");
  - the checkout's place: in any string, the path up to a folder "mjcf/" or "data/" is left out
    ("/home/a/graspcd/mjcf/example1.xml" becomes "mjcf/example1.xml"; two checkouts in different
    places write the same scene). Nothing else in a message is rewritten: a temporary folder
    named in one would be a difference.
Numbers are compared exactly. Prints one line per difference (file, JSON path, both values) and
a closing "N files compared, M differ" line; exit code 0 when every file matches, 1 otherwise, 2
for bad arguments.
"""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

TIMING_KEY = re.compile(
    r"(_ms|_ns|_us|seconds|_wall_ms|^repeats_ms|^step_ns_median|_ns_.*|^ms_per_.*)$")
DROPPED_KEYS = {"created", "machine", "build", "jobs", "graspcd", "cost"}
CHECKOUT_PATH = re.compile(r"[^\s'\"]*/(mjcf|data)/")


def normalise(value, top=False):
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if k in DROPPED_KEYS or TIMING_KEY.search(k):
                continue
            if top and k == "warnings" and v == []:
                continue
            out[k] = normalise(v)
        return out
    if isinstance(value, list):
        return [normalise(v) for v in value]
    if isinstance(value, str):
        return CHECKOUT_PATH.sub(r"\1/", value)
    return value


def diff(a, b, path, out, limit=20):
    if len(out) >= limit:
        return
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                out.append(f"{path}/{k}: {'missing before' if k not in a else 'missing after'}")
            else:
                diff(a[k], b[k], f"{path}/{k}", out, limit)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} entries before, {len(b)} after")
        for i, (x, y) in enumerate(zip(a, b)):
            diff(x, y, f"{path}[{i}]", out, limit)
    elif a != b or type(a) is not type(b):
        out.append(f"{path}: {json.dumps(a)[:80]} before, {json.dumps(b)[:80]} after")


def load(path):
    with open(path, encoding="utf-8") as f:
        return normalise(json.load(f), top=True)


VALIDATED_SCENES = ("example1", "example3", "hand_boxes", "hand_triangles")
GRASPED_SCENES = ("example1", "example2", "example3", "hand_triangles", "real_robotiq_cup")


def box_obj(x, y, z, inward=False):
    """An OBJ box of half-sizes x, y, z centred on the origin, its faces outward (or inward)."""
    corners = "".join(f"v {sx * x:g} {sy * y:g} {sz * z:g}\n"
                      for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1))
    faces = ((1, 3, 2), (2, 3, 4), (5, 6, 7), (6, 8, 7), (1, 2, 5), (2, 6, 5), (3, 7, 4), (4, 7, 8),
             (1, 5, 3), (3, 5, 7), (2, 4, 6), (4, 8, 6))
    return corners + "".join(f"f {a} {c} {b}\n" if inward else f"f {a} {b} {c}\n"
                             for a, b, c in faces)


# The object workflow's cases, run in OUT/objects/: (name, arguments, whether stdout is JSON, the
# exit code expected).
PLACED = ["--scale", "0.001", "--up", "x"]
OBJECT_CASES = [
    ("grasp_object_project", ["grasp", "--object", "block.obj", *PLACED, "--json"], True, 0),
    ("grasp_object_robotiq",
     ["grasp", "--object", "block.obj", *PLACED, "--hand", "robotiq", "--json"], True, 0),
    ("validate_objects", ["validate", "--objects", "set", *PLACED, "--json"], True, 0),
    ("refused_missing_mesh", ["grasp", "--object", "nowhere.obj", *PLACED], False, 2),
    ("refused_penetrating_start", ["grasp", "--object", "block.obj", "--scale", "0.003"], False,
     2),
]
# The README's block (millimetres, long side along x), and a cube with its faces inward.
OBJECT_FILES = {"block.obj": box_obj(30, 15, 15), "set/block.obj": box_obj(30, 15, 15),
                "set/inside_out_cube.obj": box_obj(15, 15, 15, inward=True)}


def run_object_cases(graspcd, out):
    """The object workflow's cases (OBJECT_CASES); returns an exit code."""
    folder = out / "objects"
    for name, text in OBJECT_FILES.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text, encoding="utf-8")
    unexpected = 0
    for name, args, json_out, expected in OBJECT_CASES:
        print(f"running {' '.join(args[:3])} ({name})", file=sys.stderr)
        r = subprocess.run([graspcd, *args], cwd=folder, capture_output=True, text=True,
                           check=False)
        if r.returncode != expected:
            unexpected += 1
            print(f"{' '.join(args)}: exit code {r.returncode}, expected {expected}\n{r.stderr}",
                  file=sys.stderr)
        if json_out and r.returncode == 0:
            (out / f"{name}.json").write_text(r.stdout, encoding="utf-8")
        run = {"command": args, "exit_code": r.returncode, "stderr": r.stderr.splitlines()}
        (out / f"{name}.run.json").write_text(json.dumps(run, indent=1) + "\n", encoding="utf-8")
    return 1 if unexpected else 0


def run_outputs(graspcd, out):
    """Runs the commands whose answers a refactoring must keep; returns an exit code."""
    graspcd = os.path.abspath(graspcd)
    mjcf = Path(__file__).resolve().parent.parent / "mjcf"
    out = Path(out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    runs = [([graspcd, "study", "--quick", "--out", str(out / "study")], None),
            ([graspcd, "stress", "--quick", "--json"], out / "stress.json")]
    for scene in VALIDATED_SCENES:
        runs.append(([graspcd, "validate", str(mjcf / f"{scene}.xml"), "--json",
                      "--out", str(out / "validate_out")], out / f"validate_{scene}.json"))
    for scene in GRASPED_SCENES:
        runs.append(([graspcd, "grasp", str(mjcf / f"{scene}.xml"), "--json"],
                     out / f"grasp_{scene}.json"))
    for command, stdout_file in runs:
        print("running " + " ".join(command[1:3]), file=sys.stderr)
        with open(stdout_file, "w", encoding="utf-8") if stdout_file else open(
                os.devnull, "w", encoding="utf-8") as stdout:
            rc = subprocess.run(command, stdout=stdout, check=False).returncode
        if rc != 0:
            print(f"{' '.join(command)}: exit code {rc}", file=sys.stderr)
            return 2
    return run_object_cases(graspcd, out)


def main(argv):
    if len(argv) == 4 and argv[1] == "--run":
        return run_outputs(argv[2], argv[3])
    if len(argv) != 3:
        print("usage: compare_outputs.py BEFORE AFTER | --run GRASPCD OUT", file=sys.stderr)
        return 2
    before, after = Path(argv[1]), Path(argv[2])
    if before.is_dir() and after.is_dir():
        pairs = [(p, after / p.relative_to(before)) for p in sorted(before.rglob("*.json"))]
    elif before.is_file() and after.is_file():
        pairs = [(before, after)]
    else:
        print(f"{argv[1]}, {argv[2]}: need two folders or two files", file=sys.stderr)
        return 2
    differing = 0
    for b, a in pairs:
        lines = []
        if not a.exists():
            lines.append("missing after")
        else:
            diff(load(b), load(a), "", lines)
        if lines:
            differing += 1
            for line in lines:
                print(f"{b.name}: {line}")
    print(f"{len(pairs)} files compared, {differing} differ")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
