#!/usr/bin/python3
"""study/run_race.py's judged_run: a race row judged through `graspcd judge` (the grasp writes
its run record, the judge computes the verdicts and the contact counts from it) has the numbers
of the row of `graspcd grasp --judge --json` itself, all but the wall time per physics step.
Run by ctest as race_judge_test with GRASPCD and the mjcf folder; exit 0 when every check holds.
"""

import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "study"))
import run_race  # noqa: E402

graspcd, mjcf = sys.argv[1], sys.argv[2]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


# Example 2's can in the project's hand, "graspcd" at noslip 0: the row as the race made it from
# the grasp's own JSON, and judged from its record.
scene = os.path.join(mjcf, "example2.xml")
command = [graspcd, "grasp", scene, "--judge", "--json", "--noslip", "0"]
with tempfile.TemporaryDirectory() as work:
    g, message = run_race.grasp_run(command)
    check(g is not None, f"the grasp ran: {message}")
    judged, message = run_race.judged_run(graspcd, scene, command,
                                          os.path.join(work, "run.jsonl"))
    check(judged is not None, f"the grasp was judged: {message}")
    if g is not None and judged is not None:
        direct = run_race.row("graspcd", g, 0)
        through = run_race.row("graspcd", judged, 0)
        check(direct["outcome"] in ("held", "held tilted"), f"example 2 held: {direct}")
        check(set(direct) == set(through), "the same keys")
        for key in direct:
            if key == "ms_per_physics_step":
                continue
            check(direct[key] == through[key],
                  f"{key}: {direct[key]!r} directly, {through[key]!r} judged")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("judged rows keep their numbers")
