"""The race against MuJoCo 3.14 (its rows "3.14 hull", "3.14 sdf", "3.14 sdf10", "3.14 flex",
study/race_judged.py): on the scenes 3.14 raced, each configuration beside graspcd's at the same
noslip setting (outcome of the lift and of the six directions, true penetration into the hand,
phantom and missed contacts, step cost: native and WebAssembly apart, never divided), and the
paragraph, computed from those rows, of where graspcd is better than MuJoCo 3.14 and where it is
not."""

import os
import statistics

import race_judged  # study/race_judged.py (on the path: sections/__init__.py)
import race_score  # study/race_score.py

from sections.numbers import opt

# How much deeper a true penetration must be to count as deeper: the start check's tolerance,
# as the race's findings use it (sections/race_findings.py).
from sections.race_findings import PENETRATION_SLACK


def mujoco3_section(race):
    """The subsection, or [] for a race.json without MuJoCo 3.14's rows."""
    scenes = {s: e for s, e in race["scenes"].items()
              if any(is_mujoco3(r) for r in e["rows"])}
    if not scenes:
        return []
    lines = []
    w = lines.append
    w("")
    w("### Against MuJoCo 3.14: the mesh SDF, the rigid flex and its hull")
    w("")
    w("MuJoCo 3.14 (the official WebAssembly build, `@mujoco/mujoco` 3.14.0, run by node:"
      " `tools/mujoco3/grasp3.mjs`, docs/mujoco3.md) drives the same grasp from each scene's"
      " `\"grasp\"` section with the object collided four ways: its hull with multiccd on (3.14's"
      " default; \"3.14 hull\"), the mesh as a signed distance field (`type=\"sdf\"`,"
      " `sdf_initpoints` 40, its default: \"3.14 sdf\"; 10: \"3.14 sdf10\") and a rigid flex of the"
      " mesh inflated by 0.5 mm (\"3.14 flex\"), each with the six-direction test after the hold,"
      " and writes a run record that `graspcd judge` judges on the true meshes, as every other"
      " row of the race (docs/run-record.md). Its step cost is WebAssembly's, the node"
      " process's CPU time around `mj_step` as the runner measures it (its wall time grows with"
      " whatever else the machine runs; a cost marked \"(wall)\" comes from a record made before"
      " the runner measured CPU time), in its own column: it says what a 3.14 user running this"
      " build pays, not what native MuJoCo 3.14 costs, and is never set against a native step"
      " cost."
      " The scenes of the project's own hand run on graspcd's C++ controllers, which the node"
      " runner does not drive, and are not raced in 3.14; the scenes without 3.14's rows: "
      + not_raced(race) + ".")
    missing = not_run(scenes)
    if missing:
        w("")
        w("Runs of 3.14 this race did not make (`run_race.py --mujoco3-kept-only`: no record was"
          " kept for them): " + "; ".join(missing) + ".")
    w("")
    w("Per configuration, over the runs of the scenes 3.14 raced (scene and noslip setting):"
      " the runs that kept the object (held, tilted or not) and the outcomes of the others,"
      " the six directions held over the runs that had the test, the deepest true penetration"
      " into the hand (median and largest over the runs that started), the judge's phantom and"
      " missed contacts per closing grasp step (mean), and the step cost (median; native and"
      " WebAssembly apart).")
    w("")
    w("| configuration | noslip | runs | kept | not kept | six directions held |"
      " true penetration into the hand, median / largest (mm) | phantom per step |"
      " missed per step | step cost, native (CPU ms) | step cost, WebAssembly (CPU ms) |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for name in configuration_order(scenes):
        noslips = sorted({r.get("noslip") for e in scenes.values() for r in e["rows"]
                          if r["configuration"] == name}, key=lambda n: (n is None, n))
        for noslip in noslips:
            w(summary_line(name, noslip, group(scenes, name, noslip)))
    w("")
    w(overview(scenes))
    w("")
    lines.extend(verdict_paragraph(scenes))
    return lines


def overview(scenes):
    """One paragraph of the configurations' totals, from the rows: graspcd's beside each of
    3.14's, noslip off and on."""
    names = ["graspcd"] + [n for n in configuration_order(scenes) if n.startswith("3.14 ")]
    noslips = sorted({r.get("noslip") for e in scenes.values() for r in e["rows"]
                      if is_mujoco3(r)}, key=lambda n: (n is None, n))
    parts = []
    for noslip in noslips:
        said = []
        for name in names:
            rows = group(scenes, name, noslip)
            if not rows:
                continue
            kept = sum(1 for r in rows if race_score.kept(r))
            six = [r["six_directions"] for r in rows if r.get("six_directions")]
            tps = [race_score.hand_penetration(r) for r in rows
                   if race_score.row_outcome(r) != "cannot start"
                   and race_score.hand_penetration(r) is not None]
            errors = [(r["phantom"] + r["missed"]) / r["closing_steps"] for r in rows
                      if r.get("phantom") is not None and r.get("closing_steps")]
            said.append(
                f"{name} kept {kept} of {len(rows)}"
                + ("" if not six else
                   f", held {sum(s['held'] for s in six)} of {sum(s['of'] for s in six)}"
                   " directions")
                + ("" if not tps else f", at most {1000 * max(tps):.2f} mm into the hand")
                + ("" if not errors else
                   f", {statistics.mean(errors):.2f} phantom and missed contacts per step"))
        parts.append(f"With noslip {noslip}: " + "; ".join(said) + ".")
    ours = [r["ms_per_physics_step"] for e in scenes.values() for r in e["rows"]
            if r["configuration"] == "graspcd" and r.get("ms_per_physics_step") is not None
            and r.get("step_clock") == "cpu"]
    costs = []
    for name in names[1:]:
        wasm = [r["ms_per_physics_step_wasm"] for e in scenes.values() for r in e["rows"]
                if r["configuration"] == name and r.get("ms_per_physics_step_wasm") is not None
                and r.get("step_clock") == "cpu"]
        if wasm:
            costs.append(f"{name} {min(wasm):.2f}-{max(wasm):.2f} ms of CPU in WebAssembly")
    if ours and costs:
        parts.append(f"A physics step cost graspcd {min(ours):.3f}-{max(ours):.3f} ms of CPU"
                     " (C++, native) and " + ", ".join(costs) + "; the two are different builds"
                     " and are not set against each other.")
    return "Over these scenes (runs kept, six directions held, deepest true penetration into" \
        " the hand, phantom and missed contacts per closing step): " + " ".join(parts)


def is_mujoco3(r):
    return r["configuration"].startswith("3.14 ")


def not_raced(race):
    """The scenes without 3.14's rows, by why: the project's hand (no "grasp" section in the
    scene's pair config), or the note race.json keeps."""
    why = {}
    for s, e in race["scenes"].items():
        if any(is_mujoco3(r) for r in e["rows"]):
            continue
        note = e.get("mujoco3")
        if not race_judged.driven(os.path.join(race_judged.ROOT, "mjcf", s + ".xml")):
            reason = "the project's hand, no \"grasp\" section"
        elif isinstance(note, str):
            reason = note
        else:
            reason = "not raced in 3.14 in this file"
        why.setdefault(reason, []).append(s)
    return "; ".join(f"{', '.join(s)} ({n})" for n, s in why.items()) or "none"


def not_run(scenes):
    """The 3.14 runs a race left out (--mujoco3-kept-only), as "scene: configuration noslip N"."""
    out = []
    for s, e in scenes.items():
        note = e.get("mujoco3")
        if isinstance(note, dict):
            out.extend(f"{s}: {x['configuration']} noslip {x['noslip']}" for x in note["not_run"])
    return out


def configuration_order(scenes):
    """graspcd's configurations first, then MuJoCo 2.2's, then 3.14's, each in first-seen
    order."""
    seen = []
    for e in scenes.values():
        for r in e["rows"]:
            if r["configuration"] not in seen:
                seen.append(r["configuration"])
    return sorted(seen, key=lambda n: (0 if n.startswith("graspcd") else
                                       2 if n.startswith("3.14 ") else 1, seen.index(n)))


def per_step(rows, key):
    values = [r[key] / r["closing_steps"] for r in rows
              if r.get(key) is not None and r.get("closing_steps")]
    return statistics.mean(values) if values else None


def group(scenes, name, noslip):
    """The rows of one configuration and noslip setting over the scenes."""
    return [r for e in scenes.values() for r in e["rows"]
            if r["configuration"] == name and r.get("noslip") == noslip]


def summary_line(name, noslip, rows):
    started = [r for r in rows if race_score.row_outcome(r) != "cannot start"]
    kept = [r for r in rows if race_score.kept(r)]
    others = {}
    for r in rows:
        if not race_score.kept(r):
            o = race_score.row_outcome(r)
            others[o] = others.get(o, 0) + 1
    six = [r["six_directions"] for r in rows if r.get("six_directions")]
    six_cell = (f"{sum(s['held'] for s in six)} of {sum(s['of'] for s in six)}" if six
                else "-")
    tps = [race_score.hand_penetration(r) for r in started
           if race_score.hand_penetration(r) is not None]
    tp_cell = (f"{1000 * statistics.median(tps):.2f} / {1000 * max(tps):.2f}" if tps else "-")

    def median(key):
        # CPU costs only; the wall costs of runs that did not measure CPU time, marked, where
        # no run of the configuration did.
        cpu = [r[key] for r in rows if r.get(key) is not None and r.get("step_clock") == "cpu"]
        wall = [r[key] for r in rows if r.get(key) is not None and r.get("step_clock") != "cpu"]
        if cpu:
            return f"{statistics.median(cpu):.3f}"
        return f"{statistics.median(wall):.3f} (wall)" if wall else None

    return (f"| {name} | {'-' if noslip is None else noslip} | {len(rows)} | {len(kept)} |"
            f" {', '.join(f'{n} {o}' for o, n in others.items()) or '-'} | {six_cell} |"
            f" {tp_cell} | {opt(per_step(started, 'phantom'), '.2f')} |"
            f" {opt(per_step(started, 'missed'), '.2f')} |"
            f" {median('ms_per_physics_step') or '-'} |"
            f" {median('ms_per_physics_step_wasm') or '-'} |")


def compare(ours, theirs):
    """How a 3.14 row stands against graspcd's at the same scene and noslip: "better" (for
    graspcd), "worse" or "even", by the outcome's rank, then the six directions held, then the
    true penetration into the hand (deeper by more than the slack)."""
    a, b = race_score.RANK[race_score.row_outcome(ours)], race_score.RANK[
        race_score.row_outcome(theirs)]
    if a != b:
        return "better" if a < b else "worse"
    if not race_score.kept(ours):
        return "even"
    sa = (ours.get("six_directions") or {}).get("held")
    sb = (theirs.get("six_directions") or {}).get("held")
    if sa is not None and sb is not None and sa != sb:
        return "better" if sa > sb else "worse"
    ta, tb = race_score.hand_penetration(ours), race_score.hand_penetration(theirs)
    if ta is not None and tb is not None:
        if tb > ta + PENETRATION_SLACK:
            return "better"
        if ta > tb + PENETRATION_SLACK:
            return "worse"
    return "even"


def short(r):
    """A row's outcome, six directions and hand penetration in a few words."""
    o = race_score.row_outcome(r)
    if o == "cannot start":
        return "cannot start"
    six = r.get("six_directions")
    tp = race_score.hand_penetration(r)
    return (o + ("" if not six else f", {six['held']} of {six['of']} directions")
            + ("" if tp is None else f", {1000 * tp:.2f} mm into the hand"))


def verdict_paragraph(scenes):
    """Where graspcd is better than 3.14 and where not: each 3.14 run against graspcd's row of
    the same scene and noslip setting (compare), then the penetration, contact errors, costs
    and noslip, all from the rows."""
    better, worse, even = [], [], []
    for scene, e in scenes.items():
        for r in e["rows"]:
            if not is_mujoco3(r):
                continue
            ours = next((o for o in e["rows"] if o["configuration"] == "graspcd"
                         and o.get("noslip") == r.get("noslip")), None)
            if ours is None:
                continue
            where = f"{scene} noslip {r.get('noslip')}"
            item = (f"{where}, {r['configuration']}: {short(r)} against graspcd's {short(ours)}")
            {"better": better, "worse": worse, "even": even}[compare(ours, r)].append(item)
    lines = []
    w = lines.append
    total = len(better) + len(worse) + len(even)
    w(f"Each of 3.14's {total} runs set against graspcd's at the same scene and noslip setting"
      " (the outcome first, then the six directions held, then a true penetration into the hand"
      f" deeper by more than {1000 * PENETRATION_SLACK:g} mm): graspcd does better in"
      f" {len(better)}, 3.14 in {len(worse)}, and they are even in {len(even)}.")
    for title, items in (("graspcd better", better), ("3.14 better", worse)):
        w("")
        w(f"{title}:")
        w("")
        lines.extend(f"- {x}." for x in items) if items else w("- nowhere.")
    return lines
