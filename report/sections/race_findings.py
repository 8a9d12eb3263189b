"""The race's findings, computed from its rows at each scene and noslip setting: where exactness
changes the outcome (graspcd keeps the object and a cheaper configuration does not), where
MuJoCo's own route, the hull or a decomposition, is as good and cheaper (no worse an outcome, a
true penetration no deeper than graspcd's by more than the start check's 0.5 mm, a lower step
cost), where MuJoCo's noslip solver changes whether the object is kept, and the best row by the
race's score (study/race_score.py)."""

import race_score  # study/race_score.py (on the path: sections/__init__.py)

# How much deeper than graspcd's a configuration's true penetration may be and still count as
# good as graspcd's: the start check's tolerance (grasp/start_check.h, kStartPenetration), m.
PENETRATION_SLACK = 0.5e-3


def race_findings(race):
    exact, cheap_good, verdicts = [], [], []
    for scene, e in race["scenes"].items():
        by_noslip = {}
        for r in e["rows"]:
            by_noslip.setdefault(r.get("noslip"), []).append(r)
        for noslip, rows in by_noslip.items():
            ours = next((r for r in rows if r["configuration"] == "graspcd"), None)
            if ours is None or ours.get("ms_per_physics_step") is None:
                continue
            where = scene + ("" if noslip is None else f", noslip {noslip}")
            cheaper = [r for r in rows if r is not ours and r.get("ms_per_physics_step") is not None
                       and r["ms_per_physics_step"] < ours["ms_per_physics_step"]]
            exact.extend(exactness_finding(where, ours, rows, cheaper))
            cheap_good.extend(as_good_finding(where, ours, cheaper))
            best = min(rows, key=race_score.score)
            if "outcome" in best:
                cost = (f"{best['ms_per_physics_step']:.3f} ms"
                        if best.get("ms_per_physics_step") is not None else
                        f"{best['ms_per_physics_step_wasm']:.3f} ms of CPU in WebAssembly")
                verdicts.append(f"- {where}: best {best['configuration']}"
                                f" ({shown_outcome(best)},"
                                f" {1000 * race_score.hand_penetration(best):.2f} mm into the"
                                f" hand, {best['contact_error_per_step']:.2f} errors per step,"
                                f" {cost}).")
    return findings_text(exact, cheap_good, noslip_changes(race), verdicts)


def exactness_finding(where, ours, rows, cheaper):
    """[a line] when graspcd kept the object and a cheaper configuration, or one that could not
    start, did not; else []."""
    # Runs that could not start cost nothing: they lose whatever graspcd did.
    refused = [r for r in rows if r is not ours and
               race_score.row_outcome(r) == "cannot start"]
    if not race_score.kept(ours):
        return []
    lost = [r for r in cheaper + refused if not race_score.kept(r)
            and not r["configuration"].startswith("graspcd")]
    if not lost:
        return []
    return [f"- {where}: graspcd {shown_outcome(ours)}; "
            + ", ".join(f"{r['configuration']} {shown_outcome(r)}" for r in lost) + "."]


def as_good_finding(where, ours, cheaper):
    """[a line] naming the cheaper runs of MuJoCo's routes that are as good as graspcd's; else
    []."""
    o_rank = race_score.RANK[shown_outcome(ours)]
    o_tp = race_score.hand_penetration(ours)
    o_err = round(ours["contact_error_per_step"], 2)
    good = []
    for r in cheaper:
        if r["configuration"].startswith("graspcd"):
            continue
        if race_score.RANK[race_score.row_outcome(r)] > o_rank:
            continue
        tp = race_score.hand_penetration(r)
        if (o_tp is None) != (tp is None):
            continue
        if tp is not None and tp > o_tp + PENETRATION_SLACK:
            continue
        # Compared as printed (2 decimals).
        if round(r["contact_error_per_step"], 2) > o_err:
            continue
        good.append(r)

    def numbers(r):
        tp = race_score.hand_penetration(r)
        return (f"{r['ms_per_physics_step']:.3f} ms"
                + ("" if tp is None else f", {1000 * tp:.2f} mm into the hand")
                + f", {r['contact_error_per_step']:.2f} errors per step")
    if not good:
        return []
    return [f"- {where}: graspcd {shown_outcome(ours)}, {numbers(ours)}; "
            + "; ".join(f"{r['configuration']} {shown_outcome(r)}, {numbers(r)}"
                        for r in good) + "."]


def noslip_changes(race):
    """The configurations kept with noslip off and not with it on, or the other way round."""
    rescued = []
    for scene, e in race["scenes"].items():
        off = {r["configuration"]: r for r in e["rows"] if r.get("noslip") == 0}
        for r in e["rows"]:
            if not r.get("noslip") or r["configuration"] not in off:
                continue
            before = off[r["configuration"]]
            if race_score.kept(r) != race_score.kept(before):
                rescued.append(f"{scene} {r['configuration']} ({shown_outcome(before)} at"
                               f" noslip 0, {shown_outcome(r)} at {r['noslip']})")
    return rescued


def findings_text(exact, cheap_good, rescued, verdicts):
    lines = []
    w = lines.append
    w("Where exactness changes the outcome: graspcd kept the object (held, tilted or not) and a"
      " configuration cheaper per step, or one that could not start, at the same noslip setting"
      " did not:")
    w("")
    lines.extend(exact or ["- none of these scenes."])
    w("")
    w("Where MuJoCo's own route is as good and cheaper: a run of the hull or of a decomposition"
      " (with or without multiccd) with an outcome no"
      " worse than graspcd's, a true penetration into the hand no deeper than graspcd's by more"
      f" than {1000 * PENETRATION_SLACK:g} mm (the start check's tolerance; rows of an earlier"
      " race, without true penetration, by outcome and contact error alone), no more contact"
      " error (as printed) and a lower step cost, at the same noslip setting:")
    w("")
    lines.extend(cheap_good or ["- none of these scenes."])
    w("")
    w("Where MuJoCo's noslip solver changes whether the object is kept (the same configuration"
      " with noslip off and on): " + ("; ".join(rescued) if rescued else "nowhere") + ".")
    if verdicts:
        w("")
        w("The best row of each scene and noslip setting by the race's score (outcome, true"
          " penetration into the hand, contact error):")
        w("")
        lines.extend(verdicts)
    return lines


def shown_outcome(r):
    """A row's outcome as the findings name it: "not held" for a row of an earlier race, which
    recorded neither the tilt nor an ejection."""
    if "outcome" in r:
        return r["outcome"]
    return "held" if r.get("held") else "not held"
