#!/usr/bin/python3
"""study/run_race.py: the configurations a race runs (--multiccd, --configurations) and
--merge of a scene raced in two files, on made-up rows. A configuration with MuJoCo's multiccd is
named after its route with " multiccd"; the default races every configuration but "graspcd
multiccd"; patterns select by name; --merge keeps the merged file's rows of configurations and
noslip values not raced now, and says where they came from. Run by ctest as
race_configurations_test; exit 0 when every check holds."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "study"))
import run_race  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


# Names: without and with multiccd, in the order of --multiccd.
check(run_race.configuration_names("native hull", [0, 1])
      == [("native hull", False), ("native hull multiccd", True)], "native hull, 0 and 1")
check(run_race.configuration_names("decomposed-16", [1])
      == [("decomposed-16 multiccd", True)], "decomposed-16, 1 only")

# The default: all but graspcd with multiccd.
for name in ("graspcd", "native hull", "native hull multiccd", "decomposed-16",
             "vhacd-16 multiccd"):
    check(run_race.selected(name, None), f"{name} raced by default")
check(not run_race.selected("graspcd multiccd", None), "graspcd multiccd not raced by default")

# The baselines only, as the multiccd race ran them: every native and decomposed configuration.
baselines = ["native hull*", "decomposed-*", "vhacd-*"]
for name in ("native hull", "native hull multiccd", "decomposed-8", "decomposed-16 multiccd",
             "vhacd-16"):
    check(run_race.selected(name, baselines), f"{name} is a baseline")
for name in ("graspcd", "graspcd multiccd"):
    check(not run_race.selected(name, baselines), f"{name} is not a baseline")
# graspcd's rows alone, raced again later; a name is matched whole, not as a prefix.
check(run_race.selected("graspcd", ["graspcd"]), "graspcd by name")
check(not run_race.selected("graspcd multiccd", ["graspcd"]), "a name is not a prefix")
check(run_race.selected("graspcd multiccd", ["graspcd*"]), "graspcd* names both")


def row(configuration, noslip, outcome):
    return {"configuration": configuration, "noslip": noslip, "outcome": outcome}


# --merge of a scene raced now (graspcd) and in the merged file (the baselines, and an older
# graspcd row at the same noslip, which the new one replaces).
new = {"rows": [row("graspcd", 0, "held")], "decompositions": {}}
old_entry = {"rows": [row("graspcd", 0, "dropped"), row("native hull", 0, "ejected"),
                      row("native hull multiccd", 0, "held"), row("decomposed-16", 0, "held")],
             "decompositions": {"16": {"engine": "hacd", "pieces": 16}},
             "provenance": {"graspcd": {"version": "0.3.0", "commit": "abc"}, "date": "then"}}
old = {"machine": {}, "scenes": {"s": old_entry}}
run_race.merge_rows(new, old_entry, old, "/somewhere/baselines.json")
keys = [run_race.row_key(r) for r in new["rows"]]
check(keys == [("graspcd", 0), ("native hull", 0), ("native hull multiccd", 0),
               ("decomposed-16", 0)], f"merged rows {keys}")
check(new["rows"][0]["outcome"] == "held", "the row raced now wins")
check(new["decompositions"].get("16", {}).get("pieces") == 16, "the merged decomposition kept")
merged = new.get("merged_rows", [])
check(len(merged) == 1 and merged[0]["file"] == "baselines.json"
      and merged[0]["configurations"] == ["decomposed-16", "native hull",
                                          "native hull multiccd"]
      and merged[0]["provenance"]["date"] == "then", f"merged_rows {merged}")
check(merged and merged[0].get("rows") == [["native hull", 0], ["native hull multiccd", 0],
                                         ["decomposed-16", 0]], f"the part's rows {merged}")
# That file merged again into a later race: a row it had merged keeps its origin (the race that
# ran it, not the file's own scene), the others are the file's scene's.
later = {"rows": [row("native hull", 0, "held")], "decompositions": {}}
file_entry = dict(new, provenance={"graspcd": {"version": "0.5.0", "commit": "def"},
                                   "date": "now"})
run_race.merge_rows(later, file_entry, {"machine": {}}, "joined.json")
origins = {(p["file"], p["provenance"]["date"]): p["rows"] for p in later.get("merged_rows", [])}
check(origins == {("joined.json", "now"): [["graspcd", 0]],
                  ("baselines.json", "then"): [["native hull multiccd", 0],
                                                ["decomposed-16", 0]]},
      f"origins kept through a second merge: {origins}")
# A part written before parts named their rows is matched by configuration.
legacy = dict(file_entry, merged_rows=[{"file": "old.json", "configurations": ["decomposed-16"],
                                        "provenance": {"date": "long ago"}}])
again_later = {"rows": [row("graspcd", 0, "held")], "decompositions": {}}
run_race.merge_rows(again_later, legacy, {"machine": {}}, "joined.json")
origins = {p["provenance"]["date"]: p["configurations"] for p in again_later["merged_rows"]}
check(origins == {"long ago": ["decomposed-16"],
                  "now": ["native hull", "native hull multiccd"]}, f"a legacy part: {origins}")
# Nothing left to take: no note.
again = {"rows": list(new["rows"]), "decompositions": {}}
run_race.merge_rows(again, old_entry, old, "baselines.json")
check("merged_rows" not in again and len(again["rows"]) == 4, "nothing merged twice")

# 3.14's rows raced apart and merged: the scene keeps the merged file's note of them.
ours = {"rows": [row("graspcd", 0, "held")], "decompositions": {},
        "mujoco3": "not selected (--configurations)"}
theirs = {"rows": [row("3.14 flex", 0, "held")], "decompositions": {},
          "mujoco3": {"not_run": [{"configuration": "3.14 sdf", "noslip": 10}], "why": "kept"}}
run_race.merge_rows(ours, theirs, {"machine": {}}, "mujoco3.json")
check([run_race.row_key(r) for r in ours["rows"]] == [("graspcd", 0), ("3.14 flex", 0)]
      and ours["mujoco3"] == theirs["mujoco3"], f"3.14's rows merged with their note: {ours}")

# MuJoCo 3.14's configurations: raced by default, selected by a pattern, never by graspcd's.
for name in ("3.14 hull", "3.14 sdf", "3.14 sdf10", "3.14 flex"):
    check(run_race.selected(name, None), f"{name} raced by default")
    check(run_race.selected(name, ["3.14*"]), f"{name} by 3.14*")
    check(not run_race.selected(name, ["graspcd*", "native hull*"]), f"{name} not graspcd's")
check(run_race.record_name("3.14 sdf10", 10) == "3.14_sdf10_noslip10.jsonl", "a record's name")
check(run_race.record_name("decomposed-16 multiccd", 0)
      == "decomposed-16_multiccd_noslip0.jsonl", "a record's name, with multiccd")

# race.json without this machine's paths: a checkout's file from the checkout on, any other
# absolute path its name alone; speeds and relative paths untouched.
strip = run_race.without_machine_paths
check(strip("/work/main/mjcf/concave_robotiq_bowl_rim.xml: with /work/race-work/bowl_16:"
            " cannot start") == "mjcf/concave_robotiq_bowl_rim.xml: with bowl_16: cannot start",
      "a message's paths")
check(strip(run_race.ROOT + "/study/run_race.py") == "study/run_race.py", "this checkout's file")
check(strip(["/opt/x/graspcd", "--merge", "/tmp/a/b.json"]) == ["graspcd", "--merge", "b.json"],
      "a command's paths")
check(strip({"m": "2.5 m/s over 1/60 s", "mesh": "../shared/models/objects/mug.obj"})
      == {"m": "2.5 m/s over 1/60 s", "mesh": "../shared/models/objects/mug.obj"},
      "no path, or a relative one, untouched")
check(strip({"n": 3, "x": None}) == {"n": 3, "x": None}, "numbers untouched")

for f in failures:
    print(f"race_configurations_test: FAILED: {f}", file=sys.stderr)
sys.exit(1 if failures else 0)
