"""The race's outcome and score of one grasp run (study/run_race.py, report/make_report.py).

The outcome of a run, best first (OUTCOMES):
  held          held (`graspcd grasp`'s verdict), its final tilt under 2 degrees;
  held tilted   held, its final tilt 2 degrees or more (the verdict's "tilted N°");
  dropped       not held and not ejected: the hand did not keep the object (it fell off its
                support, left the hand, slipped, was pushed over, its grip rose too little;
                `reason` says which);
  ejected       the object was thrown out: faster than gravity and the hand could make it, or out
                of the scene other than downwards (the grasp's "ejected", grasp/verdicts.h);
  cannot start  the grasp refused the start (exit code 2 with "cannot start" or "the start state
                is not valid": a hull or pieces that hold a finger), or the run failed (its
                message says why): no grasp to judge.
The outcome is the library's (`outcome` in `graspcd grasp --json` and `graspcd judge --json`).
The score orders runs: first the outcome's rank (RANK: ejected and cannot start share the worst
rank, below every run that kept the object in the scene), then the deepest penetration of the true
meshes into the hand over the run (`true_penetration.hand_max`; `true_penetration_max` for a row
without the split; none counting as infinitely deep), then the judge's contact error per closing
step (phantom plus missed; none counting as infinite). Lower is better. The support's penetration
(the table or floor the object stands on) is not in the score, as the judge leaves the support
out: its contact with the object is MuJoCo's native one in every configuration, and an object
thrown through it is ejected, which the outcome ranks.
"""

import math

OUTCOMES = ["held", "held tilted", "dropped", "ejected", "cannot start"]
RANK = {"held": 0, "held tilted": 1, "dropped": 2, "ejected": 3, "cannot start": 3}
# The verdict's tilt note starts at this final tilt (grasp_result.h, kTiltShownDeg).
TILT_SHOWN_DEG = 2.0


def outcome(g):
    """The outcome of a grasp's --json document `g` (a run that started): the library's
    "outcome" (grasp/verdicts.h, the same in `graspcd grasp --json` and `graspcd judge --json`);
    for a document without it (graspcd before 0.5.0), from its ejected, held and tilt."""
    if "outcome" in g:
        return g["outcome"]
    if g.get("ejected"):
        return "ejected"
    if g["held"]:
        return "held tilted" if g.get("tilt_final_deg", 0) >= TILT_SHOWN_DEG else "held"
    return "dropped"


def row_outcome(r):
    """A race row's outcome: its "outcome", or for a row of a race before outcomes were recorded,
    "held" or "dropped" from its held flag (such a row says nothing of tilt or ejection)."""
    if "outcome" in r:
        return r["outcome"]
    return "held" if r.get("held") else "dropped"


def _number(x):
    return math.inf if x is None else x


def hand_penetration(r):
    """The deepest true penetration of a row into the hand, m, or None when not measured."""
    tp = r.get("true_penetration")
    if tp and tp.get("hand_max") is not None:
        return tp["hand_max"]
    return r.get("true_penetration_max")


def score(r):
    """The sort key of a race row: (outcome rank, true penetration into the hand, contact error);
    lower is better."""
    return (RANK[row_outcome(r)], _number(hand_penetration(r)),
            _number(r.get("contact_error_per_step")))


def kept(r):
    """Whether the run kept the object in the scene and the hand (held, tilted or not)."""
    return RANK[row_outcome(r)] <= RANK["held tilted"]
