#!/usr/bin/python3
"""Turns the Google Benchmark JSON of `./run perf` into perf.json: medians, min and max over the
repetitions of every benchmark, and every comparison of docs/performance.md as a ratio of ours to
the peer measured in the same run, with its target and whether it is met.

Usage: /usr/bin/python3 bench/perf_summary.py FCL_BENCH.json MUJOCO_BENCH.json [FLOOR_BENCH.json]
       > perf.json

With FLOOR_BENCH.json (graspcd_floor_bench), perf.json also carries "floor": per scene, the time
per physics step (medians over the repetitions, microseconds) of the served, native and replayed
grasps and of the floor's parts, the floor (replay + tritri + contact + write), graspcd's part
(served - replay), the floor of that part (tritri + contact + write) and their ratio, with the
ratio's min and max over the repetitions (repetition K of every part of a scene paired).

A ratio's median is the ratio of the two medians; its min and max are those of the ratios of
repetition i of ours to repetition i of the peer (Google Benchmark runs the repetitions of one
benchmark back to back, so pairing them by index is pairing runs minutes apart at most; the
whole grasps are registered one benchmark per repetition, "/rep:K", in the order repetition,
scene, variant, so that repetition K of a scene's native and served grasps run one after the
other, and "/rep:K" is folded into the benchmark's name here).
Exits 2 with a one-line message when an input is missing or not Google Benchmark's JSON.
"""

import json
import math
import re
import statistics
import sys


