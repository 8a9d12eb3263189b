#!/usr/bin/env python3
"""What a build costs, per target and per translation unit, in CPU seconds.

Wall times lie on a shared machine; the CPU time of each compile and link does not. This script
is both halves of the measurement (docs/testing.md, "Where the time goes"):

  launcher: CMake runs every compile and link through it, and it appends one line per command to
  LOG: user+sys CPU seconds, wall seconds, the output file and the target.

    CCACHE_DISABLE=1 cmake -S . -B build-cost -G Ninja -DCMAKE_BUILD_TYPE=Release ... \\
      -DCMAKE_CXX_COMPILER_LAUNCHER="/usr/bin/python3;$PWD/tools/build_cost.py;--log;/tmp/cost.tsv" \\
      -DCMAKE_CXX_LINKER_LAUNCHER="/usr/bin/python3;$PWD/tools/build_cost.py;--log;/tmp/cost.tsv"
    cmake --build build-cost -j2

  report: the sums, per target, and the most expensive commands.

    /usr/bin/python3 tools/build_cost.py --report /tmp/cost.tsv [--top 25]

  ninja log: without a launcher, what a finished build's commands took, from Ninja's own log
  (each output's last build: wall seconds of one job), summed per part of the tree (src, app,
  tests, fuzz) and its most expensive commands; on an otherwise idle machine a job's wall
  seconds are its CPU seconds. A fresh clone's `./run test` leaves build/.ninja_log and
  build-asan/.ninja_log.

    /usr/bin/python3 tools/build_cost.py --ninja-log build/.ninja_log [--top 10]
"""

import argparse
import collections
import os
import re
import subprocess
import sys
import time


def output_of(command):
    """The file a compile or link command writes (its -o argument), or '?'."""
    for i, arg in enumerate(command[:-1]):
        if arg == "-o":
            return command[i + 1]
    return "?"


def target_of(output):
    """The CMake target an output belongs to: CMakeFiles/<target>.dir/ for objects and
    precompiled headers, the file's own name for an executable or a library."""
    m = re.search(r"CMakeFiles/([^/]+)\.dir/", output)
    if m:
        return m.group(1)
    name = os.path.basename(output)
    m = re.fullmatch(r"lib(.+)\.(a|so)", name)
    return m.group(1) if m else name


def kind_of(command, output):
    if "-c" in command:
        return "pch" if re.search(r"\.(pch|gch)$", output) else "compile"
    return "link"


def launch(log, command):
    """Runs the command, then appends its cost to LOG (one line, appended whole)."""
    start = time.monotonic()
    before = os.times()
    status = subprocess.call(command)
    after = os.times()
    cpu = (after.children_user - before.children_user) + (after.children_system -
                                                          before.children_system)
    output = output_of(command)
    line = "%.3f\t%.3f\t%s\t%s\t%s\n" % (cpu, time.monotonic() - start,
                                         kind_of(command, output), target_of(output), output)
    with open(log, "a", encoding="utf-8") as f:
        f.write(line)
    return status


def report(log, top):
    rows = []
    with open(log, encoding="utf-8") as f:
        for line in f:
            cpu, wall, kind, target, output = line.rstrip("\n").split("\t")
            rows.append((float(cpu), float(wall), kind, target, output))
    if not rows:
        sys.exit("%s: no commands logged" % log)
    by_kind = collections.Counter()
    by_target = collections.defaultdict(lambda: [0.0, 0, 0.0])
    for cpu, _, kind, target, _ in rows:
        by_kind[kind] += cpu
        t = by_target[target]
        t[0] += cpu
        t[1] += 1
        if kind == "link":
            t[2] += cpu
    total = sum(r[0] for r in rows)
    print("%d commands, %.0f s CPU in all: %s" % (
        len(rows), total, ", ".join("%s %.0f s" % (k, v) for k, v in sorted(by_kind.items()))))
    print("\nper target (CPU s, commands, of which link s):")
    for target, (cpu, n, link) in sorted(by_target.items(), key=lambda kv: -kv[1][0])[:top]:
        print("  %8.1f  %3d  %6.1f  %s" % (cpu, n, link, target))
    print("\nmost expensive commands (CPU s, wall s):")
    for cpu, wall, kind, _, output in sorted(rows, key=lambda r: -r[0])[:top]:
        print("  %8.1f  %6.1f  %-7s %s" % (cpu, wall, kind, output))


def ninja_report(log, top):
    """Ninja's log (version 5: start ms, end ms, mtime, output, hash per line, '#' header): the
    last entry of each output, summed by the first folder of its path."""
    last = {}
    with open(log, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                continue
            fields = line.rstrip("\n").split("\t")
            if len(fields) < 4:
                continue
            last[fields[3]] = (int(fields[1]) - int(fields[0])) / 1000.0
    if not last:
        sys.exit("%s: no commands logged" % log)
    parts = collections.defaultdict(lambda: [0.0, 0])
    for output, seconds in last.items():
        if output.startswith("/"):
            first = "(absolute paths)"
        else:
            first = output.split("/")[0] if "/" in output else "(top)"
        parts[first][0] += seconds
        parts[first][1] += 1
    print("%d outputs, %.0f job-seconds in all (wall seconds of one job each)" % (
        len(last), sum(last.values())))
    for part, (seconds, n) in sorted(parts.items(), key=lambda kv: -kv[1][0]):
        print("  %8.1f  %4d  %s" % (seconds, n, part))
    print("\nmost expensive outputs (s):")
    for output, seconds in sorted(last.items(), key=lambda kv: -kv[1])[:top]:
        print("  %8.1f  %s" % (seconds, output))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--log", help="as a compiler/linker launcher: append to LOG")
    parser.add_argument("--report", metavar="LOG", help="print the costs LOG holds")
    parser.add_argument("--ninja-log", metavar="NINJA_LOG",
                        help="print what a finished build's commands took, from Ninja's log")
    parser.add_argument("--top", type=int, default=25, help="rows per table (default 25)")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="the command to run")
    args = parser.parse_args()
    if args.report:
        report(args.report, args.top)
    elif args.ninja_log:
        ninja_report(args.ninja_log, args.top)
    elif args.log and args.command:
        sys.exit(launch(args.log, args.command))
    else:
        parser.error("give --report LOG, --ninja-log NINJA_LOG, or --log LOG followed by a "
                     "command")


if __name__ == "__main__":
    main()
