#!/usr/bin/python3
"""study/run_race.py's MuJoCo 3.14 rows on one case: `run_race.py GRASPCD --scenes
concave_robotiq_mug_rim --configurations "3.14 hull" --noslip 0` runs the node runner
(tools/mujoco3/grasp3.mjs) with the six directions, keeps its record in --work, and judges it
with `graspcd judge`. 3.14's hull starts 15-32 mm inside the mug (docs/mujoco3.md): the row must
say "cannot start" (the judge's start rule on 3.14's own contacts) or "ejected", never a grip, and
the record must show why (its first closing contacts deeper than 0.5 mm, or the mug faster than
2 m/s).
The row carries a WebAssembly step cost (the runner's CPU time per step) and no native one, the race.json no path of this
machine, and the report's race section shows the row. A second race of the same scene judges
the kept record again without running node (the record is not rewritten).

Run by ctest as race_mujoco3_test (label slow) with GRASPCD, the executable; exits 77 (skipped),
saying why, where node, tools/mujoco3's npm packages or ../shared/models is missing."""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "study"))
sys.path.insert(0, str(ROOT / "report"))
import race_judged  # noqa: E402

SKIP = 77
SCENE = "concave_robotiq_mug_rim"


def skip(why):
    print(f"race_mujoco3_test: skipped: {why}")
    sys.exit(SKIP)


graspcd = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build" / "graspcd")
missing = race_judged.mujoco3_missing()
if missing:
    skip(missing)
if not (ROOT.parent / "shared" / "models").is_dir():
    skip(f"{ROOT.parent / 'shared' / 'models'} is missing (the scene's hand and mesh)")

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def race(work, out):
    done = subprocess.run(
        ["/usr/bin/python3", str(ROOT / "study" / "run_race.py"), graspcd, "--scenes", SCENE,
         "--configurations", "3.14 hull", "--noslip", "0", "--work", work, "--out", out],
        capture_output=True, text=True, cwd=ROOT)
    if done.returncode != 0:
        print(done.stderr, file=sys.stderr)
        sys.exit(f"race_mujoco3_test: run_race.py exited {done.returncode}")
    with open(out, encoding="utf-8") as f:
        text = f.read()
    return text, json.loads(text)


with tempfile.TemporaryDirectory() as tmp:
    work = os.path.join(tmp, "work")
    text, data = race(work, os.path.join(tmp, "race.json"))
    rows = data["scenes"][SCENE]["rows"]
    check([r["configuration"] for r in rows] == ["3.14 hull"], f"rows {rows}")
    r = rows[0]
    check(r["simulator"] == race_judged.SIMULATOR, f"simulator {r.get('simulator')}")
    check(r["outcome"] in ("cannot start", "ejected"),
          f"3.14's hull of the mug: outcome {r['outcome']} ({r.get('message')})")
    check(not r["held"], "3.14's hull of the mug is not held")
    check(r["ms_per_physics_step"] is None, "no native step cost on a WebAssembly row")
    if r["outcome"] != "cannot start":
        check(r["ms_per_physics_step_wasm"] > 0, "a WebAssembly step cost")
        check(r["six_directions"]["of"] == 6, f"six directions {r.get('six_directions')}")
        check(r["phantom"] is not None and r["missed"] is not None, "the judge's contact counts")
    else:
        check(r["message"], "a row that cannot start says why")
    record = os.path.join(work, "records", SCENE, "3.14_hull_noslip0.jsonl")
    check(os.path.exists(record), f"the record kept in --work: {record}")
    with open(record, encoding="utf-8") as f:
        lines = [json.loads(x) for x in f]
    header = lines[0]
    check(header.get("six_directions") is not None, "the record has the six directions")
    check(header.get("multiccd") is True, "3.14's default: multiccd on")
    with open(record + ".summary.json", encoding="utf-8") as f:
        summary = json.load(f)
    check(summary.get("step_cpu_ms", 0) > 0, f"the runner's CPU ms per step: {summary}")
    check(r.get("step_clock") == "cpu", f"the row's step cost is CPU time: {r}")
    # Why: 3.14's hull holds the pad inside the mug's wall from the first step, its first closing
    # contacts deeper than graspcd's start rule allows (0.5 mm), or it throws the mug out (faster
    # than 2 m/s); or the runner found that it cannot start.
    if lines[-1]["end"]["status"] == "ok":
        close = next(x for x in lines if x.get("phase") == "close")
        deepest = max((-c["dist"] for c in close["contacts"]), default=0.0)
        fastest = r.get("max_speed") or 0.0
        check(deepest > 0.0005 or fastest > 2.0,
              f"deepest first contact {deepest} m, fastest {fastest} m/s")
    else:
        check(lines[-1]["end"]["status"] == "cannot start", f"end {lines[-1]['end']}")
    check(tmp not in text and str(ROOT) not in text,
          "race.json carries no path of this machine")
    check(data["scenes"][SCENE]["mujoco3"] is None, "the scene was raced in 3.14")
    judged_by = data["scenes"][SCENE]["provenance"].get("graspcd", {})
    check(judged_by.get("version") not in (None, "?") and judged_by.get("commit") not in (None, "?"),
          f"the scene's provenance names the graspcd that judged it: {judged_by}")

    # The report's race section shows the row, its WebAssembly cost in its own column.
    from sections.race import race_section  # noqa: E402  (report/sections)
    lines = race_section(data, tmp, "figures")
    shown = [x for x in lines if x.startswith(f"| {SCENE} | 3.14 hull | 0 |")]
    check(len(shown) == 1, f"the report's row: {shown}")
    check(any(x.startswith("### Against MuJoCo 3.14") for x in lines),
          "the report's 3.14 subsection")

    # Raced again: the kept record is judged again, not rewritten by node.
    before = os.stat(record).st_mtime_ns
    _, again = race(work, os.path.join(tmp, "again.json"))
    check(os.stat(record).st_mtime_ns == before, "the kept record is reused")
    r2 = again["scenes"][SCENE]["rows"][0]
    check((r2["outcome"], r2.get("message"), r2.get("true_penetration_max"))
          == (r["outcome"], r.get("message"), r.get("true_penetration_max")),
          "the same record judges to the same row")

for f in failures:
    print(f"race_mujoco3_test: FAILED: {f}", file=sys.stderr)
sys.exit(1 if failures else 0)
