"""The section "Table 1": total detection time over all grasp steps of the triangle hand, every
method beside SAT and the paper's own seconds, with the answers' agreement with CGAL, and its
figure of the ratios to SAT."""

import os

import matplotlib.pyplot as plt

from sections.numbers import ms, ratio_text


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


def table1_section(study, fig_dir, fig_rel):
    lines = []
    w = lines.append
    table1_figure(study, fig_dir)
    t = study["table1"]
    sat = next(x for x in t["methods"] if x["name"] == "sat")
    w("## Table 1: total detection time over all grasp steps (triangle hand)")
    w("")
    w(f"Mode: {t['mode']}, the exact triangle test at the leaves, the trees of the MuJoCo layer"
      " (`graspcd::mujoco`). Ours in ms, median [min-max]; ratio to SAT in the same run; the"
      " paper's MATLAB seconds (its Table 1) with, in brackets, their ratio to its SAT.")
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
    return lines
