#!/usr/bin/env python3
"""The object-set study run for real (study/run_objset.py driving graspcd): two objects, two
seeded placements each, in two configurations (graspcd and MuJoCo's hull) with the Robotiq, as
two shards run with two workers and merged; then one placement run again as a shard of another
split: the same placement, the same verdicts (reproduced from the seed). Also the reference's
rule as it ran: a quarter of the scene's time step and four times the physics steps (half of each
for its convergence run); the six-direction test after every run but the convergence run's; the
placement's offset written into the scene; and one placement in MuJoCo 3.14's hull (node, judged
by graspcd judge), skipped with a message without node or tools/mujoco3's packages.

Usage: objset_study_test.py GRASPCD MODELS_DIR WORK_DIR
Skipped with a message when MODELS_DIR has no Robotiq or objects.
"""

import json
import os
import shutil
import subprocess
import sys
import unittest

STUDY = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(
    __file__)))), "study")
sys.path.insert(0, STUDY)
import objset_rates  # noqa: E402

GRASPCD, MODELS, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
RUNNER = os.path.join(STUDY, "run_objset.py")
# Two small objects of the models folder, scaled into the Robotiq's room.
OBJECTS = ("objects/mujoco/cube_cup.obj scale=0.5 name=cup",
           "objects/prl_assets/plastic_bowl_visual.obj scale=0.35 name=bowl")
ARGS = ("--hands", "robotiq", "--grasps", "2", "--seed", "3", "--configurations",
        "graspcd,native hull", "--workers", "2")


def runner(*args):
    return subprocess.run(["/usr/bin/python3", RUNNER, *args], capture_output=True, text=True,
                          timeout=600)


def verdicts(doc):
    return [(p["index"], p["object"], p["up"], p["yaw"], p["offset"], bool(p.get("skipped")),
             {k: (v["outcome"], v.get("held")) for k, v in p.get("runs", {}).items()})
            for p in doc["placements"]]


