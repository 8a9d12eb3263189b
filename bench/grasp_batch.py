#!/usr/bin/env python3
"""What a grasp costs: one process per grasp against the batch runner (graspcd grasp --object
FILE --placements N), graspcd's default beside MuJoCo 2.2's hull (--native), and two workers.

Each figure is the median over --runs runs of the CPU seconds the processes used (user + system,
from os.wait4), so that a loaded machine's waiting does not count; wall seconds are printed
beside. Grasps per minute = grasped placements * 60 / CPU seconds. The parts (scene, compile,
trees, placement, start check, physics, true penetration, write) come from the batch's JSON Lines
("cost", docs/objects.md). State the machine's load (uptime) beside the numbers.

  bench/grasp_batch.py --graspcd build/graspcd \\
      --object ../shared/models/objects/ycb/005_tomato_soup_can/textured.obj --hand robotiq \\
      --up y --yaw 0 --placements 8 --runs 5
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time


def run(cmd):
    """Runs cmd; returns (stdout, CPU seconds of the child, wall seconds)."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.monotonic() - start
    if proc.returncode not in (0, 1):
        sys.exit(f"{' '.join(cmd)}: exit code {proc.returncode}")
    return out.decode(), usage.ru_utime + usage.ru_stime, wall


def batch_lines(out):
    lines = [json.loads(line) for line in out.splitlines() if line.strip()]
    return [l for l in lines if l["outcome"] != "summary"], lines[-1]


def parts_of(lines):
    """The summed CPU seconds per part of the grasped lines."""
    total = {}
    for line in lines:
        for key, value in line["cost"]["parts"].items():
            total[key] = total.get(key, 0.0) + value["cpu_s"]
    return total


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--graspcd", default="build/graspcd")
    ap.add_argument("--object", required=True)
    ap.add_argument("--hand", default="robotiq")
    ap.add_argument("--up")
    ap.add_argument("--yaw")
    ap.add_argument("--placements", type=int, default=8)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--single", type=int, default=3,
                    help="grasps run one process each (the first placements of the batch)")
    ap.add_argument("--today",
                    help="another graspcd (e.g. a build of an earlier commit) whose one process "
                    "per grasp is the baseline: --up/--yaw only, no offset")
    ap.add_argument("--workers", action="store_true",
                    help="also two batches at once (two workers) against one")
    args = ap.parse_args()

    base = [args.graspcd, "grasp", "--object", args.object, "--hand", args.hand]
    fixed = []
    if args.up:
        fixed += ["--up", args.up]
    if args.yaw:
        fixed += ["--yaw", args.yaw]
    batch = base + fixed + ["--placements", str(args.placements), "--seed", str(args.seed),
                            "--json"]
    results = {}
    for name, extra in (("graspcd default", []), ("MuJoCo 2.2 hull", ["--native"])):
        cpus, walls, grasped, parts, first = [], [], 0, None, None
        for _ in range(args.runs):
            out, cpu, wall = run(batch + extra)
            lines, summary = batch_lines(out)
            grasped = summary["grasped"]
            cpus.append(cpu)
            walls.append(wall)
            parts = parts_of(lines)
            first = lines[0]["cost"]["before_first_step"]["cpu_s"]
        cpu = statistics.median(cpus)
        results[name] = grasped * 60 / cpu if cpu > 0 else 0
        physics = parts.get("physics", 0) / max(1, grasped)
        other = sum(v for k, v in parts.items() if k != "physics")
        later = parts_of(lines[1:])
        later_other = sum(v for k, v in later.items() if k != "physics")
        later_share = later_other / max(1e-9, later_other + later.get("physics", 0))
        print(f"{name}: batch of {args.placements} ({grasped} grasped): median {cpu:.2f} s CPU "
              f"({statistics.median(walls):.2f} s wall) over {args.runs} runs: "
              f"{results[name]:.1f} grasps/min; first grasp {first:.3f} s CPU before its first "
              f"physics step; not physics {other / max(1e-9, other + parts.get('physics', 0)):.0%}"
              f" of the grasps' measured time ({later_share:.0%} in the grasps after the first); physics "
              f"{physics:.3f} s CPU per grasp")
        print("  parts (s CPU, summed over the batch): " +
              ", ".join(f"{k} {v:.3f}" for k, v in parts.items()))

    # One process per grasp: the batch's first placements, each run alone.
    lines, _ = batch_lines(run(batch)[0])
    cpus = []
    for line in lines[: args.single]:
        p = line["placement"]
        alone = base + ["--up", p["up"], "--yaw", repr(p["yaw_deg"]), "--offset",
                        repr(p["offset"][0]), repr(p["offset"][1]), "--json"]
        runs = [run(alone)[1] for _ in range(args.runs)]
        cpus.append(statistics.median(runs))
    single = len(cpus) * 60 / sum(cpus)
    print(f"one process per grasp: {single:.1f} grasps/min (median CPU of {args.runs} runs of "
          f"{len(cpus)} placements: {', '.join(f'{c:.2f}' for c in cpus)} s)")
    if args.today:
        today = [args.today, "grasp", "--object", args.object, "--hand", args.hand] + fixed + [
            "--quiet"]
        cpu = statistics.median(run(today)[1] for _ in range(args.runs))
        print(f"one process per grasp with {args.today}: {60 / cpu:.1f} grasps/min (median CPU "
              f"{cpu:.2f} s of {args.runs} runs); the batch: "
              f"{results['graspcd default'] * cpu / 60:.2f}x")
    print(f"batch / one process per grasp: {results['graspcd default'] / single:.2f}x; "
          f"graspcd default / hull in the batch: "
          f"{results['graspcd default'] / results['MuJoCo 2.2 hull']:.2f}x")

    if args.workers:
        start = time.monotonic()
        run(batch)
        one = time.monotonic() - start
        start = time.monotonic()
        procs = [subprocess.Popen(batch, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                 for _ in range(2)]
        for proc in procs:
            proc.wait()
        two = time.monotonic() - start
        print(f"two workers: {2 * one / two:.2f}x one (wall {one:.2f} s for one batch, "
              f"{two:.2f} s for two at once)")
    print(f"load: {open('/proc/loadavg').read().strip()}")


if __name__ == "__main__":
    main()
