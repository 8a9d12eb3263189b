"""The object-set study's reference rule and rates (study/run_objset.py records, report/ draws).

The reference verdict of a placement is graspcd's exact contacts (`grasp --exact`) at a quarter of
the scene's time step with four times the physics steps per grasp step (`--timestep-divisor 4`),
so that the drive is the same in time. The same grasp at half the step (`--timestep-divisor 2`)
says how far the reference itself has converged: the share of placements whose held verdict
differs between the half and the quarter.

A placement whose start the reference refuses ("the start state is not valid": the true meshes
penetrate the hand or the support by more than 0.5 mm at the start) is skipped: no configuration
runs it, and the rates count it apart. A configuration that refuses a placement the reference
started ("cannot start with --native ...": its hull or pieces hold a finger) is that
configuration's "cannot start": it counts in its starts, not in its verdicts.

Per configuration, over the set and per object (rates(), below):
  placements   the placements it was given (those the reference started);
  starts       the share of them it started;
  non_finite   its started runs that went non-finite (MuJoCo found a bad number in the state and
               the grasp stopped): not held, no penetration measured;
  held         the share of its started runs held after the lift;
  six          the share of its started runs held after the lift and then in all six directions
               of the six-direction test (a run's "six_directions": how many of the six it held
               in; a run without it, as one that went non-finite, is not); None when none of its
               runs had the test (runs made before the study ran it);
  disagree     the share of its started runs whose held verdict differs from the reference's,
               split into held where the reference drops (held_ref_drops) and dropped where the
               reference holds (dropped_ref_holds);
  penetration  the true meshes' deepest penetration into the hand over each run
               (`true_penetration.hand_max`, m): median, 99th percentile, largest; the runs of an
               object whose mesh is not closed for graspcd (`true_penetration.partial`: only the
               hand's inside is probed, by the object's vertices and edges; the hand's vertices
               inside the object are not seen) enter as measured, a lower bound, and are counted
               (partial_runs); the same three over the closed objects only are given apart;
  phantom, missed  the judge's phantom and missed contacts per closing grasp step (CGAL on the
               true meshes, `grasp --judge`), summed over the runs, divided by their steps;
  cost         the CPU seconds of a grasp (the `graspcd` process's user + system time), median and
               mean, its wall seconds, and the wall and CPU ms per physics step (median; the CPU
               cost is the grasp thread's over the same steps); MuJoCo 3.14's runs: the node
               process's CPU seconds, and WebAssembly's CPU ms per mj_step in its own field
               (wasm_cpu_ms_per_physics_step), never beside a native one.
"""

import math
import statistics

REFERENCE = "reference"
REFERENCE_HALF = "reference half"
REFERENCE_DIVISOR = 4
REFERENCE_HALF_DIVISOR = 2


def reference_options(divisor=REFERENCE_DIVISOR):
    """The grasp options of the reference (divisor 4) and of its convergence check (2)."""
    return ["--exact", "--timestep-divisor", str(divisor)]


NON_FINITE = "non-finite"


def outcome_of(run):
    """A run's outcome. A run that started and then went non-finite (MuJoCo found a bad number and
    reset the state; graspcd stops the grasp with an error) is "non-finite": started, not held.
    Runs recorded before the study named it have "cannot start" and that error as message."""
    if run.get("outcome") == "cannot start" and "went non-finite" in (run.get("message") or ""):
        return NON_FINITE
    return run.get("outcome")


def started(run):
    return run is not None and outcome_of(run) != "cannot start"


def held(run):
    return bool(run.get("held"))


def disagreement(run, reference):
    """None when either did not start; "held_ref_drops", "dropped_ref_holds" or "" (agree)."""
    if not started(run) or not started(reference):
        return None
    if held(run) == held(reference):
        return ""
    return "held_ref_drops" if held(run) else "dropped_ref_holds"


def percentile(values, q):
    """The q-th percentile (0-100) of values, by linear interpolation between closest ranks."""
    if not values:
        return None
    s = sorted(values)
    k = (len(s) - 1) * q / 100.0
    lo, hi = math.floor(k), math.ceil(k)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


def spread(values):
    return {"median": percentile(values, 50), "p99": percentile(values, 99),
            "max": max(values) if values else None, "n": len(values)}


def share(n, d):
    return None if d == 0 else n / d


def placements_of(document):
    """Every placement the reference started, with its runs by configuration."""
    return [p for p in document["placements"] if not p.get("skipped")]


