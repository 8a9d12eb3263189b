"""The section "Real hands and objects" from real_models.json (report/real_models.py): the real
hands of ../shared/models on the scenes mjcf/real_*.xml, their grasps and their agreement with
CGAL."""


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
