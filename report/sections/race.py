"""The section "The race" from race.json (study/run_race.py): graspcd against MuJoCo on the
object's hull and on convex decompositions, on the same grasps. What was raced and where, the
decompositions, one row per run with its outcome and costs, the figure of step cost against
contact error and true-mesh penetration, and the findings (sections/race_findings.py)."""

import os

import matplotlib.pyplot as plt
import race_score  # study/race_score.py (on the path: sections/__init__.py)

from sections.numbers import opt
from sections.race_findings import race_findings
from sections.race_mujoco3 import mujoco3_section


def race_section(race, fig_dir, fig_rel):
    """The whole section, in order."""
    lines = race_intro(race)
    lines.extend(race_runs(race))
    lines.extend(race_scenes(race))
    lines.extend(race_decompositions(race))
    lines.extend(race_protocol_text(race))
    lines.extend(race_rows(race, fig_dir, fig_rel))
    lines.extend(race_findings(race))
    lines.extend(mujoco3_section(race))
    return lines


def race_intro(race):
    """What the race runs and how each column is measured."""
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
      " so its row runs without it. The step cost is the CPU time per physics step over the"
      " whole grasp (single runs one after another, not a benchmark; CPU time, since the race"
      " shares the machine with other work and wall time grows with it; \"(wall)\" marks a row"
      " of a run that did not measure CPU time); contacts are hand-object"
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
    return lines


def race_runs(race):
    """The runs this race.json comes from: one command, or the races it joins."""
    lines = []
    w = lines.append
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
    return lines


def race_scenes(race):
    """One row per scene: what was raced, the piece counts, and the race's provenance; then the
    scenes whose rows come from another file, and the scenes' notes."""
    lines = []
    w = lines.append
    m = race["machine"]
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
    return lines


def race_decompositions(race):
    """One row per decomposition: its pieces, engine, time, Hausdorff distance, volume added."""
    lines = []
    w = lines.append
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
    return lines


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


