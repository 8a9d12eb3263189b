#!/usr/bin/env python3
"""study/run_objset.py and study/objset_rates.py without a grasp: the refusal of a bad object or
list entry (one line, exit code 2), the seeded plan, the shard split and --merge's refusals, and
the reference's rule and rates on made-up placements.

Usage: objset_rules_test.py GRASPCD MODELS_DIR
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

STUDY = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(
    __file__)))), "study")
sys.path.insert(0, STUDY)
import objset_rates  # noqa: E402
import run_objset  # noqa: E402

GRASPCD, MODELS = (os.path.abspath(a) for a in sys.argv[1:3])
RUNNER = os.path.join(STUDY, "run_objset.py")


def runner(*args):
    return subprocess.run(["/usr/bin/python3", RUNNER, *args], capture_output=True, text=True,
                          timeout=120)


class Refusals(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)
        self.good = os.path.join(self.dir.name, "block.obj")
        with open(self.good, "w") as f:
            f.write("v 0 0 0\nv 0.03 0 0\nv 0 0.03 0\nv 0 0 0.03\n"
                    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")

    def list_file(self, text):
        path = os.path.join(self.dir.name, "objects.txt")
        with open(path, "w") as f:
            f.write(text)
        return path

    def assert_one_line(self, r, *parts):
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        for p in parts:
            self.assertIn(p, r.stderr)
        self.assertEqual(r.stdout, "")

    def test_a_bad_list_entry_is_one_line_naming_the_list_and_line(self):
        listed = self.list_file("# a comment\nblock.obj up=z\nblock.obj colour=red name=b\n")
        self.assert_one_line(runner(GRASPCD, "--list", listed), f"{listed}:3: 'colour=red'")
        listed = self.list_file("block.obj up=w\n")
        self.assert_one_line(runner(GRASPCD, "--list", listed), f"{listed}:1: up=w")
        listed = self.list_file("block.obj scale=abc\n")
        self.assert_one_line(runner(GRASPCD, "--list", listed), f"{listed}:1: scale=abc")
        listed = self.list_file("block.obj\nmissing.obj\n")
        self.assert_one_line(runner(GRASPCD, "--list", listed), f"{listed}:2: ",
                             "missing.obj: no such file")
        listed = self.list_file("block.obj\nblock.obj scale=2\n")
        self.assert_one_line(runner(GRASPCD, "--list", listed), "'block' given twice")

    def test_an_object_graspcd_refuses_is_its_one_line(self):
        bad = os.path.join(self.dir.name, "bad.obj")
        with open(bad, "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
        listed = self.list_file("block.obj\nbad.obj\n")
        r = runner(GRASPCD, "--list", listed, "--out", os.path.join(self.dir.name, "o.json"))
        self.assert_one_line(r, f"{bad}:4:", "vertex index 7")
        self.assertFalse(os.path.exists(os.path.join(self.dir.name, "o.json")))

    def test_bad_options_are_one_line(self):
        listed = self.list_file("block.obj\n")
        self.assert_one_line(runner(GRASPCD, "--list", listed, "--shard", "2/2"), "--shard '2/2'")
        self.assert_one_line(runner(GRASPCD, "--list", listed, "--hands", "claw"), "'claw'")
        self.assert_one_line(runner(GRASPCD, "--list", listed, "--configurations", "sdf*"),
                             "selects none")
        self.assert_one_line(runner(GRASPCD, "--objects", self.dir.name + "/none"),
                             "no such folder")


def shard_doc(plan, i, n, runs=None):
    mine = run_objset.shard_of(plan["placements"], (i, n))
    return {"plan": plan, "shard": [i, n], "workers": 1, "machine": {}, "wall_s": 1.0,
            "complete": True, "planned": len(mine),
            "cpu_s": 2.0, "configurations": ["reference", "graspcd"],
            "placements": [dict(p, runs=runs or {}) for p in mine]}


class PlanAndShards(unittest.TestCase):
    objects = [{"name": "a", "up": "y"}, {"name": "b", "up": "-z"}]

    def plan(self, seed=7):
        return run_objset.make_plan(self.objects, ["robotiq", "shadow"], 3, seed, ["graspcd"])

    def test_the_plan_is_its_seed(self):
        a, b, c = self.plan(), self.plan(), self.plan(seed=8)
        self.assertEqual(a, b)
        self.assertNotEqual(a["placements"], c["placements"])
        self.assertNotEqual(a["id"], c["id"])
        self.assertEqual(len(a["placements"]), 2 * 2 * 3)
        for p in a["placements"]:
            axis = next(o["up"] for o in self.objects if o["name"] == p["object"])
            self.assertIn(p["up"], (axis, run_objset.opposite(axis)))
            self.assertTrue(0 <= p["yaw"] < 360)
            self.assertTrue(all(abs(x) <= run_objset.OFFSET_M for x in p["offset"]))
        self.assertGreater(len({p["yaw"] for p in a["placements"]}), 10, "drawn, not repeated")

    def test_shards_split_the_plan_whole(self):
        plan = self.plan()
        for n in (1, 2, 5, 20):
            parts = [run_objset.shard_of(plan["placements"], (i, n)) for i in range(n)]
            indices = sorted(p["index"] for part in parts for p in part)
            self.assertEqual(indices, list(range(len(plan["placements"]))), n)

    def test_merge_joins_a_whole_split_and_refuses_any_other(self):
        plan = self.plan()
        with tempfile.TemporaryDirectory() as d:
            files = []
            for i in range(3):
                files.append(os.path.join(d, f"objset.shard-{i}-of-3.json"))
                with open(files[-1], "w") as f:
                    json.dump(shard_doc(plan, i, 3), f)
            merged = run_objset.merge(files)
            self.assertEqual([p["index"] for p in merged["placements"]],
                             list(range(len(plan["placements"]))))
            self.assertEqual(merged["merged_from"], 3)
            self.assertEqual(merged["cpu_s"], 6.0)
            out = os.path.join(d, "merged.json")
            r = runner("--merge", *files, "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as f:
                self.assertEqual(json.load(f)["placements"], merged["placements"])
            # One missing, one given twice, one of another plan: one line each, nothing written.
            cases = [(files[:1] + files[2:], "shard 1 of 3 (objset.shard-1-of-3.json) is missing"),
                     (files + files[:1], "shard 0 of 3 given twice")]
            other = os.path.join(d, "other.json")
            with open(other, "w") as f:
                json.dump(shard_doc(self.plan(seed=9), 1, 3), f)
            cases.append(([files[0], other, files[2]], "a shard of another plan"))
            partial = os.path.join(d, "partial.json")
            with open(partial, "w") as f:
                json.dump(dict(shard_doc(plan, 1, 3), complete=False), f)
            cases.append(([files[0], partial, files[2]], "shard 1 of 3 is not complete"))
            for given, message in cases:
                bad = os.path.join(d, "bad.json")
                r = runner("--merge", *given, "--out", bad)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
                self.assertIn(message, r.stderr)
                self.assertFalse(os.path.exists(bad))


def run(held, pen=0.001, partial=False, phantom=0, missed=0, steps=10, cpu=2.0):
    return {"outcome": "held" if held else "dropped", "held": held, "hand_penetration": pen,
            "partial": partial, "phantom": phantom, "missed": missed, "closing_steps": steps,
            "cpu_s": cpu, "wall_s": cpu, "ms_per_physics_step": 0.1}


def placement(obj, runs, hand="robotiq", skipped=False):
    return {"object": obj, "hand": hand, "runs": runs, "skipped": skipped}


class ReferenceRule(unittest.TestCase):
    def test_the_reference_is_exact_at_a_quarter_step_and_checked_at_a_half(self):
        self.assertEqual(objset_rates.reference_options(),
                         ["--exact", "--timestep-divisor", "4"])
        self.assertEqual(objset_rates.reference_options(objset_rates.REFERENCE_HALF_DIVISOR),
                         ["--exact", "--timestep-divisor", "2"])

    def test_disagreement_both_ways_and_what_is_not_compared(self):
        refused = {"outcome": "cannot start", "held": False}
        self.assertEqual(objset_rates.disagreement(run(True), run(False)), "held_ref_drops")
        self.assertEqual(objset_rates.disagreement(run(False), run(True)), "dropped_ref_holds")
        self.assertEqual(objset_rates.disagreement(run(True), run(True)), "")
        self.assertIsNone(objset_rates.disagreement(refused, run(True)))
        self.assertIsNone(objset_rates.disagreement(run(True), None))

    def test_rates_over_the_set_and_per_object(self):
        R, H = objset_rates.REFERENCE, objset_rates.REFERENCE_HALF
        doc = {"configurations": [R, H, "graspcd"], "placements": [
            placement("a", {R: run(True), H: run(True), "graspcd": run(True, pen=0.002)}),
            placement("a", {R: run(True), H: run(False), "graspcd": run(False, pen=0.004,
                                                                       phantom=3, steps=5)}),
            placement("b", {R: run(False, partial=True), H: run(False),
                            "graspcd": run(True, pen=0.010, partial=True, missed=1)}),
            placement("b", {R: run(False), H: run(False),
                            "graspcd": {"outcome": "cannot start", "held": False}}),
            placement("b", {}, hand="shadow", skipped=True)]}
        r = objset_rates.rates(doc)
        self.assertEqual((r["placements"], r["skipped"]), (5, 1))
        self.assertEqual(r["fits"], {"robotiq": {"objects": 2, "fit": 2},
                                     "shadow": {"objects": 1, "fit": 0}})
        self.assertEqual(r["convergence"], {"compared": 4, "changed": 1, "share": 0.25})
        g = r["configurations"]["graspcd"]
        self.assertEqual((g["placements"], g["cannot_start"], g["starts"]), (4, 1, 0.75))
        self.assertAlmostEqual(g["held"], 2 / 3)
        self.assertAlmostEqual(g["disagree"], 2 / 3)
        self.assertAlmostEqual(g["held_ref_drops"], 1 / 3)
        self.assertAlmostEqual(g["dropped_ref_holds"], 1 / 3)
        self.assertEqual(g["penetration"]["median"], 0.004)
        self.assertEqual(g["penetration"]["max"], 0.010)
        self.assertEqual(g["penetration_closed"]["max"], 0.004, "the partial run left out")
        self.assertEqual(g["partial_runs"], 1)
        self.assertAlmostEqual(g["phantom_per_step"], 3 / 25)
        self.assertAlmostEqual(g["missed_per_step"], 1 / 25)
        self.assertTrue(r["objects"]["b"]["partial"])
        self.assertFalse(r["objects"]["a"]["partial"])
        self.assertEqual(r["objects"]["a"]["configurations"]["graspcd"]["disagree"], 0.5)
        self.assertEqual(r["configurations"][R]["disagree"], 0.0, "the reference agrees")

    def test_a_run_gone_non_finite_started_and_was_not_held(self):
        R = objset_rates.REFERENCE
        message = ("graspcd: error: s.xml: the simulation went non-finite in the lift (physics"
                   " step 899): MuJoCo found a bad number (NaN or beyond 1e10) in qacc")
        doc = {"configurations": [R, "graspcd"], "placements": [
            placement("a", {R: run(True), "graspcd": {"outcome": "non-finite", "held": False,
                                                      "message": message, "cpu_s": 1.0}}),
            # As a run recorded before the outcome had its name.
            placement("a", {R: run(True), "graspcd": {"outcome": "cannot start", "held": False,
                                                      "message": message, "cpu_s": 1.0}}),
            placement("a", {R: run(True), "graspcd": {"outcome": "cannot start", "held": False,
                                                      "message": "cannot start with --native"}}),
            placement("a", {R: run(True), "graspcd": run(True)})]}
        g = objset_rates.rates(doc)["configurations"]["graspcd"]
        self.assertEqual((g["placements"], g["cannot_start"], g["non_finite"]), (4, 1, 2))
        self.assertAlmostEqual(g["held"], 1 / 3)
        self.assertAlmostEqual(g["dropped_ref_holds"], 2 / 3)
        self.assertEqual(g["penetration"]["n"], 1, "no penetration of a run that stopped")

    def test_held_in_six_directions_needs_the_lift_held_and_all_six(self):
        R = objset_rates.REFERENCE
        runs = [dict(run(True), six_directions=6), dict(run(True), six_directions=5),
                dict(run(False), six_directions=6), run(True)]
        doc = {"configurations": [R, "graspcd"],
               "placements": [placement("a", {R: run(True), "graspcd": x}) for x in runs]}
        g = objset_rates.rates(doc)["configurations"]["graspcd"]
        self.assertAlmostEqual(g["six"], 1 / 4, "of the 4 started runs, one held in six")
        self.assertIsNone(objset_rates.rates(dict(doc, placements=doc["placements"][3:]))[
            "configurations"]["graspcd"]["six"], "no run had the test")

    def test_percentile(self):
        self.assertEqual(objset_rates.percentile([1, 2, 3, 4, 5], 50), 3)
        self.assertAlmostEqual(objset_rates.percentile([0, 10], 99), 9.9)
        self.assertIsNone(objset_rates.percentile([], 50))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
