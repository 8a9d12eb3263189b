#!/usr/bin/python3
"""study/race_score.py: the race's outcome and score on made-up rows and grasp documents. An
ejected or unstarted run scores worse than any run that kept the object, whatever its penetration
and contact error; within an outcome the true penetration into the hand decides, then the contact
error. Run by ctest as race_score_test; exit 0 when every check holds."""

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "study"))
import race_score  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def row(outcome, penetration, error, name):
    return {"configuration": name, "outcome": outcome, "true_penetration_max": penetration,
            "contact_error_per_step": error}


# Outcomes from grasp documents.
check(race_score.outcome({"held": True, "tilt_final_deg": 0.5, "ejected": None}) == "held",
      "held, 0.5 degrees")
check(race_score.outcome({"held": True, "tilt_final_deg": 2.0, "ejected": None}) == "held tilted",
      "held, 2 degrees is tilted")
check(race_score.outcome({"held": False, "tilt_final_deg": 0, "ejected": None}) == "dropped",
      "not held, not ejected")
check(race_score.outcome({"held": False, "ejected": {"t": 1, "speed": 57, "cause": "speed"}})
      == "ejected", "ejected")

# The worst run that kept the object (dropped, deep, many errors) beats the best ejected or
# unstarted one (no penetration, no error).
rows = [
    row("cannot start", None, None, "refused"),
    row("ejected", 0.0, 0.0, "ejected clean"),
    row("dropped", 0.05, 9.0, "dropped deep"),
    row("held tilted", 0.002, 0.0, "tilted"),
    row("held", 0.004, 3.0, "held deeper"),
    row("held", 0.001, 5.0, "held shallow"),
    row("held", 0.001, 1.0, "held shallow, fewer errors"),
]
order = [r["configuration"] for r in sorted(rows, key=race_score.score)]
check(order == ["held shallow, fewer errors", "held shallow", "held deeper", "tilted",
                "dropped deep", "ejected clean", "refused"], f"order {order}")
for bad in ("ejected clean", "refused"):
    b = next(r for r in rows if r["configuration"] == bad)
    for good in rows:
        if good["outcome"] in ("held", "held tilted", "dropped"):
            check(race_score.score(good) < race_score.score(b),
                  f"{good['configuration']} before {bad}")
# Ejected and cannot start share the worst rank.
check(race_score.RANK["ejected"] == race_score.RANK["cannot start"], "the worst rank is shared")
check(race_score.score(rows[0])[1] == math.inf, "no penetration counts as infinite")
# A row of an older race (no outcome): its held flag.
check(race_score.row_outcome({"held": True}) == "held", "old held row")
check(race_score.row_outcome({"held": False}) == "dropped", "old row not held")
check(race_score.kept(rows[3]) and not race_score.kept(rows[2]), "kept: held, tilted or not")

# The hand's penetration is scored, the support's is not: an object sunk into its table but
# shallow in the hand ranks before one deeper in the hand.
sunk = dict(row("held", 0.004, 0.0, "sunk into the table"),
            true_penetration={"hand_max": 0.0002, "support_max": 0.004})
deep = dict(row("held", 0.001, 0.0, "deeper in the hand"),
            true_penetration={"hand_max": 0.001, "support_max": 0.0})
check(race_score.score(sunk) < race_score.score(deep), "the hand's penetration, not the table's")
check(race_score.hand_penetration(sunk) == 0.0002, "hand_max read")

for f in failures:
    print(f"race_score_test: FAILED: {f}", file=sys.stderr)
sys.exit(1 if failures else 0)
