#!/usr/bin/python3
"""Contact reductions of at most 4 per pair against the default manifold, on 13 scenes.

usage: reduction_check.py GRASPCD [--jobs N] [--variants A,B,...] [--json OUT] [--grasp-args ARGS]

Runs `graspcd grasp SCENE --json --judge [--manifold X]` from the checkout's mjcf/ folder on
examples 1-3, hand_triangles, real_robotiq_cup, the two hold scenes (mjcf/hard/hold_*.xml) and
the six concave_*.xml scenes, for each variant: "default" (the pair config as shipped: "support",
8 per pair), "force4" (the force reduction, contact_manifold.h, 4 per pair) and "support4" (the
support reduction at 4 per pair); other `--manifold` values may be named with --variants, and
--grasp-args adds options to every run (e.g. "--noslip 10": MuJoCo's noslip solver). Prints
one table per measure (rows: scenes; columns: variants):
  verdict    held / not held (gripped), and the judge's phantom/missed contacts (CGAL)
  drift      hold_drift, mm: the object's largest move relative to the palm in the hold
  rest       rest.max_penetration, mm: the deepest REPORTED contact depth of an object geom in the
             hold's last second (a reduction that scales depths reports deeper points than the
             geometry has; see true)
  true       true_penetration_max, mm: the true meshes' deepest penetration over the run (CGAL-free
             exact inside test, true_penetration.h): the geometry, whatever was reported
  contacts   mean / max contacts per physics step (all pairs) and the most one pair had
  ms/step    wall ms per physics step (runs made side by side: a comparison, not a benchmark)
and per non-default variant whether it meets the criteria against the default: same held verdict,
judge 0 phantom / 0 missed, hold_drift and true penetration within +10% of the default's (or
within 0.1 mm of it, below the measures' resolution), and rest within +10% (reported only).
A run whose simulation went non-finite (graspcd's refusal) is shown as such and fails every
criterion. Exit code 0 even when a criterion fails (it is a measurement); 2 when a run fails
otherwise.
"""
import concurrent.futures
import json
import os
import subprocess
import sys

SCENES = [
    "example1", "example2", "example3", "hand_triangles", "real_robotiq_cup",
    "hard/hold_example1", "hard/hold_example3",
    "concave_bowl_lift", "concave_project_thinbox", "concave_robotiq_bowl_rim",
    "concave_robotiq_mug_handle", "concave_robotiq_mug_rim", "concave_shadow_mug_hook",
]
VARIANTS = ["default", "force4", "support4"]
RELATIVE = 0.10  # +10% of the default
ABSOLUTE = 1e-4  # m: differences below this are within the measures' resolution


def fail(message):
    print(f"reduction_check.py: {message}", file=sys.stderr)
    sys.exit(2)


def run(graspcd, mjcf, scene, variant, extra):
    cmd = [graspcd, "grasp", os.path.join(mjcf, scene + ".xml"), "--json", "--judge"] + extra
    if variant != "default":
        cmd += ["--manifold", variant]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0 and "went non-finite" in r.stderr:
        # The simulation itself failed (graspcd's one-line refusal): a result, not a broken run.
        return {"error": r.stderr.strip().splitlines()[-1]}
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} exited with {r.returncode}: {r.stderr.strip()}")
    d = json.loads(r.stdout)
    judge = d.get("judge") or {}
    return {
        "held": d["held"],
        "gripped": d["gripped"],
        "reason": d.get("reason", ""),
        "phantom": judge.get("phantom"),
        "missed": judge.get("missed"),
        "hold_drift": d["hold_drift"],
        "rest_max_penetration": d["rest"]["max_penetration"],
        "true_penetration_max": d["true_penetration_max"],
        "mean_contacts": d["mean_contacts"],
        "max_contacts": d["max_contacts"],
        "max_pair_contacts": d["max_pair_contacts"],
        "ms_per_physics_step": d["ms_per_physics_step"],
    }


def within(value, reference):
    return value <= reference * (1 + RELATIVE) or value <= reference + ABSOLUTE


