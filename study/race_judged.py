"""The race's runs judged by `graspcd judge` (study/run_race.py): every run writes a run record
(docs/run-record.md) and its row's verdicts come from judging that record on the true meshes.

- graspcd's own configurations (graspcd, its exact contacts, MuJoCo 2.2 on the hull or on
  convex pieces): `graspcd grasp SCENE --judge --json --write-run RECORD --six-directions`, then
  `graspcd judge SCENE RECORD --json`. The step cost, the contacts per step and the simulator's
  first contacts are the grasp's (what it measured while it ran: the step cost is its
  cpu_ms_per_physics_step, the thread's CPU time per physics step); the outcome, the verdicts, the
  true penetration, the six directions and the phantom and missed contacts are the judge's.
- MuJoCo 3.14 (the official WebAssembly build, run by node: tools/mujoco3/grasp3.mjs,
  docs/mujoco3.md) in four configurations of the object's collision, on the scenes whose pair
  config has a "grasp" section: its hull with multiccd on (3.14's default), the mesh SDF with
  sdf_initpoints 40 (the default) and 10, and the rigid flex (radius 0.5 mm). The runner writes
  the record (cached in WORK/mujoco3: a record that exists is judged again, not run again, since
  node takes 10 s to a few minutes per run), `graspcd judge` judges it. Its step cost is
  WebAssembly's, the node process's CPU time per mj_step as the runner measures it (its wall time
  grows with whatever else the machine runs): it goes in its own column
  (ms_per_physics_step_wasm), never beside a native one (ms_per_physics_step is null).
- Every row's step cost is CPU time ("step_clock": "cpu"); "wall" marks a row whose run did not
  measure it (a record or a grasp of an earlier build), and a row merged from an earlier race
  without the field is wall time too.
"""

import json
import os
import shutil
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUNNER = os.path.join(ROOT, "tools", "mujoco3", "grasp3.mjs")
PACKAGE = os.path.join(ROOT, "tools", "mujoco3", "node_modules", "@mujoco", "mujoco")
SIMULATOR = "MuJoCo 3.14.0 (WebAssembly)"
# The race's name of each configuration and the runner's (--configuration).
MUJOCO3 = {"3.14 hull": "hull", "3.14 sdf": "sdf", "3.14 sdf10": "sdf10", "3.14 flex": "flex"}
# The phases a run's contacts per step are counted over: the grasp, without the six directions
# (graspcd's grasp counts its mean contacts over the same phases).
GRASP_PHASES = ("close", "squeeze", "settle", "lift", "hold")


def driven(scene):
    """Whether the scene's pair config (SCENE.pairs.json beside it) has a "grasp" section: a hand
    driven through its actuators, which the node runner drives as graspcd does."""
    config = os.path.splitext(scene)[0] + ".pairs.json"
    try:
        with open(config, encoding="utf-8") as f:
            return "grasp" in json.load(f)
    except (OSError, ValueError):
        return False


def mujoco3_missing(node="node"):
    """Why MuJoCo 3.14's rows cannot run here (None when they can): node or the npm package."""
    if shutil.which(node) is None:
        return f"{node} is not on PATH"
    if not os.path.isdir(PACKAGE):
        return "tools/mujoco3's npm packages are not installed (cd tools/mujoco3 && npm ci)"
    return None


