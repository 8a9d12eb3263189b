"""The section "The recorded grasps": each grasp the study replays, how it was recorded, and its
first contacts beside CGAL's."""

# grasp::finger_segment_names() (src/graspcd/grasp/grasp_result.h): the order of every
# per-segment array in study.json.
SEGMENTS = [f"finger{f}_{s}" for f in range(1, 5) for s in "ABC"]


def recordings_section(study):
    lines = []
    w = lines.append
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
    return lines
