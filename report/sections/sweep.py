"""The section "Run time against error (the sweep)": every point of the sweep with its errors
against CGAL, its Pareto front, and its figure."""

import os

import matplotlib.pyplot as plt

from sections.numbers import ms


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


def sweep_section(sweep, fig_dir, fig_rel):
    lines = []
    w = lines.append
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
    return lines
