#!/usr/bin/python3
"""Draws the study's figures and writes REPORT.md from what `graspcd study` wrote.

Usage: /usr/bin/python3 report/make_report.py OUT_DIR
Reads OUT_DIR/study.json (Table 1, the box hand of Figures 13-15, recordings, machine, build),
OUT_DIR/sweep.json (the run-time/error sweep, possibly merged from shards) and, if present,
OUT_DIR/stress.json (`graspcd stress --json`, the numerical stress suite) and
OUT_DIR/perf.json (`./run perf`, graspcd against FCL and MuJoCo),
OUT_DIR/contacts.json (report/contacts_solver.py, what MuJoCo's solver gets) and
OUT_DIR/race.json, else the cached report/data/race.json (study/run_race.py, graspcd
against the hull and convex decompositions), writes
OUT_DIR/REPORT.md and OUT_DIR/figures/*.png. Every number in the report comes from those files; the text around a
number is chosen by comparing numbers, never written in advance.

Run with Debian's /usr/bin/python3 (python3-matplotlib), not whatever python3 is first on PATH.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import draw_figures  # noqa: E402  (report/draw_figures.py, beside this script)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "study"))
import race_score  # noqa: E402  (study/race_score.py: the race's outcome and score)

# bridge::finger_segment_names(): the order of every per-segment array in study.json.
SEGMENTS = [f"finger{f}_{s}" for f in range(1, 5) for s in "ABC"]

METHOD_COLORS = {"sat": "tab:blue", "perceptron": "tab:red", "neurosat": "tab:green"}


def fail(message):
    print(f"make_report.py: {message}", file=sys.stderr)
    sys.exit(2)


def load(path, required=True):
    if not os.path.exists(path):
        if required:
            fail(f"{path}: missing (run graspcd study first)")
        return None
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except json.JSONDecodeError as e:
        fail(f"{path}:{e.lineno}: not JSON ({e.msg})")


def ms(v):
    return f"{v:.3g}" if v < 100 else f"{v:.0f}"


def ratio_text(r):
    return f"{r:.3g}"


def cumulative(values):
    out, total = [], 0.0
    for v in values:
        total += v
        out.append(total)
    return out


def box_method(study, name):
    for m in study["box_hand"]["methods"]:
        if m["name"] == name:
            return m
    return None


def finish_box_figure(fig, axes, ylabel, title, fig_dir, name, files, legend_below=False):
    """The shared frame of Figures 13-15: one panel per segment kind, saved as PNG. With
    `legend_below`, the methods' legend goes under the panels, where it covers no line."""
    for ax, seg in zip(axes, ["B", "C"]):
        ax.set_xlabel("grasp step")
        ax.set_title(f"segments {seg}")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel(ylabel)
    fig.suptitle(title)
    if legend_below:
        handles, labels = axes[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 7), fontsize=8,
                   frameon=False)
        fig.tight_layout(rect=(0, 0.08, 1, 1))
    else:
        fig.tight_layout()
    files.append(name)
    fig.savefig(os.path.join(fig_dir, name), dpi=110)
    plt.close(fig)


def figure_13_to_15(study, fig_dir):
    box = study["box_hand"]
    names = [m["name"] for m in box["methods"]]
    steps = list(range(1, box["steps"] + 1))
    files = []

    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, seg in zip(axes, ["B", "C"]):
        for m in box["methods"]:
            y = [v / 1e3 for v in m["segments"][seg]["step_ns_median"]]
            ax.plot(steps, y, label=m["name"], color=METHOD_COLORS.get(m["name"]))
        ax.set_yscale("log")
    finish_box_figure(fig, axes, "detection time per grasp step (µs, median)",
                      "Figure 13: detection time per grasp step, box hand", fig_dir,
                      "fig13_time_per_step.png", files, legend_below=True)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, seg in zip(axes, ["B", "C"]):
        for m in box["methods"]:
            if m["name"] == "sat":
                continue
            ax.plot(steps, [max(p, 0.5) for p in m["segments"][seg]["passes"]], label=m["name"],
                    color=METHOD_COLORS.get(m["name"]))
        bound = [b if b > 0 else float("nan") for b in box["bounds"][seg]["novikoff_max_finite"]]
        ax.plot(steps, bound, ":", color="gray", label="Novikoff bound (R/γ)², largest finite")
        ax.set_yscale("log")
    axes[0].legend(fontsize=8)
    finish_box_figure(fig, axes, "perceptron passes per grasp step",
                      "Figure 14: perceptron passes per grasp step, box hand", fig_dir,
                      "fig14_passes.png", files)

    sat = box_method(study, "sat")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, seg in zip(axes, ["B", "C"]):
        base = sat["segments"][seg]["step_ns_median"]
        for m in box["methods"]:
            if m["name"] == "sat":
                continue
            own = m["segments"][seg]["step_ns_median"]
            saved = cumulative([(b - o) / 1e3 for b, o in zip(base, own)])
            ax.plot(steps, saved, label=m["name"], color=METHOD_COLORS.get(m["name"]))
        ax.axhline(0, color="black", lw=0.8)
        ax.set_yscale("symlog", linthresh=1)
    axes[0].legend()
    finish_box_figure(fig, axes, "cumulative time saved against SAT (µs)",
                      "Figure 15: cumulative time saved against SAT (negative: lost), box hand",
                      fig_dir, "fig15_time_saved.png", files)
    return names, files


def table1_figure(study, fig_dir):
    t = study["table1"]
    sat = next(m for m in t["methods"] if m["name"] == "sat")
    fig, ax = plt.subplots(figsize=(10, 4.5))
    n = len(t["methods"])
    width = 0.8 / max(n, 1)
    for i, m in enumerate(t["methods"]):
        ratios = [x["median_ms"] / s["median_ms"] for x, s in zip(m["examples"], sat["examples"])]
        xs = [e + (i - n / 2 + 0.5) * width for e in range(len(t["examples"]))]
        ax.bar(xs, ratios, width, label=m["name"])
    for e, name in enumerate(t["examples"]):
        for key, marker in (("perceptron", "v"), ("neurosat", "^")):
            paper = next((m for m in t["methods"] if m["name"] == key and "paper_s" in m), None)
            if paper and e < len(paper["paper_s"]):
                psat = sat.get("paper_s", [None] * 3)[e]
                if psat:
                    ax.plot(e, paper["paper_s"][e] / psat, marker, color="black", ms=9)
    ax.plot([], [], "v", color="black", label="paper: perceptron / SAT")
    ax.plot([], [], "^", color="black", label="paper: Neuro-SAT / SAT")
    ax.set_yscale("log")
    ax.set_xticks(range(len(t["examples"])))
    ax.set_xticklabels(t["examples"])
    ax.set_ylabel("total detection time / SAT's (log)")
    ax.axhline(1, color="black", lw=0.8)
    ax.legend(fontsize=8, ncol=2)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.set_title("Table 1 as ratios to SAT: ours (bars) and the paper's (markers)")
    fig.tight_layout()
    fig.savefig(os.path.join(fig_dir, "table1_ratios.png"), dpi=110)
    plt.close(fig)
    return "table1_ratios.png"