def fail(message):
    print(f"perf_summary.py: {message}", file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    except json.JSONDecodeError as e:
        fail(f"{path}:{e.lineno}: not JSON ({e.msg})")
    if "benchmarks" not in data or "context" not in data:
        fail(f"{path}: not Google Benchmark's JSON output (no 'benchmarks' or 'context')")
    return data


# Counters Google Benchmark adds that are not ours.
NOT_COUNTERS = {"name", "family_index", "per_family_instance_index", "run_name", "run_type",
                "repetitions", "repetition_index", "threads", "iterations", "real_time",
                "cpu_time", "time_unit", "aggregate_name", "aggregate_unit", "label",
                "error_occurred", "error_message"}


def repetitions(data):
    """name -> {"times": [cpu time per repetition], "unit", "counters" (of the first)}."""
    out = {}
    for b in data["benchmarks"]:
        if b.get("run_type") != "iteration" or b.get("error_occurred"):
            continue
        # A fixed iteration count shows in the name ("/iterations:1"), and the whole grasps'
        # repetition ("/rep:K", each its own benchmark); the comparisons depend on neither.
        name = re.sub(r"/iterations:\d+|/repeats:\d+|/manual_time|/rep:\d+", "", b["run_name"])
        entry = out.setdefault(name, {"times": [], "unit": b["time_unit"],
                                               "counters": {}})
        # Manual-time benchmarks (the whole grasps) time only what they measure: their real_time.
        entry["times"].append(b["real_time"] if b.get("use_manual_time") or
                              "manual_time" in b.get("name", "") else b["cpu_time"])
        if not entry["counters"]:
            entry["counters"] = {k: v for k, v in b.items() if k not in NOT_COUNTERS}
    return out


def summary(entry):
    t = entry["times"]
    return {"unit": entry["unit"], "median": statistics.median(t), "min": min(t), "max": max(t),
            "repetitions": len(t), "counters": entry["counters"]}


def compare(runs, group, label, ours, peer, target=None, **extra):
    """A comparison of two benchmarks, or None when either did not run."""
    if ours not in runs or peer not in runs:
        return None
    a, b = runs[ours]["times"], runs[peer]["times"]
    per_rep = [x / y for x, y in zip(a, b)]
    ratio = statistics.median(a) / statistics.median(b)
    c = {"group": group, "label": label, "ours": ours, "peer": peer,
         "ratio_median": ratio, "ratio_min": min(per_rep), "ratio_max": max(per_rep),
         "target": target, "met": None if target is None else ratio <= target}
    c.update(extra)
    return c


# The floor's parts (floor_bench.cpp), each a time per physics step.
FLOOR_PARTS = ("served", "native", "replay", "tritri", "contact", "write")


def floor_summary(runs):
    """Per scene of BM_Floor: the parts' medians, the floor and graspcd's part against its floor."""
    scenes = sorted({name.split("/")[1] for name in runs if name.startswith("BM_Floor/")})
    out = {}
    for scene in scenes:
        times = {p: runs.get(f"BM_Floor/{scene}/{p}", {}).get("times", []) for p in FLOOR_PARTS}
        if not all(times[p] for p in ("served", "replay", "tritri", "contact", "write")):
            continue
        reps = min(len(times[p]) for p in ("served", "replay", "tritri", "contact", "write"))

        def at(p, i):
            return times[p][i]

        part_floor = [at("tritri", i) + at("contact", i) + at("write", i) for i in range(reps)]
        part = [at("served", i) - at("replay", i) for i in range(reps)]
        ratio = [x / y for x, y in zip(part, part_floor)]
        med = {p: statistics.median(times[p]) if times[p] else None for p in FLOOR_PARTS}
        counters = runs[f"BM_Floor/{scene}/served"]["counters"]
        floor = med["replay"] + med["tritri"] + med["contact"] + med["write"]
        graspcd_part = med["served"] - med["replay"]
        graspcd_floor = med["tritri"] + med["contact"] + med["write"]
        out[scene] = {
            "unit": "us per physics step",
            "repetitions": reps,
            **{p: med[p] for p in FLOOR_PARTS},
            "floor": floor,
            "graspcd_part": graspcd_part,
            "graspcd_floor": graspcd_floor,
            "graspcd_part_over_floor": graspcd_part / graspcd_floor if graspcd_floor else None,
            "graspcd_part_over_floor_min": min(ratio) if graspcd_floor else None,
            "graspcd_part_over_floor_max": max(ratio) if graspcd_floor else None,
            "served_over_floor": med["served"] / floor,
            "served_over_native": med["served"] / med["native"] if med["native"] else None,
            "physics_steps": counters.get("physics_steps"),
            "tri_pairs_per_step": counters.get("tri_pairs"),
            "contacts_per_step": counters.get("contacts"),
            "served_calls_per_step": counters.get("served_calls"),
            "ns_per_tritri": runs[f"BM_Floor/{scene}/tritri"]["counters"].get("ns_each"),
            "ns_per_contact": runs[f"BM_Floor/{scene}/contact"]["counters"].get("ns_each"),
            "ns_per_write": runs[f"BM_Floor/{scene}/write"]["counters"].get("ns_each"),
        }
    return out


def main():
    if len(sys.argv) not in (3, 4):
        fail("usage: perf_summary.py FCL_BENCH.json MUJOCO_BENCH.json [FLOOR_BENCH.json]")
    fcl_data, mj_data = load(sys.argv[1]), load(sys.argv[2])
    runs = repetitions(fcl_data)
    runs.update(repetitions(mj_data))
    if len(sys.argv) == 4:
        runs.update(repetitions(load(sys.argv[3])))
    out = {"context": fcl_data["context"],
           "benchmarks": {name: summary(e) for name, e in sorted(runs.items())},
           "comparisons": []}
    comps = out["comparisons"]

    def add(c):
        if c is not None:
            comps.append(c)

    # One OBB test.
    for s in ("disjoint-heavy", "overlap-heavy"):
        add(compare(runs, "obb_test", f"{s}, B in A's frame", f"BM_ObbTest/{s}/ours",
                    f"BM_ObbTest/{s}/fcl", 0.5))
        add(compare(runs, "obb_test", f"{s}, from two world boxes", f"BM_ObbTest/{s}/ours-boxes",
                    f"BM_ObbTest/{s}/fcl"))
    # Mesh against mesh, every method.
    for name in sorted(runs):
        parts = name.split("/")
        if parts[0] != "BM_Spheres" or parts[-1] == "fcl-obb":
            continue
        peer = "/".join(parts[:-1] + ["fcl-obb"])
        if peer not in runs:
            continue
        mine, theirs = runs[name]["counters"], runs[peer]["counters"]
        target = 0.5 if parts[-1] == "ours-sat" or parts[-1] == "ours-sat-cached" else None
        add(compare(runs, "mesh", f"{parts[2]}, {parts[3]}, {parts[4]}", name, peer, target,
                    box_tests=mine.get("box_tests"), peer_box_tests=theirs.get("box_tests"),
                    pairs=mine.get("pairs"), agrees=mine.get("agrees") == 1))
    # Along the trajectories: ours with temporal coherence against FCL per step and FCL's front.
    for name in sorted(runs):
        parts = name.split("/")
        if parts[0] != "BM_Query" or parts[-1] != "ours-sat-cached":
            continue
        stem = "/".join(parts[:-1])
        for peer, what in (("fcl-obb", "FCL per step"), ("fcl-obb-front", "FCL's front list")):
            add(compare(runs, "trajectory", f"{parts[1]}, {parts[2]}, {parts[3]}, vs {what}",
                        name, f"{stem}/{peer}", 0.25,
                        box_tests=runs[name]["counters"].get("box_tests"),
                        peer_box_tests=runs.get(f"{stem}/{peer}", {}).get("counters", {})
                        .get("box_tests"),
                        hit_share=runs[name]["counters"].get("hit_share"),
                        peer_hit_share=runs.get(f"{stem}/{peer}", {}).get("counters", {})
                        .get("hit_share")))
        add(compare(runs, "trajectory_plain", f"{parts[1]}, {parts[2]}, {parts[3]}, sat vs FCL",
                    f"{stem}/ours-sat", f"{stem}/fcl-obb"))
    # Tree build, with time / (n log2 n) to show n log n.
    for name in sorted(runs):
        parts = name.split("/")
        if parts[0] != "BM_BuildScale" or parts[-1] != "ours":
            continue
        peer = "/".join(parts[:-1] + ["fcl-obb"])
        n = runs[name]["counters"].get("faces", 0)
        nlogn = n * math.log2(n) if n > 1 else 1
        add(compare(runs, "build", f"{int(n)} triangles", name, peer, None, faces=n,
                    ours_ns_per_nlogn=statistics.median(runs[name]["times"]) * 1e6 / nlogn,
                    peer_ns_per_nlogn=statistics.median(runs[peer]["times"]) * 1e6 / nlogn
                    if peer in runs else None))
    # Query cost against triangle count.
    for name in sorted(runs):
        parts = name.split("/")
        if parts[0] != "BM_QueryScale" or parts[-1] != "ours-sat":
            continue
        peer = "/".join(parts[:-1] + ["fcl-obb"])
        c = runs[name]["counters"]
        add(compare(runs, "scaling", f"{int(c.get('faces', 0))} triangles, {parts[2]}", name, peer,
                    None, faces=c.get("faces"), box_tests=c.get("box_tests"),
                    peer_box_tests=runs.get(peer, {}).get("counters", {}).get("box_tests"),
                    agrees=c.get("agrees") == 1))
    # MuJoCo: mj_step of the triangle hand with our callback against MuJoCo's own collision.
    add(compare(runs, "mujoco", "mj_step, triangle hand, served pairs by graspcd",
                "BM_StepServed", "BM_StepPlain", 2.0))
    # Whole grasps: consecutive physics steps, served against native, target 2x.
    for name in sorted(runs):
        parts = name.split("/")
        if parts[0] != "BM_WholeGrasp" or parts[2] != "served":
            continue
        native = "/".join(parts[:2] + ["native"] + parts[3:])
        c = runs[name]["counters"]
        add(compare(runs, "grasp", f"whole grasp {parts[1]}, served / native per physics step",
                    name, native, 2.0, max_contacts=c.get("max_contacts"),
                    native_max_contacts=runs.get(native, {}).get("counters", {}).get(
                        "max_contacts"), held=c.get("held") == 1))
        exact = "/".join(parts[:2] + ["served-exact"] + parts[3:])
        roots = "/".join(parts[:2] + ["served-roots"] + parts[3:])
        add(compare(runs, "grasp", f"whole grasp {parts[1]}, front list / from the roots (exact)",
                    exact, roots, None))
        # Exact contacts every step ("contact_reuse": 0, grasp --exact) against native, and what
        # the default's reuse saves (no target: references).
        ec = runs.get(exact, {}).get("counters", {})
        add(compare(runs, "grasp_exact",
                    f"whole grasp {parts[1]}, exact contacts every step / native per physics step",
                    exact, native, None, max_contacts=ec.get("max_contacts"),
                    mean_contacts=ec.get("mean_contacts"), held=ec.get("held") == 1))
        add(compare(runs, "grasp_exact",
                    f"whole grasp {parts[1]}, served (default) / exact per physics step",
                    name, exact, None, reused_calls=c.get("reused_calls"),
                    mean_contacts=c.get("mean_contacts"), held=c.get("held") == 1))
        # MuJoCo natively with its multi-point convex collision (grasp --multiccd): graspcd's
        # served step against it, and what multiccd costs MuJoCo (no target: a reference).
        multi = "/".join(parts[:2] + ["native-multiccd"] + parts[3:])
        mc = runs.get(multi, {}).get("counters", {})
        add(compare(runs, "grasp_multiccd",
                    f"whole grasp {parts[1]}, served / native with multiccd per physics step",
                    name, multi, None, max_contacts=c.get("max_contacts"),
                    native_max_contacts=mc.get("max_contacts"),
                    native_mean_contacts=mc.get("mean_contacts"), held=c.get("held") == 1,
                    native_held=mc.get("held") == 1))
        add(compare(runs, "grasp_multiccd",
                    f"whole grasp {parts[1]}, native with multiccd / native per physics step",
                    multi, native, None, max_contacts=mc.get("max_contacts"),
                    native_max_contacts=runs.get(native, {}).get("counters", {}).get(
                        "max_contacts"), held=mc.get("held") == 1))
    floor = floor_summary(runs)
    if floor:
        out["floor"] = floor
    json.dump(out, sys.stdout, indent=1, sort_keys=True)
    sys.stdout.write("\n")
    # A short table on stderr.
    for c in comps:
        met = "" if c["met"] is None else (" met" if c["met"] else " NOT met")
        target = "" if c["target"] is None else f" (target <= {c['target']}{met})"
        print(f"{c['group']:16s} {c['label']:60s} {c['ratio_median']:.3f}"
              f" [{c['ratio_min']:.3f}, {c['ratio_max']:.3f}]{target}", file=sys.stderr)
    for scene, f in floor.items():
        native = "-" if f["native"] is None else f"{f['native']:.1f}"
        ratio = "-" if f["graspcd_part_over_floor"] is None else \
            f"{f['graspcd_part_over_floor']:.2f}"
        print(f"floor            {scene:28s} served {f['served']:.1f} native {native}"
              f" floor {f['floor']:.1f} us/step; graspcd {f['graspcd_part']:.1f}"
              f" / its floor {f['graspcd_floor']:.1f} = {ratio}", file=sys.stderr)


if __name__ == "__main__":
    main()
