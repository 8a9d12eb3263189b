"""The section "Contacts and the solver" from contacts.json (report/contacts_solver.py): each
scene's grasp natively, served with the contact manifold, served with every contact as before the
manifold, and with contacts reused, and what MuJoCo's solver makes of them at rest."""


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
          f" set on {', '.join(worse)} (docs/design.md, \"The MuJoCo layer\", says what the"
          " budget costs).")
    return lines
