#!/usr/bin/python3
"""Runs every real-hand scene (mjcf/real_*.xml) and writes report/data/real_models.json.

Per scene: `graspcd grasp --json --exact` REPEATS times (the grasp result with exact contacts
every step, so that every closing step's detection is a query, and the detection time per
closing grasp step of each run: detection_ns_close over the closing steps; the median and min-max
over the runs), then `graspcd validate --json --all-methods` once (per method: checks, agreements
with CGAL, CGAL hits, missed and false collisions, summed over the pairs); when that takes longer
than --timeout seconds (the perceptrons on the Shadow hand's 127 steps take over 10 minutes),
the config's method alone, marked "all_methods": false. Also records the
machine, the commit and the load average before and after (others building on the machine show
there). Needs ../shared/models beside the project: without it, says so and exits 0 writing nothing.

Usage, from the project's root, after building build/graspcd (Release):
    /usr/bin/python3 report/real_models.py [--repeats 3] [--timeout 120] [--graspcd build/graspcd]
        [--out report/data/real_models.json]
report/make_report.py draws the "Real hands and objects" section from the file when it sits
beside study.json.
"""

import argparse
import glob
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_json(cmd, timeout=None):
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        sys.exit(f"real_models.py: {' '.join(cmd)} failed (exit {p.returncode}): "
                 f"{p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ''}")
    return json.loads(p.stdout)


def scene_facts(path):
    """Hand, object file and scale, read from the scene's MJCF text (its include and its mesh)."""
    text = open(path, encoding="utf-8").read()
    hand = re.search(r'<include file="[^"]*/hands/([^/"]+)/([^"]+)"', text)
    mesh = re.search(r'<mesh name="[^"]*" file="([^"]+)" scale="([^" ]+)', text)
    return {
        "hand": f"{hand.group(1)}/{hand.group(2)}" if hand else "?",
        "object": os.path.basename(mesh.group(1)) if mesh else "?",
        "scale": float(mesh.group(2)) if mesh else None,
    }


def machine():
    cpu = "?"
    try:
        for line in open("/proc/cpuinfo", encoding="utf-8"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    osname = platform.platform()
    try:
        for line in open("/etc/os-release", encoding="utf-8"):
            if line.startswith("PRETTY_NAME="):
                osname = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "os": osname}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--graspcd", default="build/graspcd")
    parser.add_argument("--out", default="report/data/real_models.json")
    parser.add_argument("--timeout", type=float, default=120,
                        help="seconds for validate --all-methods per scene before falling back to "
                             "the config's method alone (default 120)")
    args = parser.parse_args()
    models = os.path.join(ROOT, "..", "shared", "models")
    if not os.path.isdir(models):
        print(f"real_models.py: {os.path.normpath(models)} not found: no real scenes to run",
              file=sys.stderr)
        return 0
    exe = args.graspcd
    version = subprocess.run([exe, "--version"], cwd=ROOT, capture_output=True, text=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    out = {"created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
           "commit": commit, "version": version.stdout.strip().splitlines(),
           "machine": machine(), "repeats": args.repeats,
           "loadavg_before": list(os.getloadavg()), "scenes": []}
    for path in sorted(glob.glob(os.path.join(ROOT, "mjcf", "real_*.xml"))):
        scene = os.path.relpath(path, ROOT)
        print(f"real_models.py: {scene}", file=sys.stderr)
        runs = [run_json([exe, "grasp", "--json", "--exact", scene]) for _ in range(args.repeats)]
        per_step = [r["detection_ns_close"] / max(1, len(r["steps"])) for r in runs]
        g = runs[0]
        grasp = {
            "closing_steps": len(g["steps"]),
            "first_contact": g["first_contact"],
            "gripped": g["gripped"], "held": g["held"],
            "object_z_initial": g["object_z_initial"], "object_z_gripped": g["object_z_gripped"],
            "object_z_final": g["object_z_final"], "hold_drift": g["hold_drift"],
            "max_contacts": g["max_contacts"],
            "per_step_ns": {"runs": per_step, "median": statistics.median(per_step),
                            "min": min(per_step), "max": max(per_step)},
            "same_result_every_run": all(r["first_contact"] == g["first_contact"] and
                                         r["held"] == g["held"] for r in runs),
        }
        try:
            v = run_json([exe, "validate", "--json", "--all-methods", scene], args.timeout)
            all_methods = True
        except subprocess.TimeoutExpired:  # the perceptrons can take many minutes: SAT alone
            print(f"real_models.py: {scene}: validate --all-methods over {args.timeout} s; "
                  "the config's method only", file=sys.stderr)
            v = run_json([exe, "validate", "--json", scene])
            all_methods = False
        methods = []
        for m in v["methods"]:
            rows = m["pairs"]
            methods.append({
                "method": m["method"], "pairs": len(rows),
                "checks": sum(r["steps"] for r in rows), "agree": sum(r["agree"] for r in rows),
                "cgal_hits": sum(r["truth_hits"] for r in rows),
                "missed": sum(r["missed"] for r in rows),
                "false": sum(r["false_contacts"] for r in rows),
            })
        out["scenes"].append({"scene": scene, **scene_facts(path), "grasp": grasp,
                              "validate": {"steps": v.get("steps"), "all_methods": all_methods,
                                           "methods": methods}})
    out["loadavg_after"] = list(os.getloadavg())
    os.makedirs(os.path.dirname(os.path.join(ROOT, args.out)), exist_ok=True)
    with open(os.path.join(ROOT, args.out), "w", encoding="utf-8") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print(f"real_models.py: wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
