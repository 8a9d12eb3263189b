#!/usr/bin/python3
"""Draws the study's figures and writes REPORT.md from what `graspcd study` wrote.

Usage: /usr/bin/python3 report/make_report.py OUT_DIR
Reads OUT_DIR/study.json (Table 1, the box hand of Figures 13-15, recordings, machine, build),
OUT_DIR/sweep.json (the run-time/error sweep, possibly merged from shards) and, if present,
OUT_DIR/stress.json (`graspcd stress --json`, the numerical stress suite) and
OUT_DIR/perf.json (`./run perf`, graspcd against FCL and MuJoCo),
OUT_DIR/contacts.json (report/contacts_solver.py, what MuJoCo's solver gets) and
OUT_DIR/race.json, else the cached report/data/race.json (study/run_race.py, graspcd
against the hull and convex decompositions), OUT_DIR/objset.json, else report/data/objset.json
(study/run_objset.py, the object-set study), writes
OUT_DIR/REPORT.md and OUT_DIR/figures/*.png. Every number in the report comes from those files; the text around a
number is chosen by comparing numbers, never written in advance. Each section of REPORT.md is a
module of report/sections/ (its figures drawn there too); this script reads the files and puts the
sections in order.

Run with Debian's /usr/bin/python3 (python3-matplotlib), not whatever python3 is first on PATH.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import draw_figures  # noqa: E402  (report/draw_figures.py, beside this script)
from sections.box_hand import box_hand_section  # noqa: E402  (report/sections/, beside it)
from sections.contacts import contacts_section  # noqa: E402
from sections.differences import differences_section  # noqa: E402
from sections.heading import heading  # noqa: E402
from sections.objset import objset_section  # noqa: E402
from sections.performance import perf_section  # noqa: E402
from sections.race import race_section  # noqa: E402
from sections.real_hands import real_models_section  # noqa: E402
from sections.recordings import recordings_section  # noqa: E402
from sections.reproduce import reproduce_section  # noqa: E402
from sections.stress import stress_section  # noqa: E402
from sections.sweep import sweep_section  # noqa: E402
from sections.table1 import table1_section  # noqa: E402


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


def report(study, sweep, fig_dir, fig_rel, stress=None, perf=None):
    """REPORT.md from `graspcd study`'s study.json and sweep.json, with the stress and performance
    sections when their files are given; draws the figures into fig_dir."""
    lines = heading(study)
    lines.extend(recordings_section(study))
    lines.extend(table1_section(study, fig_dir, fig_rel))
    lines.extend(differences_section(study))
    lines.extend(box_hand_section(study, fig_dir, fig_rel))
    if sweep:
        lines.extend(sweep_section(sweep, fig_dir, fig_rel))
    if stress is not None:
        lines.extend(stress_section(stress))
    if perf is not None:
        lines.extend(perf_section(perf, fig_dir, fig_rel))
    lines.extend(reproduce_section(stress, perf))
    return "\n".join(lines)


def before_reproduce(text, section):
    """`text` with the section's lines put before its "## Reproduce" (at its end without one)."""
    at = text.find("## Reproduce")
    if at < 0:
        at = len(text)
    return text[:at].rstrip("\n") + "\n\n" + "\n".join(section) + "\n\n" + text[at:]


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
    text = report(study, sweep, fig_dir, args.figures, stress, perf)
    # Sections drawn from optional files of other scripts, each before "## Reproduce":
    # report/real_models.py (the real hands of ../shared/models), report/contacts_solver.py
    # (what the solver gets) and the race, OUT_DIR/race.json of study/run_race.py, else the
    # cached run, report/data/race.json.
    real = load(os.path.join(args.out_dir, "real_models.json"), required=False)
    if real is not None:
        text = before_reproduce(text, real_models_section(real))
    contacts = load(os.path.join(args.out_dir, "contacts.json"), required=False)
    if contacts is not None:
        text = before_reproduce(text, contacts_section(contacts))
    race = load(os.path.join(args.out_dir, "race.json"), required=False)
    if race is None:
        race = load(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "race.json"),
                    required=False)
    if race is not None:
        text = before_reproduce(text, race_section(race, fig_dir, args.figures))
    # The object set, OUT_DIR/objset.json of study/run_objset.py, else the committed run,
    # report/data/objset.json.
    objset = load(os.path.join(args.out_dir, "objset.json"), required=False)
    if objset is None:
        objset = load(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data",
                                   "objset.json"), required=False)
    if objset is not None:
        # A second run on a subset of the set (MuJoCo 3.14's configurations, which node runs at
        # 5-40 s of CPU a grasp): its own table, beside the first's.
        subset = load(os.path.join(args.out_dir, "objset-subset.json"), required=False)
        if subset is None and not os.path.exists(os.path.join(args.out_dir, "objset.json")):
            subset = load(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data",
                                       "objset-subset.json"), required=False)
        text = before_reproduce(text, objset_section(objset, fig_dir, args.figures, subset))
    # The pictures of the grasps and the trees, from OUT_DIR/trajectories when present.
    text = draw_figures.insert_section(text, args.out_dir, fig_dir, args.figures)
    with open(os.path.join(args.out_dir, "REPORT.md"), "w", encoding="utf-8") as f:
        f.write(text)
    print(f"wrote {os.path.join(args.out_dir, 'REPORT.md')} and {fig_dir}/*.png", file=sys.stderr)


if __name__ == "__main__":
    main()
