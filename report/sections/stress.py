"""The section "Numerical stability (stress)" from `graspcd stress --json`: every class of
generated pairs against every method, CGAL deciding each pair, and what the counts say."""


def stress_gap(v):
    return "-" if v is None else ("0" if v == 0 else f"{v:.3g}")


def stress_section(stress):
    """The "Numerical stability (stress)" section from `graspcd stress --json`."""
    lines = []
    w = lines.append
    rows = stress["rows"]
    tol = stress["tolerances"]
    total = {}
    for r in rows:
        total[r["class"]] = r["cases"]
    w("## Numerical stability (stress)")
    w("")
    w(f"From `stress.json` (`graspcd stress --json`, seed {stress['seed']}"
      f"{', --quick: not for quoting' if stress['quick'] else ''}; {sum(total.values())} pairs in"
      f" {len(total)} classes, {stress['seconds']:.0f} s). Each pair is built around a known"
      " contact and moved apart or into contact by a signed gap; CGAL decides each pair on the"
      " doubles as generated. Box pairs go to every method (a fresh detector per pair), triangle"
      " pairs to the core's test, its exact fallback and the two reference Möller variants.")
    w("")
    for c in stress["classes"]:
        if c["name"] in total:
            w(f"- `{c['name']}` ({total[c['name']]} pairs): {c['description']}.")
    w("")
    w("| class | method | pairs | overlapping | false separations | false overlaps |"
      " largest false-overlap gap (rel.) | outside band | perceptron capped |")
    w("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        name = r["method"] + (" (reference)" if r["reference"] else "")
        capped = "-" if r["perceptron_capped"] is None else r["perceptron_capped"]
        w(f"| {r['class']} | {name} | {r['cases']} | {r['overlapping']} |"
          f" {r['false_separated']} | {r['false_overlap']} |"
          f" {stress_gap(r['max_false_overlap_gap_rel'])} | {r['outside_band']} | {capped} |")
    w("")
    w("The relative gap is the exact `box_box_gap` of a falsely overlapping box pair divided by"
      " both boxes' half-extents summed plus |cB - cA|_1, the scale of `kSatRelativeSlack`"
      f" ({tol['sat_relative_slack']:g}). Outside band: for sat, sat-cached and the Neuro-SATs,"
      " false overlaps whose exact gap on one of the 15 axes exceeds the slack of"
      " `tolerances.h` plus the SAT's rounding; for the exact triangle tests, any false overlap."
      f" Perceptron capped: tests that used all their passes (cap {tol['perceptron_cap']},"
      f" Neuro-SAT's switch {tol['neurosat_switch']}), overlapping pairs included.")
    w("")
    lines.extend(stress_findings(stress))
    return lines


def stress_findings(stress):
    """What the stress table says: false separations, false overlaps outside the band, SAT's and
    the perceptron's largest gaps, the reference Möller variants' misses."""
    lines = []
    w = lines.append
    rows = stress["rows"]
    tol = stress["tolerances"]
    real = [r for r in rows if not r["reference"]]
    broken = [r for r in real if r["false_separated"] > 0]
    if broken:
        w("**False separations** (a missed collision): " + ", ".join(
            f"{r['method']} on {r['class']} ({r['false_separated']})" for r in broken) + ".")
    else:
        w("No method of the core separated an overlapping pair in any class.")
    out_band = [r for r in real if r["outside_band"] > 0]
    if out_band:
        w(" **Outside the documented band:** " + ", ".join(
            f"{r['method']} on {r['class']} ({r['outside_band']})" for r in out_band) + ".")
    else:
        w(" Every false overlap of the SAT family lies within the slack of `tolerances.h`, and the"
          " exact triangle tests made no error.")
    sat_rows = [r for r in real if r["kind"] == "boxes" and r["method"] == "sat"]
    if sat_rows:
        worst = max(sat_rows, key=lambda r: r["max_false_overlap_gap_rel"] or 0)
        gap = worst["max_false_overlap_gap_rel"] or 0
        if gap > 10 * tol["sat_relative_slack"]:
            w(f" SAT's largest false-overlap gap, {gap:.3g} of the pair's size in"
              f" `{worst['class']}`, is {gap / tol['sat_relative_slack']:.3g} times"
              " `kSatRelativeSlack`: the slack is compared with unnormalised axes, and the"
              " cross-product axis of two nearly parallel edges has length sin(angle), so in metres"
              " it allows slack / sin(angle) (as `tolerances.h` documents)" +
              ("; still inside the band." if worst["outside_band"] == 0 else "."))
        else:
            w(f" SAT's largest false-overlap gap is {gap:.3g} of the pair's size"
              f" (`{worst['class']}`).")
    perc = [r for r in real if r["kind"] == "boxes" and r["method"] == "perceptron"]
    if perc:
        worst = max(perc, key=lambda r: r["max_false_overlap_gap_rel"] or 0)
        w(f" The perceptron (cap {tol['perceptron_cap']}) left disjoint pairs unproven up to a gap"
          f" of {stress_gap(worst['max_false_overlap_gap_rel'])} of the pair's size"
          f" (`{worst['class']}`); they go down the tree, they are not errors of the answer.")
    missed = {}
    for r in rows:
        if r["reference"]:
            missed[r["method"]] = missed.get(r["method"], 0) + r["false_separated"]
    if any(missed.values()):
        w(" The reference Möller variants, kept only to be measured, missed intersections: " +
          ", ".join(f"{m} {n} pairs" for m, n in missed.items()) + ".")
    w("")
    return lines
