"""The section "Figures 13-15": the box hand's detection time, perceptron passes and time saved
against SAT per grasp step, segments B and C, and their figures."""

import os

import matplotlib.pyplot as plt

from sections.numbers import ms

METHOD_COLORS = {"sat": "tab:blue", "perceptron": "tab:red", "neurosat": "tab:green"}


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


def box_hand_section(study, fig_dir, fig_rel):
    lines = []
    w = lines.append
    figure_13_to_15(study, fig_dir)
    bsat = box_method(study, "sat")
    bper = box_method(study, "perceptron")
    bneu = box_method(study, "neurosat")
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
    return lines