def race_rows(race, fig_dir, fig_rel):
    """One row per run, and the figure of their step costs, contact errors and penetrations."""
    lines = [""]
    w = lines.append
    w("| scene | configuration | noslip | outcome | six directions | tilt final (deg) |"
      " top speed (m/s) | kinetic energy (mJ) | true penetration: hand, support (mm) |"
      " step cost, native (CPU ms) | step cost, WebAssembly (CPU ms) | contacts per step |"
      " first contact as CGAL's | phantom, missed | contact error per step |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    fig, (ax, axp) = plt.subplots(1, 2, figsize=(13, 4.8))
    markers = "osD^v<>phH*"
    for k, (scene, e) in enumerate(race["scenes"].items()):
        points = {True: ([], [], []), False: ([], [], [])}
        for r in e["rows"]:
            w(row_line(scene, r))
            # A WebAssembly step cost is not on the native axis, nor a wall time on a CPU one.
            if (race_score.row_outcome(r) != "cannot start"
                    and r.get("ms_per_physics_step") is not None
                    and r.get("step_clock") == "cpu"):
                plot_row(r, ax, axp, points)
        plot_scene(scene, color=f"C{k % 10}", marker=markers[k % len(markers)], points=points,
                   ax=ax, axp=axp)
    finish_race_figure(fig, ax, axp, fig_dir)
    w("")
    w(f"![step cost against contact error and true-mesh penetration]({fig_rel}/race_pareto.png)")
    w("")
    w("Filled markers: the object was kept (held, tilted or not); hollow: it was not (dropped,"
      " ejected; a run that could not start has no point). Rows whose step cost is wall time"
      " (an earlier race's) and MuJoCo 3.14's rows (a WebAssembly step cost, not a native one)"
      " are not in the figure.")
    w("")
    return lines


def row_line(scene, r):
    """A run's row of the table."""
    outcome = race_score.row_outcome(r)
    noslip = r.get("noslip")
    if outcome == "cannot start":
        # The grasp's message from "cannot start" on (without the scene's and the
        # pieces' paths, which race.json keeps).
        message = r.get("message") or ""
        at = message.find("cannot start with ")
        message = message[at + len("cannot start with "):] if at >= 0 else message
        return (f"| {scene} | {r['configuration']} | {noslip} | cannot start:"
                f" {message.replace('|', '/')} | - | - | - | - | - | - | - | - | - | - | - |")
    # A segment is a geom name (the project's hands) or a "body:NAME" touch pattern.
    segments = r["first_contact"]
    same = sum(1 for seg, step in segments.items()
               if (r["cgal_first_contact_body"].get(seg[5:]) if seg.startswith("body:")
                   else r["cgal_first_contact"].get(seg)) == step)
    shown = outcome if "outcome" in r else ("held" if r["held"] else "not held")
    if "outcome" in r and outcome == "dropped" and r.get("reason"):
        shown = f"dropped ({r['reason']})"
    return (f"| {scene} | {r['configuration']} | {'-' if noslip is None else noslip} |"
            f" {shown} | {six_directions_cell(r)} | {opt(r.get('tilt_final_deg'), '.1f')} |"
            f" {opt(r.get('max_speed'), '.3g')} |"
            f" {opt(None if r.get('kinetic_energy_max') is None else 1000 * r['kinetic_energy_max'], '.3g')} |"
            f" {penetration_cell(r)} |"
            f" {cost_cell(r, 'ms_per_physics_step')} |"
            f" {cost_cell(r, 'ms_per_physics_step_wasm')} |"
            f" {opt(r.get('contacts_per_step'), '.1f')} |"
            f" {same} of {len(segments)} |"
            f" {by_geom(r['phantom'], r.get('phantom_by_geom'))},"
            f" {by_geom(r['missed'], r.get('missed_by_geom'))} |"
            f" {opt(r.get('contact_error_per_step'), '.2f')} |")


def cost_cell(r, key):
    """A row's step cost (`key`: the native or the WebAssembly column): CPU ms per physics step,
    or wall ms marked "(wall)" for a run that did not measure CPU time (study/race_judged.py)."""
    if r.get(key) is None:
        return "-"
    cell = opt(r[key], ".3f")
    return cell if r.get("step_clock") == "cpu" else f"{cell} (wall)"


def six_directions_cell(r):
    """A row's six-direction result: "6 of 6", "4 of 6 (lost -y, -z)", "-" without the test."""
    six = r.get("six_directions")
    if not six:
        return "-"
    lost = [d["direction"] for d in six.get("directions", []) if not d.get("passed")]
    return f"{six['held']} of {six['of']}" + (f" (lost {', '.join(lost)})" if lost else "")


def plot_row(r, ax, axp, points):
    """A run that started: its point (kept or not) and its label in both panels."""
    noslip = r.get("noslip")
    tp = race_score.hand_penetration(r)
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


def plot_scene(scene, color, marker, points, ax, axp):
    """A scene's points, filled where the object was kept, hollow where it was not."""
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


def finish_race_figure(fig, ax, axp, fig_dir):
    """The panels' scales, labels and legend; saves race_pareto.png."""
    ax.set_xscale("log")
    ax.set_xlabel("step cost: CPU ms per physics step (log)")
    ax.set_ylabel("contact error: phantom + missed per closing step")
    ax.set_title("Contact error (the judge)")
    if not axp.collections:
        axp.text(0.5, 0.5, "no row of this race.json measured the true meshes", ha="center",
                 va="center", transform=axp.transAxes, fontsize=8)
    axp.set_xscale("log")
    axp.set_yscale("log")
    axp.set_xlabel("step cost: CPU ms per physics step (log)")
    axp.set_ylabel("deepest true penetration into the hand (mm, log; at least 0.01)")
    axp.set_title("True-mesh penetration (the protocol's rows)")
    # The legend beside the axes, never over the points.
    axp.legend(*ax.get_legend_handles_labels(), fontsize=6, loc="upper left",
               bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    fig.savefig(os.path.join(fig_dir, "race_pareto.png"), dpi=120, bbox_inches="tight")
    plt.close(fig)


def penetration_cell(r):
    """A row's deepest true penetration into the hand and into the support, mm ("hand 0.2,
    support 3.1"), "-" for a row without it."""
    tp = r.get("true_penetration")
    if not tp:
        return "-"
    return f"{1000 * tp['hand_max']:.3g}, {1000 * tp['support_max']:.3g}"


def by_geom(total, counts):
    """A phantom or missed count with the hand geoms it came from: "1 (finger2_C 1)"."""
    if not total or not counts:
        return str(total)
    return f"{total} ({', '.join(f'{g} {n}' for g, n in sorted(counts.items()))})"