def run_measured(command):
    """Runs `command`: (exit code, stdout, stderr, cost), cost the process's {cpu_s: user +
    system seconds, wall_s} (os.wait4: its own, whatever else the machine runs)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        p = subprocess.Popen(command, stdout=out, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
        cost = {"cpu_s": round(usage.ru_utime + usage.ru_stime, 3),
                "wall_s": round(time.monotonic() - start, 3)}
        out.seek(0)
        err.seek(0)
        return (os.waitstatus_to_exitcode(status), out.read().decode(errors="replace"),
                err.read().decode(errors="replace"), cost)


def judge(graspcd, scene, record):
    """`graspcd judge SCENE RECORD --json`: (its document, None), or (None, its one-line error)."""
    done = subprocess.run([graspcd, "judge", scene, record, "--json"], capture_output=True,
                          text=True)
    if done.returncode != 0:
        lines = [x for x in done.stderr.strip().splitlines() if not x.startswith("warning:")]
        return None, (lines[-1] if lines else f"graspcd judge: exit {done.returncode}")
    return json.loads(done.stdout), None


def verdict_fields(j):
    """The judged verdicts of a row (the judge's document `j`)."""
    tp = j.get("true_penetration")
    return {"outcome": j["outcome"],
            "message": j.get("message"),
            "reason": j.get("reason"),
            "ejected": j.get("ejected"),
            "gripped": j.get("gripped", False), "held": j.get("held", False),
            "tilt_deg": j.get("tilt_deg"), "tilt_final_deg": j.get("tilt_final_deg"),
            "max_speed": j.get("max_speed"),
            "kinetic_energy_max": j.get("kinetic_energy_max"),
            "true_penetration_max": j.get("true_penetration_max"),
            "true_penetration": tp,
            "rise": (None if j.get("object_z_final") is None else
                     j["object_z_final"] - j["object_z_initial"]),
            "six_directions": j.get("six_directions")}


def contact_fields(judged):
    """The judge's phantom and missed contacts (`judge` of its document; None without contacts)."""
    if not judged:
        return {"cgal_first_contact": {}, "cgal_first_contact_body": {}, "closing_steps": None,
                "judged_contacts": None, "phantom": None, "missed": None,
                "phantom_by_geom": None, "missed_by_geom": None,
                "contact_error_per_step": None}
    return {"cgal_first_contact": judged.get("cgal_first_contact", {}),
            "cgal_first_contact_body": judged.get("cgal_first_contact_body", {}),
            "closing_steps": judged["steps"], "judged_contacts": judged["contacts"],
            "phantom": judged["phantom"], "missed": judged["missed"],
            "phantom_by_geom": judged["phantom_by_geom"],
            "missed_by_geom": judged["missed_by_geom"],
            "contact_error_per_step": judged["contact_error_per_step"]}


def judged_row(name, j, noslip, multiccd, grasp=None, summary=None):
    """A race row from the judge's document `j` of a run's record: the verdicts and contact
    errors the judge computed; the step cost, contacts per step and first contacts from what
    the run measured: graspcd's grasp JSON `grasp` (native milliseconds), or the node runner's
    `summary` (WebAssembly milliseconds, its own column)."""
    r = {"configuration": name, "noslip": noslip, "multiccd": multiccd,
         "simulator": j.get("simulator"), "inflation": j.get("inflation", 0)}
    r.update(verdict_fields(j))
    r.update(contact_fields(j.get("judge")))
    if grasp is not None:
        # The CPU time per physics step (the grasp's thread: what the steps cost, whatever
        # else the machine runs); the wall time where the grasp did not measure it.
        r.update({"ms_per_physics_step": grasp.get("cpu_ms_per_physics_step",
                                                   grasp["ms_per_physics_step"]),
                  "step_clock": "cpu" if "cpu_ms_per_physics_step" in grasp else "wall",
                  "ms_per_physics_step_wasm": None,
                  "contacts_per_step": grasp["mean_contacts"],
                  "first_contact": grasp["first_contact"]})
    else:
        s = summary or {}
        r.update({"ms_per_physics_step": None,
                  # The runner's CPU time per mj_step; a summary without it (a runner before
                  # it measured CPU time) gives its wall time, and the row says which.
                  "ms_per_physics_step_wasm": s.get("step_cpu_ms", s.get("step_ms")),
                  "step_clock": "cpu" if "step_cpu_ms" in s else "wall",
                  "contacts_per_step": s.get("contacts_per_step"),
                  "first_contact": s.get("first_contact", {})})
    return r


def grasp_row(graspcd, name, command, scene, record, noslip, multiccd):
    """One run of graspcd's: the grasp (`command`, a `graspcd grasp ... --judge --json` list)
    writes RECORD with the six directions, the judge judges it. (row, None, the grasp's graspcd
    provenance: version and commit), or (None, message, None) when the grasp or the judge
    refused."""
    if os.path.exists(record):
        os.remove(record)
    os.makedirs(os.path.dirname(record) or ".", exist_ok=True)
    done = subprocess.run(command + ["--write-run", record, "--six-directions"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        lines = [x for x in done.stderr.strip().splitlines() if not x.startswith("warning:")]
        message = lines[-1] if lines else f"exit {done.returncode}"
        # A start the grasp refused still writes its record: the judge's "cannot start" on it.
        j = judge(graspcd, scene, record)[0] if os.path.exists(record) else None
        if j is None or j["outcome"] != "cannot start":
            return None, message, None
        r = judged_row(name, j, noslip, multiccd)
        r["grasp_outcome"] = "cannot start"
        return r, None, j.get("graspcd", {})
    g = json.loads(done.stdout)
    j, message = judge(graspcd, scene, record)
    if j is None:
        return None, message, None
    r = judged_row(name, j, g.get("noslip_iterations", noslip), g.get("multiccd", multiccd),
                   grasp=g)
    # What graspcd's own run concluded, kept beside the judge's verdict: the two agree (a judged
    # record gives the run's verdicts), and a row where they do not says so.
    r["grasp_outcome"] = g.get("outcome")
    return r, None, g.get("graspcd", {})


def mujoco3_record(scene, configuration, noslip, record, node="node"):
    """The node runner's record of (scene, configuration, noslip), made unless it exists, with
    the six directions; its summary (RECORD.summary.json: the runner's --summary, with the
    contacts per step and the node process's cost, {cpu_s, wall_s}, added) or None where 3.14
    could not start; and a message where the runner failed without a record (bad input, a
    defect: exit 1 or 2)."""
    summary_file = summary_file_of(record)
    if os.path.exists(failed_file(record)) and not os.path.exists(record):
        with open(failed_file(record), encoding="utf-8") as f:
            return None, f.read().strip()
    if not os.path.exists(record):
        os.makedirs(os.path.dirname(record) or ".", exist_ok=True)
        code, stdout, stderr, cost = run_measured(
            [node, RUNNER, scene, "--configuration", configuration, "--noslip", str(noslip),
             "--six-directions", "--summary", "--out", record])
        if code not in (0, 3):
            message = failure_message(code, stderr)
            with open(failed_file(record), "w", encoding="utf-8") as f:
                f.write(message + "\n")
            return None, message
        text = stdout.strip()
        with open(summary_file, "w", encoding="utf-8") as f:
            f.write(json.dumps(dict(json.loads(text), process=cost)) + "\n" if text else "")
    summary = summary_of(record)
    if summary is not None and "contacts_per_step" not in summary:
        summary["contacts_per_step"] = contacts_per_step(record)
        with open(summary_file, "w", encoding="utf-8") as f:
            f.write(json.dumps(summary) + "\n")
    return summary, None


def summary_file_of(record):
    """Where the runner's summary of a record is kept (RECORD.summary.json)."""
    return record + ".summary.json"


def summary_of(record):
    """The kept summary of a record (mujoco3_record), or None: none kept, or 3.14 could not
    start."""
    if not os.path.exists(summary_file_of(record)):
        return None
    with open(summary_file_of(record), encoding="utf-8") as f:
        text = f.read().strip()
    return json.loads(text) if text else None


def failed_file(record):
    """Where a run that wrote no record keeps why (RECORD.failed), so that a later race reports it
    again without running node."""
    return record + ".failed"


def failure_message(code, stderr):
    """The row's message of a runner that wrote no record: its one line (bad input, exit 2), or
    the first line of its stack (exit 1: an error MuJoCo 3.14 raised during the run, as
    "collisionTask: collision function returned 11 contacts", or a defect of the runner)."""
    lines = [x.strip() for x in stderr.strip().splitlines() if x.strip()]
    first = lines[0] if lines else f"exit {code}"
    for prefix in ("grasp3.mjs: ", "Error: "):
        first = first[len(prefix):] if first.startswith(prefix) else first
    if code == 1:
        return f"the runner stopped during the run (exit 1): {first}"
    return first


def contacts_per_step(record):
    """The hand-object contacts per physics step of a record with contacts, over the grasp's
    phases (close to hold): contacts whose other side is not the support's body (the table,
    whose contact with the object is not the grasp's). None without contacts."""
    steps = contacts = 0
    with open(record, encoding="utf-8") as f:
        header = json.loads(f.readline())
        if not header.get("contacts"):
            return None
        support, obj = header.get("support"), header.get("object")
        for line in f:
            s = json.loads(line)
            if s.get("phase") not in GRASP_PHASES:
                continue
            steps += 1
            for c in s.get("contacts", []):
                other = c["b"] if c["a"]["body"] == obj else c["a"]
                if other["body"] != support:
                    contacts += 1
    return contacts / steps if steps else None


def mujoco3_row(graspcd, name, scene, record, noslip, node="node"):
    """MuJoCo 3.14's row of one (scene, configuration `name`, noslip): the record made (or
    reused) and judged. (row, None, the judge's graspcd provenance: version and commit), or
    (None, message, None) where no record could be judged."""
    summary, message = mujoco3_record(scene, MUJOCO3[name], noslip, record, node)
    if message is not None:
        return None, message, None
    j, message = judge(graspcd, scene, record)
    if j is None:
        return None, message, None
    r = judged_row(name, j, noslip, j.get("multiccd"), summary=summary)
    r["record"] = os.path.basename(record)
    return r, None, {"graspcd": j.get("graspcd", {})}
