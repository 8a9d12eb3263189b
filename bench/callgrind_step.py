#!/usr/bin/python3
"""Instructions per physics step of a whole grasp, split by part, counted by valgrind's callgrind.

Runs `graspcd grasp SCENE --json` (served, the scene's config: contacts reused within 20 um by
default; --exact: exact contacts every step; --native: MuJoCo's own collision; --decomposed DIR:
the object as the convex pieces of `graspcd decompose`) under callgrind, collecting only inside
mj_step1, mj_step2 and mj_step (--toggle-collect: the grasp of our hands steps as mj_step1, control,
mj_step2; a driven real hand as mj_step), so that loading, tree builds, the start check and the
grasp's own measures between steps are not counted. callgrind_annotate --inclusive=yes then gives
each function's instructions with its callees; divided by the grasp's physics steps:
  step               mj_step1 + mj_step2 + mj_step
  graspcd_function   graspcd's collision function (collide_geoms), inclusive: the served pairs
                     and the pairs it hands to MuJoCo's originals
  served             of which the served pairs (collide_served_pair), and within them the tree
                     query, the triangle tests, the contact routine, the manifold and the
                     containment check (null where a part was inlined or never ran)
  solver             MuJoCo's constraint solver (mj_fwdConstraint, which runs mj_solPGS, mj_solCG
                     or mj_solNewton: those are not exported by MuJoCo 2.2.2)
  constraint_setup   mj_makeConstraint + mj_projectConstraint + mj_referenceConstraint
  collision          mj_collision (MuJoCo's broad phase with every pair's function)
  rest               step - graspcd_function - solver
  mujoco             step - served: MuJoCo's own step with the same contacts (a served pair's
                     contacts are all MuJoCo takes from it, so MuJoCo's work is the same)
With --floor-bench PATH (served only), the floor's parts in instructions too: graspcd_floor_bench
runs the scene's recorded intersecting triangle pairs through the certified test and the contact
routine, and its kept contacts through the write, under callgrind; each part's instructions (its
pass, inclusive) per physics step, and floor = mujoco + tritri + contact + write, with graspcd's
part (served) over its floor (tritri + contact + write).

Usage: /usr/bin/python3 bench/callgrind_step.py GRASPCD SCENE [--native | --decomposed DIR | --exact]
           [--floor-bench PATH] [--keep DIR]
Prints one JSON document. valgrind 3.19 (Debian 12) cannot run AVX-512 code: the build must not
be compiled for it (the project's builds are not; glibc picks its routines by the CPU valgrind
reports). Exits 2 with a one-line message on bad input, 1 when a run fails.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile


def fail(message, code=2):
    print(f"callgrind_step.py: {message}", file=sys.stderr)
    sys.exit(code)


def callgrind(command, out_file):
    """Runs `command` (valgrind options first) under callgrind, writing `out_file`."""
    return subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}",
                           *command], capture_output=True, text=True, check=False)


def inclusive(out_file):
    """function name -> inclusive instructions (callgrind_annotate --inclusive=yes)."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out_file],
                          capture_output=True, text=True, check=True).stdout
    costs = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\([^)]*\)\s+[^:]*:(.*?)(?: \[[^\]]*\])?$", line)
        if m:
            name = m.group(2)
            costs[name] = max(costs.get(name, 0), int(m.group(1).replace(",", "")))
    return costs


def find(costs, pattern):
    """The largest inclusive cost of a function whose name matches `pattern` (regex), or None."""
    found = [v for k, v in costs.items() if re.search(pattern, k)]
    return max(found) if found else None


def total(costs, *patterns):
    parts = [find(costs, p) for p in patterns]
    return sum(p for p in parts if p is not None) if any(p is not None for p in parts) else None


def per_step(x, steps):
    return None if x is None else x / steps


def grasp_split(args, work):
    out_file = os.path.join(work, "callgrind.grasp")
    command = [args.graspcd, "grasp", args.scene, "--json", "--quiet"]
    if args.native:
        command.append("--native")
    if args.decomposed:
        command += ["--decomposed", args.decomposed]
    if args.exact:
        command.append("--exact")
    run = callgrind(["--collect-atstart=no", "--toggle-collect=mj_step1",
                     "--toggle-collect=mj_step2", "--toggle-collect=mj_step", *command], out_file)
    if run.returncode != 0:
        last = (run.stderr.strip().splitlines() or ["(no message)"])[-1]
        fail(f"{args.scene}: graspcd grasp exited with {run.returncode}: {last}", 1)
    try:
        result = json.loads(run.stdout)
    except json.JSONDecodeError:
        fail(f"{args.scene}: graspcd grasp printed no JSON", 1)
    steps = result["physics_steps"]
    c = inclusive(out_file)
    step = total(c, r"^mj_step1$", r"^mj_step2$", r"^mj_step$")
    if step is None:
        fail(f"{args.scene}: no physics step in the profile (mj_step1, mj_step2, mj_step)", 1)
    function = find(c, r"graspcd::mujoco::collide_geoms\(")
    served = find(c, r"graspcd::mujoco::collide_served_pair\(")
    solver = find(c, r"^mj_fwdConstraint$")
    split = {
        "step": step,
        "graspcd_function": function,
        "served": served,
        "served_tree_query": total(c, r"graspcd::Detector::collide_coherent\(",
                                   r"graspcd::Detector::collide\("),
        "served_tri_tri_intersect": find(c, r"^graspcd::tri_tri_intersect\("),
        "served_triangle_pair_contact": find(c, r"^graspcd::triangle_pair_contact\("),
        "served_manifold": find(c, r"^graspcd::build_contact_manifold"),
        "served_containment": find(c, r"^graspcd::mesh_containment\("),
        "solver": solver,
        "constraint_setup": total(c, r"^mj_makeConstraint$", r"^mj_projectConstraint$",
                                  r"^mj_referenceConstraint$"),
        "collision": find(c, r"^mj_collision$"),
        "rest": step - (function or 0) - (solver or 0),
        "mujoco": step - (served or 0),
    }
    return result, steps, {k: per_step(v, steps) for k, v in split.items()}


