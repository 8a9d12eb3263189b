#!/usr/bin/python3
"""report/compare_outputs.py: what it removes (timings, the machine, the provenance envelope, empty
warnings, checkout paths, also inside a message) and what it must still see (any answer, a missing
file, a warning, a message naming another file or worded otherwise).
Run by ctest as compare_outputs_test; exit 0 when every check holds."""

import copy
import json
import subprocess
import sys
import tempfile
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "report" / "compare_outputs.py"

BASE = {
    "graspcd": {"version": "0.1.0", "commit": "abc", "dirty": False},
    "warnings": [],
    "created": "2026-11-24T00:00:00Z",
    "machine": {"cores": 2},
    "scene": "/home/a/graspcd/mjcf/example1.xml",
    "methods": [{"method": "sat", "missed": 0, "median_ms": 1.5, "repeats_ms": [1, 2],
                 "tester_seconds": 0.1, "ms_per_physics_step": 0.1}],
}


def compare(before, after):
    with tempfile.TemporaryDirectory() as d:
        a, b = Path(d) / "a", Path(d) / "b"
        for folder, docs in ((a, before), (b, after)):
            folder.mkdir()
            for name, doc in docs.items():
                (folder / name).write_text(json.dumps(doc))
        r = subprocess.run([sys.executable, str(SCRIPT), str(a), str(b)], capture_output=True,
                           text=True, check=False)
        return r.returncode, r.stdout


def main():
    failures = []

    checks = 0

    def check(what, got, want):
        nonlocal checks
        checks += 1
        if got != want:
            failures.append(f"{what}: exit {got}, expected {want}")

    same = copy.deepcopy(BASE)
    same["graspcd"] = {"version": "0.2.0", "commit": "def-dirty", "dirty": True}
    same["created"] = "2026-11-25T00:00:00Z"
    same["machine"] = {"cores": 64}
    same["scene"] = "/tmp/clone/mjcf/example1.xml"
    same["methods"][0].update(median_ms=9.0, repeats_ms=[9, 9, 9], tester_seconds=3.0,
                             ms_per_physics_step=0.4)
    check("timings, machine, provenance and checkout path ignored",
          compare({"x.json": BASE}, {"x.json": same})[0], 0)

    answer = copy.deepcopy(BASE)
    answer["methods"][0]["missed"] = 1
    code, out = compare({"x.json": BASE}, {"x.json": answer})
    check("a changed answer is a difference", code, 1)
    if "/methods[0]/missed" not in out:
        failures.append("the difference is not named by its JSON path: " + out)

    warned = copy.deepcopy(BASE)
    warned["warnings"] = [{"code": "mesh_open", "message": "m", "count": 1}]
    check("a new warning is a difference", compare({"x.json": BASE}, {"x.json": warned})[0], 1)
    check("a missing file is a difference", compare({"x.json": BASE, "y.json": BASE},
                                                    {"x.json": BASE})[0], 1)
    r = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, check=False)
    check("no arguments", r.returncode, 2)

    # A command's stderr (--run's NAME.run.json): the checkout's place is left out of a message,
    # the message itself is not.
    run = {"command": ["validate"], "exit_code": 2,
           "stderr": ["/home/a/graspcd/mjcf/example1.xml:1: template scene: no body"]}
    moved = copy.deepcopy(run)
    moved["stderr"] = ["/tmp/clone/mjcf/example1.xml:1: template scene: no body"]
    check("a message from another checkout",
          compare({"x.run.json": run}, {"x.run.json": moved})[0], 0)
    renamed = copy.deepcopy(run)
    renamed["stderr"] = ["/tmp/graspcd-object-Ab12Cd/scene.xml:1: template scene: no body"]
    check("a message naming another file is a difference",
          compare({"x.run.json": run}, {"x.run.json": renamed})[0], 1)
    worded = copy.deepcopy(run)
    worded["stderr"] = ["/home/a/graspcd/mjcf/example1.xml:1: template scene: no <body>"]
    check("a message worded otherwise is a difference",
          compare({"x.run.json": run}, {"x.run.json": worded})[0], 1)

    for f in failures:
        print("FAIL " + f)
    print(f"{checks - len(failures)} of {checks} checks hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