def configuration_rates(placements, name):
    runs = [(p, p["runs"].get(name)) for p in placements if name in p["runs"]]
    begun = [(p, r) for p, r in runs if started(r)]
    verdicts = [disagreement(r, p["runs"].get(REFERENCE)) for p, r in begun]
    compared = [v for v in verdicts if v is not None]
    pen = [r["hand_penetration"] for _, r in begun if r.get("hand_penetration") is not None]
    pen_closed = [r["hand_penetration"] for _, r in begun
                  if r.get("hand_penetration") is not None and not r.get("partial")]
    steps = sum(r.get("closing_steps") or 0 for _, r in begun if r.get("phantom") is not None)
    cpu = [r["cpu_s"] for _, r in begun if r.get("cpu_s") is not None]
    wall = [r["wall_s"] for _, r in begun if r.get("wall_s") is not None]
    step_ms = [r["ms_per_physics_step"] for _, r in begun
               if r.get("ms_per_physics_step") is not None]
    step_cpu_ms = [r["cpu_ms_per_physics_step"] for _, r in begun
                   if r.get("cpu_ms_per_physics_step") is not None]
    step_wasm_ms = [r["wasm_cpu_ms_per_physics_step"] for _, r in begun
                    if r.get("wasm_cpu_ms_per_physics_step") is not None]
    # Held at the lift and then in all six directions, over the started runs (one that went
    # non-finite had no test: not held in six). Runs of a study made before the test (none has a
    # count) have no rate.
    tested = any(isinstance(r.get("six_directions"), int) for _, r in begun)
    six = [held(r) and r.get("six_directions") == 6 for _, r in begun] if tested else []
    return {
        "placements": len(runs),
        "starts": share(len(begun), len(runs)),
        "cannot_start": len(runs) - len(begun),
        "non_finite": sum(outcome_of(r) == NON_FINITE for _, r in begun),
        "held": share(sum(held(r) for _, r in begun), len(begun)),
        "six": share(sum(six), len(six)) if six else None,
        "compared": len(compared),
        "disagree": share(sum(v != "" for v in compared), len(compared)),
        "held_ref_drops": share(compared.count("held_ref_drops"), len(compared)),
        "dropped_ref_holds": share(compared.count("dropped_ref_holds"), len(compared)),
        "penetration": spread(pen),
        "penetration_closed": spread(pen_closed),
        "partial_runs": sum(bool(r.get("partial")) for _, r in begun),
        "phantom_per_step": share(sum(r["phantom"] for _, r in begun
                                      if r.get("phantom") is not None), steps),
        "missed_per_step": share(sum(r["missed"] for _, r in begun
                                     if r.get("missed") is not None), steps),
        "cpu_s_median": statistics.median(cpu) if cpu else None,
        "cpu_s_mean": statistics.mean(cpu) if cpu else None,
        "wall_s_median": statistics.median(wall) if wall else None,
        "ms_per_physics_step": statistics.median(step_ms) if step_ms else None,
        "cpu_ms_per_physics_step": statistics.median(step_cpu_ms) if step_cpu_ms else None,
        "wasm_cpu_ms_per_physics_step": (statistics.median(step_wasm_ms) if step_wasm_ms
                                         else None),
    }


def convergence(placements):
    """The reference's own convergence: placements whose held verdict differs between half and a
    quarter of the scene's step, over those both started."""
    both = [p for p in placements
            if started(p["runs"].get(REFERENCE)) and started(p["runs"].get(REFERENCE_HALF))]
    changed = sum(held(p["runs"][REFERENCE]) != held(p["runs"][REFERENCE_HALF]) for p in both)
    return {"compared": len(both), "changed": changed, "share": share(changed, len(both))}


def rates(document):
    """The rates of a study document (run_objset.py's JSON): over the set, per object, the
    reference's convergence and the counts of placements, skipped starts and fitting objects."""
    every = document["placements"]
    kept = placements_of(document)
    names = document["configurations"]
    objects = sorted({p["object"] for p in every})
    per_object = {}
    for o in objects:
        mine = [p for p in kept if p["object"] == o]
        per_object[o] = {
            "placements": sum(p["object"] == o for p in every),
            "skipped": sum(p["object"] == o and bool(p.get("skipped")) for p in every),
            "partial": any(p["runs"].get(REFERENCE, {}).get("partial") for p in mine),
            "configurations": {n: configuration_rates(mine, n) for n in names}}
    fits = {}
    for hand in sorted({p["hand"] for p in every}):
        tried = {p["object"] for p in every if p["hand"] == hand}
        fit = {p["object"] for p in kept if p["hand"] == hand}
        fits[hand] = {"objects": len(tried), "fit": len(fit)}
    return {"placements": len(every), "skipped": len(every) - len(kept), "fits": fits,
            "convergence": convergence(kept),
            "configurations": {n: configuration_rates(kept, n) for n in names},
            "objects": per_object}