class ObjsetStudy(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not os.path.isdir(os.path.join(MODELS, "objects")):
            raise unittest.SkipTest(f"{MODELS}/objects is absent: the real objects are not here")
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)
        cls.list = os.path.join(WORK, "objects.txt")
        with open(cls.list, "w") as f:
            f.write("".join(os.path.join(MODELS, x) + "\n" for x in OBJECTS))
        cls.out = os.path.join(WORK, "objset.json")
        for i in range(2):
            r = runner(GRASPCD, "--list", cls.list, *ARGS, "--shard", f"{i}/2", "--out", cls.out)
            assert r.returncode == 0, r.stderr
        files = [os.path.join(WORK, f"objset.shard-{i}-of-2.json") for i in range(2)]
        r = runner("--merge", *files, "--out", cls.out)
        assert r.returncode == 0, r.stderr
        with open(cls.out) as f:
            cls.doc = json.load(f)

    def test_every_placement_ran_in_both_configurations_against_the_reference(self):
        doc = self.doc
        self.assertEqual(doc["merged_from"], 2)
        self.assertEqual([p["index"] for p in doc["placements"]], [0, 1, 2, 3])
        self.assertEqual(doc["configurations"],
                         ["reference", "reference half", "graspcd", "native hull"])
        started = [p for p in doc["placements"] if not p.get("skipped")]
        self.assertGreater(len(started), 0, "some placement started")
        for p in started:
            self.assertEqual(set(p["runs"]), set(doc["configurations"]), p)
            for name, run in p["runs"].items():
                if run["outcome"] == "cannot start":
                    continue
                self.assertGreater(run["physics_steps"], 0, name)
                self.assertGreater(run["cpu_s"], 0, name)
                self.assertGreater(run["cpu_ms_per_physics_step"], 0, name)
                if name == "reference half":
                    self.assertIsNone(run["six_directions"], "no six directions: held only")
                else:
                    self.assertIn(run["six_directions"], range(7), name)
                self.assertIsNotNone(run["hand_penetration"], name)
                if not name.startswith("reference"):
                    self.assertGreater(run["closing_steps"], 0, f"{name}: judged")
        r = objset_rates.rates(doc)
        self.assertEqual(r["placements"], 4)
        self.assertEqual(r["configurations"]["reference"]["disagree"], 0.0)
        for name in ("graspcd", "native hull"):
            self.assertEqual(r["configurations"][name]["placements"], len(started))

    def test_the_reference_runs_at_a_quarter_step_with_four_times_the_steps(self):
        for p in self.doc["placements"]:
            if p.get("skipped"):
                continue
            runs = p["runs"]
            scene_dt = runs["graspcd"]["timestep"]
            self.assertAlmostEqual(runs["reference"]["timestep"], scene_dt / 4, delta=1e-12)
            self.assertAlmostEqual(runs["reference half"]["timestep"], scene_dt / 2, delta=1e-12)
            # The same drive in time: close to 4 (2) times the physics steps (the closing may end
            # at another grasp step).
            ratio = runs["reference"]["physics_steps"] / runs["graspcd"]["physics_steps"]
            self.assertGreater(ratio, 3.0, p)
            self.assertLess(ratio, 5.0, p)

    def test_the_placement_is_written_into_the_scene(self):
        p = self.doc["placements"][0]
        scene_dir = os.path.join(WORK, "objset", "scenes", f"{p['object']}-robotiq-0")
        scenes = [f for f in os.listdir(scene_dir) if f.endswith(".xml")]
        self.assertEqual(len(scenes), 1, scenes)
        with open(os.path.join(scene_dir, scenes[0])) as f:
            header = f.read(4000)
        self.assertIn(f"file axis {p['up']} up", header)
        self.assertRegex(header, r"centred on it moved -?[0-9.e-]+, -?[0-9.e-]+ m across gravity")

    def test_a_placement_run_again_gives_the_same_placement_and_verdicts(self):
        again = os.path.join(WORK, "again", "objset.json")
        r = runner(GRASPCD, "--list", self.list, *ARGS, "--shard", "3/4", "--out", again)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(WORK, "again", "objset.shard-3-of-4.json")) as f:
            doc = json.load(f)
        self.assertEqual(doc["plan"]["id"], self.doc["plan"]["id"])
        mine = [p for p in self.doc["placements"] if p["index"] == 3]
        self.assertEqual(verdicts(doc), verdicts({"placements": mine}))

    def test_mujoco3s_hull_runs_on_the_written_scene_and_is_judged(self):
        sys.path.insert(0, STUDY)
        import race_judged  # noqa: E402
        why = race_judged.mujoco3_missing()
        if why is not None:
            self.skipTest(f"MuJoCo 3.14's runner cannot run here: {why}")
        out = os.path.join(WORK, "mujoco3", "objset.json")
        r = runner(GRASPCD, "--list", self.list, "--only", "cup", "--hands", "robotiq",
                   "--grasps", "1", "--seed", "3", "--configurations", "3.14 hull",
                   "--workers", "1", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            doc = json.load(f)
        self.assertEqual(doc["configurations"], ["reference", "reference half", "3.14 hull"])
        p = doc["placements"][0]
        # The same placement as the first run's: the plan's placements come from the seed.
        first = next(x for x in self.doc["placements"] if x["object"] == "cup" and x["k"] == 0)
        self.assertEqual((p["up"], p["yaw"], p["offset"]), (first["up"], first["yaw"],
                                                            first["offset"]))
        if p.get("skipped"):
            self.skipTest("the cup's first placement did not start")
        run = p["runs"]["3.14 hull"]
        self.assertIn(run["outcome"], ("held", "held tilted", "dropped", "ejected",
                                       "cannot start"), run)
        self.assertGreater(run["cpu_s"], 0, "the node process's CPU")
        if run["outcome"] != "cannot start":
            self.assertGreater(run["closing_steps"], 0, "judged by graspcd judge")
            self.assertIsNotNone(run["hand_penetration"])
            self.assertGreater(run["wasm_cpu_ms_per_physics_step"], 0)
            self.assertIsNone(run["cpu_ms_per_physics_step"], "never beside a native cost")
            self.assertIn(run["six_directions"], range(7))
        c = objset_rates.rates(doc)["configurations"]["3.14 hull"]
        self.assertEqual(c["placements"], 1)
        self.assertIsNone(c["cpu_ms_per_physics_step"])


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
