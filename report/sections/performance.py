"""The section "Performance against FCL and MuJoCo" from perf.json (`./run perf`): each group of
comparisons as ratios ours / peer measured in the same run, the floor of a served step, the
figures of query and build scaling, and the closing note on the targets."""

import os

import matplotlib.pyplot as plt

from sections.numbers import ms

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