def main():
    args = sys.argv[1:]
    jobs, variants, out, extra = 2, VARIANTS, None, []
    rest = []
    while args:
        a = args.pop(0)
        if a == "--jobs" and args:
            jobs = int(args.pop(0))
        elif a == "--variants" and args:
            variants = ["default"] + [v for v in args.pop(0).split(",") if v != "default"]
        elif a == "--json" and args:
            out = args.pop(0)
        elif a == "--grasp-args" and args:
            extra = args.pop(0).split()
        else:
            rest.append(a)
    if len(rest) != 1:
        fail("usage: reduction_check.py GRASPCD [--jobs N] [--variants A,B,...] [--json OUT] "
             "[--grasp-args ARGS]")
    graspcd = os.path.abspath(rest[0])
    mjcf = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mjcf")
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {(s, v): pool.submit(run, graspcd, mjcf, s, v, extra) for s in SCENES for v in variants}
        results = {key: f.result() for key, f in futures.items()}
    if out:
        with open(out, "w") as f:
            json.dump({f"{s} {v}": r for (s, v), r in results.items()}, f, indent=1)

    width = max(len(s) for s in SCENES)
    columns = lambda cells: " | ".join(f"{c:>22}" for c in cells)

    def table(title, cell):
        print(f"\n{title}")
        print(f"{'scene':<{width}} | " + columns(variants))
        for s in SCENES:
            print(f"{s:<{width}} | " + columns(
                "non-finite" if "error" in results[(s, v)] else cell(results[(s, v)])
                for v in variants))

    table("verdict (held, judge phantom/missed)", lambda r: (
        f"{'held' if r['held'] else 'NOT held'} {r['phantom']}/{r['missed']}"))
    table("hold_drift, mm", lambda r: f"{1e3 * r['hold_drift']:.3f}")
    table("rest_max_penetration (reported), mm", lambda r: f"{1e3 * r['rest_max_penetration']:.3f}")
    table("true_penetration_max (geometry), mm", lambda r: f"{1e3 * r['true_penetration_max']:.3f}")
    table("contacts per step mean/max, per pair max", lambda r: (
        f"{r['mean_contacts']:.1f}/{r['max_contacts']}/{r['max_pair_contacts']}"))
    table("ms per physics step", lambda r: f"{r['ms_per_physics_step']:.3f}")

    print("\ncriteria against the default (same verdict, judge 0/0, drift and true penetration "
          f"within +{RELATIVE:.0%} or {1e3 * ABSOLUTE:.1f} mm; rest reported within +{RELATIVE:.0%})")
    for v in variants[1:]:
        ok = {"verdict": 0, "judge": 0, "drift": 0, "true": 0, "rest": 0, "all": 0}
        for s in SCENES:
            d, r = results[(s, "default")], results[(s, v)]
            if "error" in r or "error" in d:
                print(f"  {s} {v if 'error' in r else 'default'}: {(r if 'error' in r else d)['error']}")
                continue
            checks = {
                "verdict": r["held"] == d["held"],
                "judge": r["phantom"] == 0 and r["missed"] == 0,
                "drift": within(r["hold_drift"], d["hold_drift"]),
                "true": within(r["true_penetration_max"], d["true_penetration_max"]),
                "rest": within(r["rest_max_penetration"], d["rest_max_penetration"]),
            }
            for k, passed in checks.items():
                ok[k] += passed
            ok["all"] += all(checks[k] for k in ("verdict", "judge", "drift", "true"))
        n = len(SCENES)
        print(f"{v}: verdict {ok['verdict']}/{n}, judge 0/0 {ok['judge']}/{n}, drift {ok['drift']}/{n}, "
              f"true {ok['true']}/{n}, rest (reported) {ok['rest']}/{n}; all but rest {ok['all']}/{n}")
        finite = [s for s in SCENES if "error" not in results[(s, v)]]
        mean = lambda key, var: sum(results[(s, var)][key] for s in finite) / len(finite)
        print(f"  mean contacts per step {mean('mean_contacts', v):.2f} "
              f"(default {mean('mean_contacts', 'default'):.2f}); ms per physics step "
              f"{mean('ms_per_physics_step', v):.3f} (default "
              f"{mean('ms_per_physics_step', 'default'):.3f})")


if __name__ == "__main__":
    main()