def floor_parts(args, work, steps):
    """Instructions per physics step of the floor's parts, from graspcd_floor_bench."""
    stem = os.path.splitext(os.path.basename(args.scene))[0]
    out_file = os.path.join(work, "callgrind.floor")
    bench_json = os.path.join(work, "floor.json")
    run = callgrind([args.floor_bench, f"--benchmark_filter=BM_Floor/{re.escape(stem)}/"
                     "(tritri|contact|write)/", f"--benchmark_out={bench_json}",
                     "--benchmark_out_format=json"], out_file)
    if run.returncode != 0:
        last = (run.stderr.strip().splitlines() or ["(no message)"])[-1]
        fail(f"{args.scene}: graspcd_floor_bench exited with {run.returncode}: {last}", 1)
    with open(bench_json, encoding="utf-8") as f:
        runs = {b["name"].split("/")[2]: b for b in json.load(f)["benchmarks"]
                if b.get("run_type") == "iteration"}
    c = inclusive(out_file)
    parts = {}
    for part in ("tritri", "contact", "write"):
        if part not in runs:
            fail(f"{args.scene}: graspcd_floor_bench ran no {part} pass", 1)
        b = runs[part]
        if b["physics_steps"] != steps:
            fail(f"{args.scene}: the floor bench's grasp took {b['physics_steps']:.0f} physics "
                 f"steps, graspcd grasp's {steps}", 1)
        # pass<part's lambda>: the part's passes (its iterations), inclusive.
        cost = find(c, rf"pass<.*::{part}\(benchmark::State&")
        if cost is None:
            fail(f"{args.scene}: no pass of {part} in the callgrind profile", 1)
        parts[part] = cost / b["iterations"] / steps
        cases = b["tri_pairs" if part != "write" else "contacts"] * steps
        parts[f"{part}_each"] = cost / b["iterations"] / cases if cases else None
    return parts


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("graspcd")
    parser.add_argument("scene")
    variant = parser.add_mutually_exclusive_group()
    variant.add_argument("--native", action="store_true")
    variant.add_argument("--decomposed", metavar="DIR")
    variant.add_argument("--exact", action="store_true",
                         help="served with exact contacts every step (grasp --exact)")
    parser.add_argument("--floor-bench", metavar="PATH")
    parser.add_argument("--keep", metavar="DIR", help="keep the callgrind files in DIR")
    args = parser.parse_args()
    for tool in ("valgrind", "callgrind_annotate"):
        if shutil.which(tool) is None:
            fail(f"{tool} not found (Debian package valgrind; ./run perf installs it)")
    if not os.path.isfile(args.graspcd):
        fail(f"{args.graspcd}: no such executable")
    if not os.path.isfile(args.scene):
        fail(f"{args.scene}: no such scene")
    if args.floor_bench and (args.native or args.decomposed):
        fail("--floor-bench: the floor is of the served grasp (not with --native or --decomposed)")
    if args.floor_bench and not os.path.isfile(args.floor_bench):
        fail(f"{args.floor_bench}: no such executable")
    work = args.keep or tempfile.mkdtemp(prefix="callgrind_step.")
    os.makedirs(work, exist_ok=True)
    try:
        result, steps, split = grasp_split(args, work)
        out = {"scene": args.scene,
               "variant": "native" if args.native else
               ("decomposed" if args.decomposed else
                ("served-exact" if args.exact else "served")),
               "physics_steps": steps, "held": result.get("held"),
               "unit": "instructions per physics step", "split": split}
        if args.floor_bench:
            f = floor_parts(args, work, steps)
            graspcd_floor = f["tritri"] + f["contact"] + f["write"]
            out["floor"] = {**f, "mujoco": split["mujoco"],
                            "floor": split["mujoco"] + graspcd_floor,
                            "graspcd_floor": graspcd_floor,
                            "graspcd_part_over_floor": split["served"] / graspcd_floor
                            if graspcd_floor else None,
                            "step_over_floor": split["step"] / (split["mujoco"] + graspcd_floor)}
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    json.dump(out, sys.stdout, indent=1, sort_keys=True)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