def pareto(points):
    """Indices of the points no other point beats on every objective (lower is better)."""
    front = []
    for i, p in enumerate(points):
        dominated = any(all(b <= a for a, b in zip(p, q)) and any(b < a for a, b in zip(p, q))
                        for j, q in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return front


def sweep_error(c):
    """Missed and false contacts per (grasp step, pair), plus wrong triangle pairs."""
    return (c["missed"] + c["false_contacts"] + c.get("missed_tri_pairs", 0) +
            c.get("false_tri_pairs", 0))


# Sweep labels of points within this factor of each other in time are staggered.
LABEL_GAP = 3.0


def sweep_figure(sweep, fig_dir):
    configs = sweep["configs"]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    pts = [(c["median_ms"], sweep_error(c)) for c in configs]
    # The front over time, count errors and contact position error together.
    front = pareto([(c["median_ms"], sweep_error(c), c["position_error_mean_mm"]) for c in configs])
    families = sorted({c["family"] for c in configs})
    cmap = plt.get_cmap("tab10")
    for k, fam in enumerate(families):
        idx = [i for i, c in enumerate(configs) if c["family"] == fam]
        axes[0].scatter([pts[i][0] for i in idx], [pts[i][1] for i in idx], color=cmap(k % 10),
                        label=fam, s=30)
        axes[1].scatter([configs[i]["median_ms"] for i in idx],
                        [configs[i]["position_error_mean_mm"] for i in idx], color=cmap(k % 10),
                        label=fam, s=30)
    fx = sorted((pts[i] for i in front))
    axes[0].plot([p[0] for p in fx], [p[1] for p in fx], "k--", lw=1, label="Pareto front")
    # Labels only where they say something: the front and the points with errors. Points closer
    # than a factor LABEL_GAP in time get their labels on staggered heights, each joined to its
    # point by a thin line, so that no two labels overlap.
    labelled = sorted((i for i, c in enumerate(configs)
                       if i in front or pts[i][1] > 0 or c["position_error_mean_mm"] > 0),
                      key=lambda i: pts[i][0])
    level, last_x = 0, None
    for i in labelled:
        c = configs[i]
        x = pts[i][0]
        level = level + 1 if last_x is not None and x < last_x * LABEL_GAP else 0
        last_x = x
        line = dict(arrowstyle="-", lw=0.5, color="#555555")
        axes[0].annotate(c["name"], pts[i], fontsize=7, xytext=(6, 10 + 14 * level),
                         textcoords="offset points", arrowprops=line)
        axes[1].annotate(c["name"], (c["median_ms"], c["position_error_mean_mm"]), fontsize=7,
                         xytext=(6, -14 - 14 * level), textcoords="offset points",
                         arrowprops=line)
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("replay time, all grasp steps (ms, median)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_yscale("symlog", linthresh=1)
    axes[0].set_ylim(bottom=-0.3)
    axes[0].set_ylabel("missed + false contacts and triangle pairs, against CGAL")
    axes[1].set_yscale("symlog", linthresh=0.01)
    axes[1].set_ylim(bottom=-0.003)
    axes[1].set_ylabel("mean contact position error (mm)")
    axes[0].legend(fontsize=7, loc="center right")
    fig.suptitle("Run time against error (sweep); ★ in REPORT.md: the Pareto front")
    fig.tight_layout()
    fig.savefig(os.path.join(fig_dir, "sweep_pareto.png"), dpi=110)
    plt.close(fig)
    return "sweep_pareto.png", [configs[i]["name"] for i in front]


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


# --- Performance: from perf.json of `./run perf` --------------------------------------------------

PERF_GROUPS = [
    ("obb_test", "One OBB test (65,536 pairs, ns per test)"),
    ("mesh", "Mesh against mesh: two 3,968-triangle spheres (r = 5 cm), every method"),
    ("trajectory", "Along coherent trajectories (0.003 rad a step): ours with temporal coherence"
                   " (sat-cached) per step"),
    ("trajectory_plain", "Along the same trajectories without coherence (ours-sat against FCL)"),
    ("build", "Tree build (UV spheres)"),
    ("scaling", "Query cost against triangle count (two UV spheres, all contacts)"),
    ("mujoco", "In MuJoCo: mj_step of the triangle hand"),
    ("grasp", "Whole grasps: consecutive physics steps (close, squeeze, lift, hold), served"
              " (the default: contacts reused within 20 µm) against native, and the front list"
              " against descents from the roots (us per physics step)"),
    ("grasp_exact", "Whole grasps with exact contacts every step (\"contact_reuse\": 0,"
                    " `grasp --exact`) against native, and the default against them"),
    ("grasp_multiccd", "Whole grasps against MuJoCo with its multi-point convex collision"
                       " (native-multiccd, `grasp --multiccd`): served against it, and it against"
                       " plain native"),
]


def perf_time(bench):
    return f"{ms(bench['median'])} [{ms(bench['min'])}, {ms(bench['max'])}] {bench['unit']}"


def perf_ratio(c):
    return (f"{c['ratio_median']:.3f} [{c['ratio_min']:.3f}, {c['ratio_max']:.3f}]")


def perf_verdict(c):
    if c["target"] is None:
        return ""
    return f"≤ {c['target']:g}: {'met' if c['met'] else '**not met**'}"


def perf_figures(perf, fig_dir):
    """Query scaling and build scaling against triangle count; returns the file names drawn."""
    files = []
    comps = perf["comparisons"]
    bench = perf["benchmarks"]
    scaling = [c for c in comps if c["group"] == "scaling"]
    if scaling:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        for gap, style in (("near_miss_0.5mm", "-"), ("overlap_1mm", "--")):
            rows = sorted((c for c in scaling if f"/{gap}/" in c["ours"]), key=lambda c: c["faces"])
            for who, key, color in (("graspcd sat", "ours", "tab:blue"),
                                    ("FCL OBB", "peer", "tab:orange")):
                ax.plot([c["faces"] for c in rows], [bench[c[key]]["median"] for c in rows],
                        style, marker="o", color=color, label=f"{who}, {gap}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles per sphere")
        ax.set_ylabel("query time, median (µs)")
        ax.set_title("Query cost against triangle count")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(fig_dir, "perf_scaling.png"), dpi=110)
        plt.close(fig)
        files.append("perf_scaling.png")
    build = sorted((c for c in comps if c["group"] == "build"), key=lambda c: c["faces"])
    if build:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        ax.plot([c["faces"] for c in build], [c["ours_ns_per_nlogn"] for c in build], marker="o",
                label="graspcd")
        ax.plot([c["faces"] for c in build], [c["peer_ns_per_nlogn"] for c in build], marker="o",
                label="FCL OBB")
        ax.set_xscale("log")
        ax.set_ylim(bottom=0)
        ax.set_xlabel("triangles")
        ax.set_ylabel("build time / (n log2 n) (ns)")
        ax.set_title("Tree build: flat means n log n")
        ax.grid(True, alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(fig_dir, "perf_build.png"), dpi=110)
        plt.close(fig)
        files.append("perf_build.png")
    return files


def perf_section(perf, fig_dir, fig_rel):
    """The "Performance against FCL and MuJoCo" section from perf.json (`./run perf`)."""
    lines = []
    w = lines.append
    ctx = perf["context"]
    bench = perf["benchmarks"]
    comps = perf["comparisons"]
    w("## Performance against FCL and MuJoCo")
    w("")
    reps = max((b["repetitions"] for b in bench.values()), default=0)
    w(f"From `perf.json` (`./run perf`, {ctx.get('date', '?')}, host {ctx.get('host_name', '?')},"
      f" {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz,"
      f" {ctx.get('graspcd_build', 'build flags not recorded')}). Every comparison is measured in"
      f" the same run and given as the ratio ours / peer: the ratio of the medians of {reps}"
      " repetitions, with the min and max of the per-repetition ratios in brackets; times are"
      " CPU time, median [min, max]. Below 1 is faster than the peer.")
    load = ctx.get("load_avg")
    if load:
        busy = "others were running too, so the" if max(load) > 2 else "the"
        w("")
        w(f"Load average when the run started: {', '.join(f'{x:.2f}' for x in load)} on"
          f" {ctx.get('num_cpus', '?')} CPUs: {busy} times are noisy; the ratios, measured in"
          " the same run, are what to read.")
    w("")
    for group, title in PERF_GROUPS:
        rows = [c for c in comps if c["group"] == group]
        if not rows:
            continue
        w(f"### {title}")
        w("")
        extra = group in ("mesh", "scaling", "trajectory")
        head = "| case | ours | peer | ratio | target |"
        if extra:
            head += " box tests ours / peer | same answer |"
        w(head)
        w("|" + "---|" * (head.count("|") - 1))
        for c in rows:
            who = c["ours"].split("/")[-1]
            label = c["label"] if who in c["label"] else f"{c['label']} `{who}`"
            row = (f"| {label} | {perf_time(bench[c['ours']])} |"
                   f" {perf_time(bench[c['peer']])} | {perf_ratio(c)} | {perf_verdict(c)} |")
            if extra:
                bt, pbt = c.get("box_tests"), c.get("peer_box_tests")
                boxes = "" if bt is None or pbt is None else f"{bt:.0f} / {pbt:.0f}"
                same = c.get("agrees")
                if group == "trajectory":
                    same = c.get("hit_share") == c.get("peer_hit_share")
                row += f" {boxes} | {'yes' if same else '**no**'} |"
            w(row)
        if group == "trajectory":
            w("")
            w("FCL turns its early stop off when it starts from a front list"
              " (fcl/narrowphase/detail/traversal/traversal_recurse-inl.h), so its first-contact"
              " queries with the front list test every overlapping pair: the ratios against"
              " the front list in first-contact mode measure that, not our speed.")
        if group == "build":
            w("")
            w("Build time / (n log2 n), ns: " + ", ".join(
                f"{int(c['faces'])}: {c['ours_ns_per_nlogn']:.3g} (FCL {c['peer_ns_per_nlogn']:.3g})"
                for c in rows) + ".")
        w("")
    lines.extend(perf_floor_table(perf))
    for f in perf_figures(perf, fig_dir):
        w(f"![{f[:-4]}]({fig_rel}/{f})")
        w("")
    lines.extend(perf_closing_note(perf))
    return lines


def perf_floor_table(perf):
    """The floor of a served step (graspcd_floor_bench; docs/performance.md), when perf.json has
    it: per scene, µs per physics step."""
    floor = perf.get("floor")
    if not floor:
        return []
    lines = ["### The floor of a served step", "",
             "A served step's floor is MuJoCo's own step with the same contacts (the grasp replayed"
             " from its recorded contacts, trajectory checked bit for bit) plus one certified"
             " triangle test and one contact routine per intersecting triangle pair plus one"
             " contact written per kept contact; graspcd's part is the served step less the"
             " replay. µs per physics step, medians (docs/performance.md).", "",
             "| scene | native | served | replay | triangle tests + contacts | writes | floor |"
             " served / floor | graspcd's part / its floor |",
             "|---|---|---|---|---|---|---|---|---|"]

    def us(x):
        return "-" if x is None else f"{x:.1f}"

    for scene, f in sorted(floor.items()):
        ratio = f.get("graspcd_part_over_floor")
        span = ("-" if ratio is None else
                f"{ratio:.2f} [{f['graspcd_part_over_floor_min']:.2f},"
                f" {f['graspcd_part_over_floor_max']:.2f}]")
        lines.append(f"| {scene} | {us(f['native'])} | {us(f['served'])} | {us(f['replay'])} |"
                     f" {us(f['tritri'] + f['contact'])} | {us(f['write'])} | {us(f['floor'])} |"
                     f" {f['served_over_floor']:.2f} | {span} |")
    lines.append("")
    return lines


PERF_TARGETS = [
    ("obb_test", "One OBB test at most 0.5x FCL's obbDisjoint"),
    ("mesh", "Mesh against mesh (sat, sat-cached) at most 0.5x FCL, no more box tests,"
             " identical answers"),
    ("trajectory", "Along the trajectories, with temporal coherence, at most 0.25x FCL per step"
                   " and FCL's front list"),
    ("mujoco", "mj_step with our callback at most 2x MuJoCo's native collision"),
    ("grasp", "A served step of a whole grasp at most 2x a native one"),
]


def perf_closing_note(perf):
    """Every target against its measured ratios; the reasons are chosen by comparing numbers."""
    lines = []
    w = lines.append
    comps = perf["comparisons"]
    w("### Closing note: the targets")
    w("")
    w("| target | comparisons met | ratio medians (min-max over the comparisons) | why not, where"
      " not |")
    w("|---|---|---|---|")
    for group, text in PERF_TARGETS:
        rows = [c for c in comps if c["group"] == group and c["target"] is not None]
        if not rows:
            w(f"| {text} | not measured | | |")
            continue
        met = sum(1 for c in rows if c["met"])
        lo = min(c["ratio_median"] for c in rows)
        hi = max(c["ratio_median"] for c in rows)
        why = []
        failed = [c for c in rows if not c["met"]]
        more_boxes = [c for c in failed if c.get("box_tests") is not None
                      and c.get("peer_box_tests") is not None
                      and c["box_tests"] > c["peer_box_tests"]]
        if more_boxes:
            why.append(f"{len(more_boxes)} of the {len(failed)} missed do more box tests than the"
                       " peer (FCL's boxes separate sooner there)")
        if group == "mesh":
            extra = [c for c in rows if c.get("box_tests") is not None
                     and c.get("peer_box_tests") is not None
                     and c["box_tests"] > c["peer_box_tests"]]
            wrong = [c for c in rows if not c.get("agrees")]
            why.append(f"box tests above FCL's in {len(extra)} of {len(rows)};"
                       f" answers differing from FCL's in {len(wrong)}")
        if group == "trajectory" and failed:
            bench = perf["benchmarks"]
            slower = [c for c in failed
                      if bench[c["ours"]]["median"]
                      >= bench[c["ours"].replace("ours-sat-cached", "ours-sat")]["median"]]
            if slower:
                why.append(f"in {len(slower)} of the {len(failed)} missed, sat-cached is no"
                           " faster than plain sat: its cache lookup costs what the hinted axis"
                           " saves, so the coherence we use does not pay yet")
        if group == "obb_test" and failed:
            why.append("the test itself: the disjoint-heavy mix exits early on both sides, so"
                       " the fixed cost of the slack and the absolute rotation weighs most")
        if group == "grasp" and failed:
            means = [c["mean_contacts"] for c in failed if c.get("mean_contacts") is not None]
            why.append("a pair that moved more than the drift is still queried exactly, and"
                       " MuJoCo's solver works on graspcd's manifold"
                       + (f" ({min(means):.1f}-{max(means):.1f} contacts a step where missed)"
                          if means else "")
                       + " against one contact per pair natively (docs/performance.md)")
        if group in ("mujoco", "grasp") and failed:
            why.append("graspcd's exact mesh-mesh queries of the served pairs cost more than"
                       " MuJoCo's convex (hull) collision of the same pairs, which is not right"
                       " on non-convex objects")
        w(f"| {text} | {met} of {len(rows)} | {lo:.3f}-{hi:.3f} | {'; '.join(why)} |")
    return lines


def contacts_section(contacts):
    """The "Contacts and the solver" section from contacts.json (report/contacts_solver.py)."""
    lines = []
    w = lines.append
    before = contacts["before_budget"]
    w("## Contacts and the solver")
    w("")
    w("From `contacts.json` (`report/contacts_solver.py`, run by `./run study`): each scene's grasp"
      " (`graspcd grasp SCENE --json`) natively (MuJoCo's convex hulls), served with the contact"
      " manifold as shipped (at most 4 points per patch and 8 per geom pair) and served with"
      f" {before} per pair and per patch (every intersecting triangle pair's contact up to"
      " MuJoCo's cap, as before the manifold), both with exact contacts every step (`grasp"
      " --exact`). Contacts are finger-object contacts per physics"
      " step over the whole grasp; \"most per pair\" is the most one geom pair had in one step;"
      " rise is the object's final height above its start; at rest is the hold's last second"
      " (the object's largest speed and deepest contact); buffers full counts the steps that"
      " filled MuJoCo's contact or constraint buffer. The served step's cost against native is"
      " a benchmark, `BM_WholeGrasp` of `./run perf` (docs/performance.md), not these single"
      " runs.")
    if "reuse" in contacts:
        w("")
        w(f"\"reused\" is the manifold with contacts reused across steps within"
          f" {contacts['reuse'] * 1e6:g} µm (`grasp --contact-reuse`, the default since 0.4,"
          " not exact:"
          " docs/design.md); the last column counts the served calls it answered without a"
          " query.")
    w("")
    reuse = "reuse" in contacts
    w("| scene | variant | contacts per step (mean, max) | most per pair | held, rise (cm) |"
      " at rest: speed (mm/s), penetration (mm) | buffers full |"
      + (" reused calls |" if reuse else ""))
    w("|---|---|---|---|---|---|---|" + ("---|" if reuse else ""))
    names = {"native": "native", "manifold": "manifold (4/8)", "before": f"before ({before})",
             "reuse": "manifold, reused"}
    for scene, variants in contacts["scenes"].items():
        for key in ("native", "manifold", "before", "reuse"):
            if key not in variants:
                continue
            r = variants[key]
            full = r["contact_buffer_full"] + r["constraint_buffer_full"]
            w(f"| {scene} | {names[key]} | {r['mean_contacts']:.1f}, {r['max_contacts']} |"
              f" {r['max_pair_contacts']} | {'yes' if r['held'] else 'no'},"
              f" {100 * r['rise']:.2f} | {1000 * r['rest_max_speed']:.2f},"
              f" {1000 * r['rest_max_penetration']:.3f} | {full} |"
              + (f" {r.get('reused_calls', 0)} |" if reuse else ""))
    # What the table says about the manifold at rest, read from it.
    worse = [scene for scene, v in contacts["scenes"].items()
             if v["manifold"]["rest_max_speed"] > 1.2 * max(v["before"]["rest_max_speed"],
                                                            v["native"]["rest_max_speed"])]
    if worse:
        w("")
        w("At rest the manifold leaves the object faster than both native and the full contact"
          f" set on {', '.join(worse)} (docs/design.md, \"The seam with MuJoCo\", says what the"
          " budget costs).")
    return lines


def race_section(race, fig_dir, fig_rel):
    """The "The race" section from race.json (study/run_race.py)."""
    lines = []
    w = lines.append
    m = race["machine"]
    w("## The race: the hull, convex decompositions and graspcd")
    w("")
    w("From `race.json` (`study/run_race.py build/graspcd`, not part of `./run test`; the"
      " decompositions are cached in its `--work` folder, by default `report/out/race`). Each scene's grasp runs as graspcd"
      " serves it (the contact manifold), natively on MuJoCo's convex hull, and natively on"
      " HACD decompositions of the object into at most N convex pieces (`graspcd decompose`,"
      " `grasp --decomposed`; decomposed-N), and V-HACD's where raced (`decompose --engine"
      " vhacd`; vhacd-N). MuJoCo's native configurations also ran with its multi-point convex"
      " collision where raced (`grasp --multiccd`, `run_race.py --multiccd 0,1`: up to 5"
      " contacts per convex pair instead of 1; \"native hull multiccd\", \"decomposed-N"
      " multiccd\", in the figure \"mc\"); graspcd's served pairs are not convex and are its own,"
      " so its row runs without it. The step cost is the wall time per physics step over the whole"
      " grasp (single runs one after another, not a benchmark); contacts are hand-object"
      " contacts per physics step; the contact error is phantom plus missed contacts per closing"
      " grasp step, judged by CGAL on the true meshes (`grasp --judge`: a phantom's point lies"
      " more than 1 mm from a true surface; a missed contact is a finger segment whose true mesh"
      " meets the object's with no contact; the judge's hand geoms are every collidable geom"
      " outside the object, the world body and the body the object stands on, the pair config's"
      " \"support\" (the driven table of the Robotiq scenes, whose contact with the object"
      " MuJoCo computes natively in every configuration and is not the grasp's): the phantom and"
      " missed columns name the hand geoms they came from). \"First contact\" counts the"
      " segments whose first-contact step is CGAL's on the true meshes at the same poses (never, for both,"
      " counts as the same). The one-sided Hausdorff distance is from the pieces' surfaces to"
      " the object's (CGAL's bounded_error_Hausdorff_distance, with its bound); HACD clusters"
      " the surface, and a cluster that rings a cavity (a cup's rim) has a hull that closes it,"
      " which the Hausdorff distance and the volume added show. A mesh too large for HACD"
      " (`run_race.py --simplify-above FACES=F`) is decomposed with `decompose --simplify F`:"
      " HACD partitions a copy decimated to at most F faces by CGAL's edge collapse, each"
      " original face joins the cluster of its nearest decimated face, and each piece is the hull"
      " of its cluster's original vertices, so the pieces come from a decimated partition but"
      " follow the original surface (the Hausdorff distance is against the original)."
      f" Machine: {m['cpu']}, {m['cores']} cores. Each scene's race ran as below (a scene of an"
      " earlier run kept by `run_race.py --merge` keeps that run's machine, date and load; the"
      " load average is the machine's, shared with other builds, so compare step costs within a"
      " scene, not across scenes).")
    if race.get("merged"):
        w("")
        w(f"This file joins races run apart (`{' '.join(race['command'])}`), each scene with the"
          " provenance of the race that ran it:")
        w("")
        for part in race["merged"]:
            if not part["scenes"]:
                continue
            if part.get("command"):
                load = ", ".join(f"{x:.1f}" for x in part["load_average"] or [])
                end = ", ".join(f"{x:.1f}" for x in part["load_average_end"] or [])
                w(f"- {', '.join(part['scenes'])}: `{' '.join(part['command'])}`,"
                  f" {part['wall_seconds'] / 60:.0f} minutes of wall time, the load average"
                  f" {load} at its start and {end} at its end.")
            else:
                w(f"- {', '.join(part['scenes'])}: an earlier race ({part['file']}).")
    elif race.get("command"):
        w("")
        w(f"This file comes from one run, `{' '.join(race['command'])}`: "
          f"{race['wall_seconds'] / 60:.0f} minutes of wall time, the load average"
          f" {', '.join(f'{x:.1f}' for x in race['machine']['load_average'])} (1, 5, 15 min) at"
          f" its start and {', '.join(f'{x:.1f}' for x in race['load_average_end'])} at its end.")
    w("")
    w("| scene | object | N raced | graspcd | date | load average | race wall time |")
    w("|---|---|---|---|---|---|---|")
    for scene, e in race["scenes"].items():
        p = e.get("provenance", {"machine": m})
        obj = e.get("object")
        what = (f"`grasp --object {obj['file']} {' '.join(obj['options'])}`" if obj
                else f"mjcf/{scene}.xml")
        counts = ", ".join(str(n) for n in e.get("pieces", race["pieces"])) or "none"
        if e.get("vhacd_pieces") is not None:
            counts = (f"HACD {counts}; V-HACD"
                      f" {', '.join(str(n) for n in e['vhacd_pieces']) or 'none'}")
        if "machine" in p:
            old = p["machine"]
            w(f"| {scene} | {what} | {counts} | (not recorded) | {old['date']} |"
              f" {', '.join(f'{x:.1f}' for x in old['load_average'])} (run's end) | - |")
        else:
            g = p["graspcd"]
            commit = g.get("commit", "?")[:7] + (" (dirty)" if g.get("dirty") else "")
            w(f"| {scene} | {what} | {counts} | {g.get('version', '?')} {commit} | {p['date']} |"
              f" {', '.join(f'{x:.1f}' for x in p['load_average'])} |"
              f" {p['wall_seconds'] / 60:.1f} min |")
    for scene, e in race["scenes"].items():
        for part in e.get("merged_rows", []):
            p = part["provenance"]
            g = p.get("graspcd", {})
            when = p.get("date") or p.get("machine", {}).get("date", "?")
            w("")
            w(f"{scene}: the rows of {', '.join(part['configurations'])} come from"
              f" {part['file']} (graspcd {g.get('version', '?')} {g.get('commit', '?')[:7]},"
              f" {when}).")
        if e.get("note"):
            w("")
            w(f"{scene}: {e['note']}")
    w("")
    w("The one-sided Hausdorff distance is in the scene's metres: the decomposition is in the"
      " mesh file's units, times the scene's mesh scale (`mesh_scale`; 1 where race.json has"
      " none).")
    w("")
    w("| scene | N asked | pieces | engine on | decomposition (s) | one-sided Hausdorff (mm) |"
      " volume added |")
    w("|---|---|---|---|---|---|---|")
    for scene, e in race["scenes"].items():
        scale = e.get("mesh_scale", [1, 1, 1])[0]
        for n, d in e["decompositions"].items():
            if "error" in d:
                w(f"| {scene} ({e['mesh']}) | {n} | - | {d.get('engine', 'hacd')} failed:"
                  f" {d['error']} | - | - | - |")
                continue
            vol = d["volume"]
            added = "open mesh" if vol is None else f"{100 * vol['added_fraction']:.0f}%"
            simp = d.get("simplify")
            engine = d.get("engine", "hacd").upper().replace("VHACD", "V-HACD")
            on = (f"{engine} on the mesh" if not simp or not simp["decimated"] else
                  f"{engine} on a copy of {simp['faces_after']} faces (`--simplify"
                  f" {simp['max_faces']}`, {simp['seconds']:.1f} s)")
            haus = ("-" if d.get("hausdorff") is None else
                    f"{1000 * scale * d['hausdorff']:.2f} +-"
                    f" {1000 * scale * d['hausdorff_bound']:.2f}")
            w(f"| {scene} ({e['mesh']}, {d['source_faces']} faces) | {n} | {d['pieces']} |"
              f" {on} | {d['seconds']:.1f} | {haus} | {added} |")
    lines.extend(race_protocol_text(race))
    w("")
    w("| scene | configuration | noslip | outcome | tilt final (deg) | top speed (m/s) |"
      " kinetic energy (mJ) | true penetration: hand, support (mm) | step cost (ms) |"
      " contacts per step |"
      " first contact as CGAL's | phantom, missed | contact error per step |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    fig, (ax, axp) = plt.subplots(1, 2, figsize=(13, 4.8))
    markers = "osD^v<>phH*"
    for k, (scene, e) in enumerate(race["scenes"].items()):
        color = f"C{k % 10}"
        marker = markers[k % len(markers)]
        points = {True: ([], [], []), False: ([], [], [])}
        for r in e["rows"]:
            outcome = race_score.row_outcome(r)
            noslip = r.get("noslip")
            if outcome == "cannot start":
                # The grasp's message from "cannot start" on (without the scene's and the
                # pieces' paths, which race.json keeps).
                message = r.get("message") or ""
                at = message.find("cannot start with ")
                message = message[at + len("cannot start with "):] if at >= 0 else message
                w(f"| {scene} | {r['configuration']} | {noslip} | cannot start:"
                  f" {message.replace('|', '/')} | - | - | - | - | - | - | - | - | - |")
                continue
            # A segment is a geom name (the project's hands) or a "body:NAME" touch pattern.
            segments = r["first_contact"]
            same = sum(1 for seg, step in segments.items()
                       if (r["cgal_first_contact_body"].get(seg[5:]) if seg.startswith("body:")
                           else r["cgal_first_contact"].get(seg)) == step)
            shown = outcome if "outcome" in r else ("held" if r["held"] else "not held")
            if "outcome" in r and outcome == "dropped" and r.get("reason"):
                shown = f"dropped ({r['reason']})"
            tp = race_score.hand_penetration(r)
            w(f"| {scene} | {r['configuration']} | {'-' if noslip is None else noslip} |"
              f" {shown} | {opt(r.get('tilt_final_deg'), '.1f')} |"
              f" {opt(r.get('max_speed'), '.3g')} |"
              f" {opt(None if r.get('kinetic_energy_max') is None else 1000 * r['kinetic_energy_max'], '.3g')} |"
              f" {penetration_cell(r)} |"
              f" {r['ms_per_physics_step']:.3f} | {r['contacts_per_step']:.1f} |"
              f" {same} of {len(segments)} |"
              f" {by_geom(r['phantom'], r.get('phantom_by_geom'))},"
              f" {by_geom(r['missed'], r.get('missed_by_geom'))} |"
              f" {r['contact_error_per_step']:.2f} |")
            good = race_score.kept(r)
            points[good][0].append(r["ms_per_physics_step"])
            points[good][1].append(r["contact_error_per_step"])
            points[good][2].append(tp)
            label = (r["configuration"].replace("decomposed-", "d").replace("vhacd-", "v")
                     .replace(" multiccd", " mc"))
            if noslip:
                label += f" ns{noslip}"
            ax.annotate(label, (r["ms_per_physics_step"], r["contact_error_per_step"]),
                        fontsize=5, xytext=(3, 3), textcoords="offset points")
            if tp is not None:
                axp.annotate(label, (r["ms_per_physics_step"], max(1000 * tp, 0.01)), fontsize=5,
                             xytext=(3, 3), textcoords="offset points")
        for good, (xs, ys, tps) in points.items():
            if not xs:
                continue
            style = ({"color": color} if good else {"facecolors": "none", "edgecolors": color})
            name = f"{scene} ({'kept' if good else 'not kept'})"
            ax.scatter(xs, ys, marker=marker, label=name, **style)
            with_tp = [(x, max(1000 * t, 0.01)) for x, t in zip(xs, tps) if t is not None]
            if with_tp:
                axp.scatter([x for x, _ in with_tp], [t for _, t in with_tp], marker=marker,
                            **style)
    ax.set_xscale("log")
    ax.set_xlabel("step cost: wall ms per physics step (log)")
    ax.set_ylabel("contact error: phantom + missed per closing step")
    ax.set_title("Contact error (the judge)")
    if not axp.collections:
        axp.text(0.5, 0.5, "no row of this race.json measured the true meshes", ha="center",
                 va="center", transform=axp.transAxes, fontsize=8)
    axp.set_xscale("log")
    axp.set_yscale("log")
    axp.set_xlabel("step cost: wall ms per physics step (log)")
    axp.set_ylabel("deepest true penetration into the hand (mm, log; at least 0.01)")
    axp.set_title("True-mesh penetration (the protocol's rows)")
    # The legend beside the axes, never over the points.
    axp.legend(*ax.get_legend_handles_labels(), fontsize=6, loc="upper left",
               bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    fig.savefig(os.path.join(fig_dir, "race_pareto.png"), dpi=120, bbox_inches="tight")
    plt.close(fig)
    w("")
    w(f"![step cost against contact error and true-mesh penetration]({fig_rel}/race_pareto.png)")
    w("")
    w("Filled markers: the object was kept (held, tilted or not); hollow: it was not (dropped,"
      " ejected; a run that could not start has no point). Rows of an earlier race (no noslip"
      " column) have no true penetration and appear in the left panel only.")
    w("")
    lines.extend(race_findings(race))
    return lines


def shown_outcome(r):
    """A row's outcome as the findings name it: "not held" for a row of an earlier race, which
    recorded neither the tilt nor an ejection."""
    if "outcome" in r:
        return r["outcome"]
    return "held" if r.get("held") else "not held"


def penetration_cell(r):
    """A row's deepest true penetration into the hand and into the support, mm ("hand 0.2,
    support 3.1"), "-" for a row without it."""
    tp = r.get("true_penetration")
    if not tp:
        return "-"
    return f"{1000 * tp['hand_max']:.3g}, {1000 * tp['support_max']:.3g}"


def opt(value, spec):
    """A number as `spec`, or "-" for none."""
    return "-" if value is None else format(value, spec)


def race_protocol_text(race):
    """What a row of the race says, and the order the race scores rows by."""
    lines = [""]
    lines.append(
        "Each configuration of a scene raced under the protocol (rows with a noslip value) ran"
        " once per MuJoCo noslip setting (`grasp --noslip N`: N iterations of MuJoCo's noslip"
        " solver, which removes the contacts' slip; 0 is MuJoCo's default, off). The outcome is"
        " the grasp's verdict: held (final tilt under 2 degrees), held tilted, dropped (not held,"
        " not ejected: the reason beside it), ejected (faster than 2 m/s, below its support or out"
        " of the scene) or cannot start (the grasp refused the start: a hull or pieces that hold a"
        " finger at the start, with the grasp's message). The true penetration is the deepest"
        " penetration of the true meshes over the run (`grasp`'s true_penetration: the object"
        " against every hand geom and its support, once per grasp step in every phase, whatever"
        " geometry the configuration collided, by the start check's exact inside test on vertices"
        " and edge points; shown into the hand and into the support, the table or floor), so a"
        " run that throws the object out is not scored on the contacts it no longer has; the"
        " kinetic energy is the object's largest. Rows are scored by outcome (held, held tilted,"
        " dropped, then ejected and cannot start alike, worse than any run that kept the object"
        " in the scene), then by the true penetration into the hand (the support's, like the"
        " judge's, is not the grasp's: its contact with the object is MuJoCo's native one in"
        " every configuration but the decomposed, and an object thrown through it is ejected),"
        " then by the contact error (`study/race_score.py`).")
    return lines


def race_findings(race):
    """The race's findings, computed from the rows: where exactness changes the outcome (graspcd
    keeps the object and a cheaper configuration does not, at the same noslip setting) and where
    MuJoCo's own route, the hull or a decomposition, is as good and cheaper (no worse an outcome, a true penetration no deeper than
    graspcd's by more than the start check's 0.5 mm, a lower step cost)."""
    lines = []
    w = lines.append
    exact, cheap_good, verdicts = [], [], []
    for scene, e in race["scenes"].items():
        by_noslip = {}
        for r in e["rows"]:
            by_noslip.setdefault(r.get("noslip"), []).append(r)
        for noslip, rows in by_noslip.items():
            ours = next((r for r in rows if r["configuration"] == "graspcd"), None)
            if ours is None or ours.get("ms_per_physics_step") is None:
                continue
            setting = "" if noslip is None else f", noslip {noslip}"
            cheaper = [r for r in rows if r is not ours and r.get("ms_per_physics_step") is not None
                       and r["ms_per_physics_step"] < ours["ms_per_physics_step"]]
            # Runs that could not start cost nothing: they lose whatever graspcd did.
            refused = [r for r in rows if r is not ours and
                       race_score.row_outcome(r) == "cannot start"]
            if race_score.kept(ours):
                lost = [r for r in cheaper + refused if not race_score.kept(r)
                        and not r["configuration"].startswith("graspcd")]
                if lost:
                    exact.append(
                        f"- {scene}{setting}: graspcd {shown_outcome(ours)}; "
                        + ", ".join(f"{r['configuration']} {shown_outcome(r)}"
                                    for r in lost) + ".")
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
            if good:
                cheap_good.append(
                    f"- {scene}{setting}: graspcd {shown_outcome(ours)}, {numbers(ours)}; "
                    + "; ".join(f"{r['configuration']} {shown_outcome(r)}, {numbers(r)}"
                                for r in good) + ".")
            best = min(rows, key=race_score.score)
            if "outcome" in best:
                verdicts.append(f"- {scene}{setting}: best {best['configuration']}"
                                f" ({shown_outcome(best)},"
                                f" {1000 * race_score.hand_penetration(best):.2f} mm into the"
                                f" hand, {best['contact_error_per_step']:.2f} errors per step,"
                                f" {best['ms_per_physics_step']:.3f} ms).")
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


# How much deeper than graspcd's a configuration's true penetration may be and still count as
# good as graspcd's: the start check's tolerance (grasp/start_check.h, kStartPenetration), m.
PENETRATION_SLACK = 0.5e-3


def by_geom(total, counts):
    """A phantom or missed count with the hand geoms it came from: "1 (finger2_C 1)"."""
    if not total or not counts:
        return str(total)
    return f"{total} ({', '.join(f'{g} {n}' for g, n in sorted(counts.items()))})"


def real_models_section(real):
    """The "Real hands and objects" section from report/real_models.py's real_models.json."""
    lines = []
    w = lines.append
    m = real["machine"]
    la, lb = real["loadavg_before"], real["loadavg_after"]
    w("## Real hands and objects")
    w("")
    w(f"The real hands of `../shared/models` (used by path, never copied) in the scenes `mjcf/real_*.xml`,"
      f" run by `report/real_models.py` on {real['created']} (commit {real['commit']}), {m['cpu']},"
      f" {m['cores']} cores, {m['os']}; load average {la[0]:.2f} before and {lb[0]:.2f} after (above 1:"
      " others were building or testing on the machine). Detection time per closing grasp step: the"
      " tree queries of all registered pairs over the physics steps of the closing, divided by its"
      f" grasp steps, median and min-max over {real['repeats']} runs of `graspcd grasp --json` (method"
      " sat). Heights are along -gravity from the driven table (the hands are fixed; the table moving"
      " away along gravity is the lift).")
    w("")
    w("| scene | hand | object x scale | closing steps | first contacts (step) | gripped | held |"
      " lifted (cm) | detection per step (µs), median [min-max] |")
    w("| --- | --- | --- | ---: | --- | --- | --- | ---: | --- |")
    for s in real["scenes"]:
        g = s["grasp"]
        t = g["per_step_ns"]
        fc = sorted(v for v in g["first_contact"].values() if v is not None)
        touched = f"{len(fc)}/{len(g['first_contact'])} at {fc[0]}-{fc[-1]}" if fc else "none"
        lift = 100 * (g["object_z_final"] - g["object_z_gripped"])
        w(f"| `{s['scene']}` | {s['hand']} | {s['object']} x {s['scale']:g} | {g['closing_steps']} |"
          f" {touched} | {'yes' if g['gripped'] else 'no'} | {'yes' if g['held'] else 'no'} |"
          f" {lift:.1f} | {t['median'] / 1e3:.0f} [{t['min'] / 1e3:.0f}-{t['max'] / 1e3:.0f}] |")
    w("")
    w("Agreement with CGAL (`graspcd validate --json --all-methods`): every registered pair at every"
      " closing grasp step, summed over the pairs. A missed collision is CGAL saying the surfaces"
      " meet where the method says they do not.")
    w("")
    w("| scene | methods | checks | agree | CGAL hits | missed | false |")
    w("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    total_missed = 0
    keys = ("checks", "agree", "cgal_hits", "missed", "false")
    for s in real["scenes"]:
        rows = s["validate"]["methods"]
        total_missed += sum(r["missed"] for r in rows)
        groups = {}  # methods with the same counts share a row
        for r in rows:
            groups.setdefault(tuple(r[k] for k in keys), []).append(r["method"])
        for counts, names in groups.items():
            every = len(groups) == 1 and len(names) > 1
            label = f"all {len(names)}" if every else ", ".join(names)
            w(f"| `{s['scene']}` | {label} | " + " | ".join(str(c) for c in counts) + " |")
    w("")
    methods = ", ".join(r["method"] for r in real["scenes"][0]["validate"]["methods"])
    text = f"Methods checked: {methods}. "
    text += ("No method missed a collision on the real scenes." if total_missed == 0 else
             f"The methods missed {total_missed} collisions on the real scenes: see the rows above.")
    partial = [s["scene"] for s in real["scenes"] if not s["validate"].get("all_methods", True)]
    if partial:
        text += (" Only the config's method on " + ", ".join(f"`{p}`" for p in partial) +
                 ": `--all-methods` took longer than the script's timeout there.")
    held = [s["scene"] for s in real["scenes"] if not s["grasp"]["held"]]
    if held:
        text += (" Not held in the lift: " + ", ".join(f"`{h}`" for h in held) +
                 " (the fingers reach the object; the scene's header says why).")
    w(text)
    w("")
    w("Reproduce: `/usr/bin/python3 report/real_models.py --out report/out/real_models.json` (needs"
      " `../shared/models` and `build/graspcd`), then `report/make_report.py report/out`.")
    w("")
    return lines


def report(study, sweep, fig_dir, fig_rel, stress=None, perf=None):
    lines = []
    w = lines.append
    m = study["machine"]
    b = study["build"]
    w("# graspcd reproduction study")
    w("")
    w(f"Generated by `report/make_report.py` from `graspcd study` output of {study['created']}"
      f"{' (--quick: a smoke test, not for quoting)' if study['quick'] else ''}. Every number below"
      " is read from the `study.json` and `sweep.json` it was drawn from (beside it in"
      " `report/out/`; in `report/data/` for the committed reference).")
    w("")
    mem = m["memory"]
    if mem.endswith("kB") and mem.split()[0].isdigit():
        mem = f"{int(mem.split()[0]) / 2**20:.1f} GiB"
    w(f"- Machine: {m['cpu']}, {m['cores']} cores, {mem}, {m['os']}, {m['kernel']}.")
    w(f"- Build: graspcd {b['graspcd']}, {b['build_type']}, {b['compiler']}, flags `{b['flags']}`;"
      f" MuJoCo {b['mujoco']}, Eigen {b['eigen']}, CGAL {b['cgal']}.")
    # The envelope's provenance (docs/design.md, "The command line"): the commit the study's
    # binary was built from, and whether its tree had uncommitted changes.
    prov = study.get("graspcd")
    if prov:
        state = "with uncommitted changes" if prov["dirty"] else "clean tree"
        w(f"- Commit: `{prov['commit']}` ({state}).")
    else:
        w("- Commit: not recorded (study.json written before graspcd 0.2.0).")
    jobs = study["table1"].get("jobs", 1)
    # Table 1's perceptron methods that run to their cap replay fewer times (study.json's
    # "perceptron_repeats"; each cell's own count is its "repeats").
    fewer = study.get("perceptron_repeats", study["repeats"])
    w(f"- Timing: every method replays the same recorded grasp steps {study['repeats']} times"
      + (f" (perceptron, perceptron-warm and perceptron-scaled {fewer} times, most of the"
         " study's time)" if fewer != study["repeats"] else "") + ";"
      " times are medians with [min-max] over those repeats, wall clock of the queries alone"
      " (poses computed before the clock starts), each replay on one thread"
      + (f", {jobs} replays at a time (one per core; the box hand alone)." if jobs > 1 else "."))
    w("")
    w("## The recorded grasps")
    w("")
    w("| grasp | recorded with | grasp steps | pairs | faces | held | rise (cm) |"
      " first contact (ours / CGAL on the same poses) |")
    w("|---|---|---|---|---|---|---|---|")
    for r in study["recordings"]:
        fc = ", ".join(
            f"{n} {s}/{t}" for n, s, t in zip(SEGMENTS, r["first_contact"], r["truth_first_contact"])
            if s > 0 or t > 0)
        w(f"| {r['name']} | {r['recorded_with']} | {r['grasp_steps']} | {r['pairs']} |"
          f" {r['faces']} | {'yes' if r['held'] else 'no'} | {100 * r['object_rise_m']:.1f} |"
          f" {fc} |")
    br = study["box_hand"]["recording"]
    w(f"| box hand | {br['recorded_with']} | {br['grasp_steps']} | {study['box_hand']['pairs']} box"
      f" pairs (segments B, C) | - | {'yes' if br['held'] else 'no'} |"
      f" {100 * br['object_rise_m']:.1f} | - |")
    w("")
    w("First contact counts the grasp step whose end state has a segment's mesh intersecting the"
      " object's; the recording stops a segment at the first physics step with a contact inside"
      " the grasp step, CGAL judges the end state only, so the two may differ by a step.")
    w("")

    # Table 1.
    t = study["table1"]
    sat = next(x for x in t["methods"] if x["name"] == "sat")
    w("## Table 1: total detection time over all grasp steps (triangle hand)")
    w("")
    w(f"Mode: {t['mode']}, the exact triangle test at the leaves, the bridge's trees. Ours in ms,"
      " median [min-max]; ratio to SAT in the same run; the paper's MATLAB seconds (its Table 1)"
      " with, in brackets, their ratio to its SAT.")
    w("")
    head = "| method | " + " | ".join(f"{e} ms | {e} / SAT | paper s [/ SAT]"
                                     for e in t["examples"])
    w(head + " | answers = CGAL |")
    w("|---" * (1 + 3 * len(t["examples"]) + 1) + "|")
    for meth in t["methods"]:
        cells = []
        for e, x in enumerate(meth["examples"]):
            ratio = x["median_ms"] / sat["examples"][e]["median_ms"]
            paper = "-"
            if "paper_s" in meth and "paper_s" in sat:
                paper = (f"{meth['paper_s'][e]:.2f}"
                         f" [{ratio_text(meth['paper_s'][e] / sat['paper_s'][e])}]")
            cells.append(f"{ms(x['median_ms'])} [{ms(x['min_ms'])}-{ms(x['max_ms'])}] |"
                         f" {ratio_text(ratio)} | {paper}")
        agree = all(x["agrees_with_cgal"] for x in meth["examples"])
        hits = all(x.get("hits_agree_with_cgal", x["agrees_with_cgal"]) for x in meth["examples"])
        verdict = "yes" if agree else ("contacts yes, triangle pairs no" if hits else "NO")
        w(f"| {meth['name']} | " + " | ".join(cells) + f" | {verdict} |")
    w("")
    hashes = {x["pairs_hash"] for meth in t["methods"] for x in meth["examples"][:1]}
    truth = study["recordings"][0]["truth_pairs_hash"]
    ours = [meth for meth in t["methods"] if not meth["name"].startswith("fcl")]
    hashes = {x["pairs_hash"] for meth in ours for x in meth["examples"][:1]}
    w(f"Answer hashes (example 1, every intersecting triangle pair of every step and pair): "
      f"{len(hashes)} distinct value(s) over graspcd's {len(ours)} methods, "
      f"{'equal to' if hashes == {truth} else 'NOT equal to'} CGAL's `{truth}`. \"answers ="
      " CGAL\" compares every triangle pair of every example; \"contacts yes\" means the"
      " same (step, pair) contacts with different triangle pairs (FCL's floating-point triangle"
      " test on touching triangles).")
    fcl = next((m for m in t["methods"] if m["name"] == "fcl-obb"), None)
    if fcl:
        r = [x["median_ms"] / s["median_ms"] for x, s in zip(fcl["examples"], sat["examples"])]
        w("")
        w(f"FCL's OBB tree on the same queries takes {', '.join(ratio_text(v) for v in r)} times"
          " our SAT's time (examples in order).")
    w("")
    w(f"![Table 1 ratios]({fig_rel}/table1_ratios.png)")
    w("")

    # Why: the perceptron against SAT.
    box = study["box_hand"]
    bsat = box_method(study, "sat")
    bper = box_method(study, "perceptron")
    bneu = box_method(study, "neurosat")
    n_steps = box["steps"]
    sat_ns = sum(bsat["segments"][k]["total"]["median_ms"] for k in "BC") * 1e6
    per_ns = sum(bper["segments"][k]["total"]["median_ms"] for k in "BC") * 1e6
    per_passes = sum(sum(bper["segments"][k]["passes"]) for k in "BC")
    box_tests = n_steps * box["pairs"]
    ns_per_sat = sat_ns / box_tests
    ns_per_pass = per_ns / per_passes if per_passes else float("nan")
    per_ratio = per_ns / sat_ns
    w("## Where we differ from the paper, and why")
    w("")
    pm = next((x for x in t["methods"] if x["name"] == "perceptron"), None)
    if pm:
        ours = [x["median_ms"] / s["median_ms"] for x, s in zip(pm["examples"], sat["examples"])]
        paper = [p / s for p, s in zip(pm["paper_s"], sat["paper_s"])]
        verdict = ("contradicts" if min(ours) > 1 and max(paper) < 1 else "agrees with")
        span = (lambda v: ratio_text(v[0]) if len(v) == 1 or min(v) == max(v)
                else f"{ratio_text(min(v))}-{ratio_text(max(v))}")
        paper = paper[:len(ours)]
        w(f"The perceptron takes {span(ours)} times SAT's time on our example(s); the paper"
          f" reports {span(paper)} on the same example(s). Our measurement {verdict} the paper's"
          " ranking. Three measured facts explain it:")
    w("")
    w(f"1. **One pass against one SAT.** On the box hand's {box_tests} box tests, one SAT costs"
      f" {ns_per_sat:.0f} ns (all 15 axes when the boxes overlap, fewer when an early axis"
      f" separates), one perceptron pass over the 16 corners {ns_per_pass:.1f} ns. A perceptron"
      f" test pays off only if it converges in under {ns_per_sat / ns_per_pass:.1f} passes.")
    max_pass = max(max(bper["segments"][k]["passes"]) for k in "BC")
    contact_steps = sum(1 for i in range(n_steps)
                        if any(box["bounds"][k]["pairs_in_contact"][i] for k in "BC"))
    w(f"2. **Passes near contact.** Overlapping or touching boxes can never be separated, so the"
      f" perceptron runs to its cap ({bper['cap']} passes on the box hand, as in the paper) on"
      f" every such pair: {contact_steps} of {n_steps} box-hand grasp steps have a pair in contact,"
      f" and the most passes in one grasp step was {max_pass:.0f} (Figure 14). On the box hand the"
      f" perceptron took {ratio_text(per_ratio)} times SAT's time in total.")
    finite = [v for k in "BC" for v in box["bounds"][k]["novikoff_max_finite"] if v > 0]
    if finite:
        w(f"3. **The (R / γ)² bound.** Novikoff's bound on the perceptron's updates grows as the"
          f" inverse square of the gap: over the box hand's separated pairs the largest bound was"
          f" {max(finite):.3g} updates and the smallest {min(finite):.3g}. In metres the bias"
          " input 1 dominates R (corners lie within centimetres of the midpoint), so R ≈ 1 and a"
          " 1 mm gap allows about 4·10⁶ updates; the paper's MATLAB units are not stated. The"
          " scaled perceptron (`perceptron-scaled`, beyond the paper) divides the corners by their"
          " extent and shrinks the bound accordingly (Table 1).")
    if bneu:
        neu_ns = sum(bneu["segments"][k]["total"]["median_ms"] for k in "BC") * 1e6
        w("")
        w(f"Neuro-SAT on the box hand took {ratio_text(neu_ns / sat_ns)} times SAT's time: it"
          f" pays up to {bneu['switch']} passes before SAT answers.")
    w("")
    w(f"Correctness on the box hand, against CGAL's exact box test on all {box['box_tests']} box"
      f" tests ({box['overlapping_exact']} overlapping): false \"separated\" "
      + ", ".join(f"{x['name']} {x['false_separated']}" for x in box["methods"])
      + "; disjoint pairs left unproven (\"may overlap\", which costs time, never a contact) "
      + ", ".join(f"{x['name']} {x['unproven_disjoint']}" for x in box["methods"]) + ".")
    w("")
    w("## Figures 13-15: the box hand, segments B and C")
    w("")
    for f in ("fig13_time_per_step.png", "fig14_passes.png", "fig15_time_saved.png"):
        w(f"![{f}]({fig_rel}/{f})")
        w("")
    for k in "BC":
        saved_p = (bsat["segments"][k]["total"]["median_ms"] - bper["segments"][k]["total"]["median_ms"])
        w(f"- Segments {k}: SAT {ms(bsat['segments'][k]['total']['median_ms'] * 1e3)} µs,"
          f" perceptron {ms(bper['segments'][k]['total']['median_ms'] * 1e3)} µs,"
          f" Neuro-SAT {ms(bneu['segments'][k]['total']['median_ms'] * 1e3)} µs over all steps;"
          f" time saved by the perceptron: {saved_p * 1e3:.3g} µs.")
    w("")

    if sweep:
        fig, front = sweep_figure(sweep, fig_dir)
        w("## Run time against error (the sweep)")
        w("")
        w(f"{len(sweep['configs'])} points on {', '.join(r['name'] for r in sweep['recordings'])}"
          f" ({sweep['repeats']} repeats each"
          f"{'; merged from ' + str(sweep['merged_from']) + ' shards' if 'merged_from' in sweep else ''}),"
          " errors against CGAL on every (grasp step, pair): missed and false contacts, the"
          " first-contact grasp step of each finger segment, and the contact position (mean of"
          " the intersecting triangle pairs' centroids).")
        w("")
        w("| point | time ms [min-max] | missed | false | missed / false triangle pairs |"
          " first-contact step error (max / sum) | position error mm (max / mean) | box tests |"
          " passes | triangle tests |")
        w("|---|---|---|---|---|---|---|---|---|---|")
        for c in sweep["configs"]:
            w(f"| {c['name']}{' ★' if c['name'] in front else ''} | {ms(c['median_ms'])}"
              f" [{ms(c['min_ms'])}-{ms(c['max_ms'])}] | {c['missed']} | {c['false_contacts']} |"
              f" {c['missed_tri_pairs']} / {c['false_tri_pairs']} |"
              f" {c['first_contact_step_error_max']} / {c['first_contact_step_error_sum']} |"
              f" {c['position_error_max_mm']:.3g} / {c['position_error_mean_mm']:.3g} |"
              f" {c['counters']['box_tests']} | {c['counters']['perceptron_passes']} |"
              f" {c['counters']['tri_tests']} |")
        w("")
        w("★ the Pareto front: no other point is as fast, with as few errors (missed and false"
          " contacts and triangle pairs) and as small a contact position error. First-contact mode"
          " reports one triangle pair per contact by design: its missing pairs are not counted,"
          " its position error is.")
        w("")
        w(f"![sweep]({fig_rel}/{fig})")
        w("")
        bad = [c for c in sweep["configs"] if c["missed"] > 0]
        if bad:
            w("Points that missed contacts (the worst defect): " +
              ", ".join(f"{c['name']} ({c['missed']})" for c in bad) + ".")
        else:
            w("No point of the sweep missed a contact against CGAL.")
        plain = next((c for c in sweep["configs"] if "moller-plain" in c["name"]), None)
        if plain and sweep_error(plain) == 0:
            w(" Plain Möller (no error bound) makes no error on these grasps; it misses touching"
              " pairs with shared vertices and edges, which `tests/core/tritri_test.cpp` counts.")
        falsep = [c for c in sweep["configs"] if c["false_contacts"] > 0]
        if falsep:
            w("Points with false contacts: " +
              ", ".join(f"{c['name']} ({c['false_contacts']})" for c in falsep) + ".")
        w("")
    if stress is not None:
        lines.extend(stress_section(stress))
    if perf is not None:
        lines.extend(perf_section(perf, fig_dir, fig_rel))
    w("## Reproduce")
    w("")
    w("```")
    w("./run study                      # records, replays, writes report/out/, draws this report")
    w("build/graspcd study --help       # options: --quick, --repeats, --shard i/n, --merge")
    if stress is not None:
        w("build/graspcd stress --help      # the stress suite: classes, columns, --seed, --cases")
    if perf is not None:
        w("./run perf                       # graspcd against FCL and MuJoCo: report/out/perf.json")
    w("```")
    w("")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir", help="the folder graspcd study wrote")
    parser.add_argument("--figures", default="figures",
                        help="figure folder, relative to OUT_DIR (default: figures)")
    args = parser.parse_args()
    study = load(os.path.join(args.out_dir, "study.json"))
    sweep = load(os.path.join(args.out_dir, "sweep.json"), required=False)
    stress = load(os.path.join(args.out_dir, "stress.json"), required=False)
    perf = load(os.path.join(args.out_dir, "perf.json"), required=False)
    fig_dir = os.path.join(args.out_dir, args.figures)
    os.makedirs(fig_dir, exist_ok=True)
    figure_13_to_15(study, fig_dir)
    table1_figure(study, fig_dir)
    text = report(study, sweep, fig_dir, args.figures, stress, perf)
    # Sections drawn from optional files of other scripts, each before "## Reproduce":
    # report/real_models.py (the real hands of ../shared/models) and
    # report/contacts_solver.py (what the solver gets).
    for name, draw in (("real_models.json", real_models_section),
                       ("contacts.json", contacts_section)):
        data = load(os.path.join(args.out_dir, name), required=False)
        if data is None:
            continue
        section = "\n".join(draw(data)) + "\n\n"
        at = text.find("## Reproduce")
        if at < 0:
            at = len(text)
        text = text[:at].rstrip("\n") + "\n\n" + section + text[at:]
    # The race: OUT_DIR/race.json, else the cached run, report/data/race.json.
    race = load(os.path.join(args.out_dir, "race.json"), required=False)
    if race is None:
        race = load(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "race.json"),
                    required=False)
    if race is not None:
        section = "\n".join(race_section(race, fig_dir, args.figures)) + "\n\n"
        at = text.find("## Reproduce")
        if at < 0:
            at = len(text)
        text = text[:at].rstrip("\n") + "\n\n" + section + text[at:]
    # The pictures of the grasps and the trees, from OUT_DIR/trajectories when present.
    text = draw_figures.insert_section(text, args.out_dir, fig_dir, args.figures)
    with open(os.path.join(args.out_dir, "REPORT.md"), "w", encoding="utf-8") as f:
        f.write(text)
    print(f"wrote {os.path.join(args.out_dir, 'REPORT.md')} and {fig_dir}/*.png", file=sys.stderr)


if __name__ == "__main__":
    main()
