#!/usr/bin/env python3
"""The study's sweep and an object set through a real Slurm cluster.

Usage: slurm_test.py GRASPCD SOURCE_DIR WORK_DIR MODELS_DIR

One cluster (slurm_cluster.py: munged, slurmctld and slurmd of this machine, private to the run)
serves every test of this file:
  - the sweep: cluster/sweep.sbatch as a 2-task array (the quick sweep, one repeat), then its
    merge job with --dependency=afterok; the merged sweep.json must equal an unsharded run's in
    every point's errors and counters (timings removed); `study --merge` with a shard missing
    names it;
  - a failed array: its afterok merge never runs and is cancelled (kill_invalid_depend);
  - an object set: cluster/validate_objects.sbatch on three small objects of MODELS_DIR and
    a malformed OBJ (SAT, --fit, the project's hand) as a 2-task array and its merge; the shard
    with the refused object still completes, the merge exits 2 as the unsharded run does, and the
    merged rows equal the unsharded `validate --objects` run's (skipped with a message when
    MODELS_DIR is absent).
  - the object-set study: cluster/objset.sbatch on one small object of MODELS_DIR, two
    placements with the Robotiq in graspcd's configuration, as a 2-task array and its merge; the
    merged placements and verdicts equal an unsharded run's (skipped when MODELS_DIR is absent).
The cluster failing to start fails the test with the daemon's log; it never skips.
"""

import json
import os
import shutil
import subprocess
import sys
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import slurm_cluster  # noqa: E402

GRASPCD, SOURCE, WORK, MODELS = (os.path.abspath(a) for a in sys.argv[1:5])
BUILD = os.path.dirname(GRASPCD)
JOB_DEADLINE_S = 300
# Small objects of ../shared/models/objects (1-2 s each with SAT on this machine).
SMALL_OBJECTS = ("mujoco/cube_cup.obj", "prl_assets/plastic_glass_visual.obj",
                 "prl_assets/plastic_bowl_visual.obj")
# A malformed OBJ beside them (a face index out of range): a refused row, exit code 2.
BAD_OBJECT = "bad/face_out_of_range.obj"


def graspcd(*args):
    return subprocess.run([GRASPCD, *args], capture_output=True, text=True, timeout=600)


def without_timings(value):
    """The document with every timing (keys ending in _ms) removed, recursively."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if not k.endswith("_ms")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def load(path):
    with open(path) as f:
        return json.load(f)


class SlurmTest(unittest.TestCase):
    cluster = None

    @classmethod
    def setUpClass(cls):
        missing = slurm_cluster.missing_programs()
        if missing:
            raise RuntimeError("Slurm is not installed (./run installs slurmctld, slurmd, "
                               "slurm-client and munge): missing " + ", ".join(missing))
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)
        start = time.monotonic()
        cls.cluster = slurm_cluster.SlurmCluster().start()
        print(f"[slurm] cluster up in {time.monotonic() - start:.1f} s "
              f"(SLURM_CONF={cls.cluster.conf})", flush=True)

    @classmethod
    def tearDownClass(cls):
        if cls.cluster is not None:
            cls.cluster.stop()

    def submit(self, script, env, extra=()):
        return self.cluster.sbatch([f"--chdir={SOURCE}", f"--output={WORK}/%x-%A_%a.out",
                                    *extra, script], env=dict(env, BUILD_DIR=BUILD))

    def array_and_merge(self, script, env):
        """SCRIPT (under SOURCE) as a 2-task array, then as its merge job (MERGE=1, SHARDS=2) with
        --dependency=afterok on it, as a user submits them; waits for both. Returns the merge's
        job id and every task's (state, exit code)."""
        script = os.path.join(SOURCE, script)
        array = self.submit(script, env, ["--array=0-1"])
        merge = self.submit(script, dict(env, MERGE="1", SHARDS="2"),
                            [f"--dependency=afterok:{array}"])
        return merge, self.cluster.wait([array, merge], JOB_DEADLINE_S)

    def job_outputs(self):
        text = ""
        for name in sorted(os.listdir(WORK)):
            if name.endswith(".out"):
                text += f"--- {name}:\n" + slurm_cluster.tail(os.path.join(WORK, name), 15)
        return text

    def assert_completed(self, states):
        for task, (state, code) in states.items():
            self.assertEqual((state, code), ("COMPLETED", "0:0"),
                             f"job {task}: {state} {code}\n{self.job_outputs()}")

    def test_sweep_through_slurm_equals_one_unsharded_run(self):
        whole = os.path.join(WORK, "sweep-whole")
        parts = os.path.join(WORK, "sweep-parts")
        r = graspcd("study", "--quick", "--no-table", "--repeats", "1", "--out", whole)
        self.assertEqual(r.returncode, 0, r.stderr)
        env = {"OUT": parts, "SWEEP_ARGS": "--quick --repeats 1"}
        merge, states = self.array_and_merge("cluster/sweep.sbatch", env)
        self.assertEqual(len(states), 3, states)  # two array tasks and the merge
        self.assert_completed(states)
        a = load(os.path.join(whole, "sweep.json"))
        b = load(os.path.join(parts, "sweep.json"))
        self.assertEqual(b["merged_from"], 2)
        self.assertEqual(a["recordings"], b["recordings"], "the same recorded poses")
        self.assertEqual(a["config_names"], b["config_names"])
        self.assertGreaterEqual(len(a["configs"]), 6)
        for x, y in zip(without_timings(a["configs"]), without_timings(b["configs"])):
            self.assertEqual(x, y, x["name"])
        # Directly, a merge with a shard missing refuses and names it.
        r = graspcd("study", "--merge", os.path.join(parts, "sweep.shard-1-of-2.json"), "--out",
                    os.path.join(WORK, "sweep-bad"))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("shard 0 of 2 (sweep.shard-0-of-2.json) is missing", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertFalse(os.path.exists(os.path.join(WORK, "sweep-bad", "sweep.json")))

    def test_a_failed_shard_cancels_the_merge(self):
        out = os.path.join(WORK, "sweep-failed")
        env = {"OUT": out, "SWEEP_ARGS": "--no-such-option"}
        merge, states = self.array_and_merge("cluster/sweep.sbatch", env)
        for task, (state, _) in states.items():
            expected = "CANCELLED" if task == merge else "FAILED"
            self.assertEqual(state, expected, f"{task}: {states}\n{self.job_outputs()}")
        self.assertFalse(os.path.exists(os.path.join(out, "sweep.json")))

    def test_object_set_through_slurm_equals_one_unsharded_run(self):
        objects_root = os.path.join(MODELS, "objects")
        if not os.path.isdir(objects_root):
            self.skipTest(f"{objects_root} is absent: the real objects are not here")
        objects = os.path.join(WORK, "objects")
        for rel in SMALL_OBJECTS:
            os.makedirs(os.path.dirname(os.path.join(objects, rel)), exist_ok=True)
            shutil.copyfile(os.path.join(objects_root, rel), os.path.join(objects, rel))
        os.makedirs(os.path.join(objects, os.path.dirname(BAD_OBJECT)))
        with open(os.path.join(objects, BAD_OBJECT), "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
        args = ["--fit", "--method", "sat"]
        whole = os.path.join(WORK, "objects-whole")
        r = graspcd("validate", "--objects", objects, *args, "--out", whole)
        self.assertEqual(r.returncode, 2, "one object refused\n" + r.stderr)
        self.assertIn(f"warning: {objects}/{BAD_OBJECT}:4: face 1: vertex index 7", r.stderr)
        parts = os.path.join(WORK, "objects-parts")
        env = {"OUT": parts, "OBJECTS": objects, "VALIDATE_ARGS": " ".join(args)}
        merge, states = self.array_and_merge("cluster/validate_objects.sbatch", env)
        self.assertEqual(len(states), 3, states)
        # The shards complete (a refused object is a row of the shard's file); the merge, which
        # writes the whole table, exits 2 as the unsharded run does.
        self.assertEqual(states.pop(merge), ("FAILED", "2:0"), self.job_outputs())
        self.assert_completed(states)
        a = load(os.path.join(whole, "objects.json"))
        b = load(os.path.join(parts, "objects.json"))
        self.assertEqual(b["merged_from"], 2)
        self.assertEqual(a["objects"], sorted((*SMALL_OBJECTS, BAD_OBJECT)))
        self.assertEqual(a["objects"], b["objects"])
        self.assertEqual(a["rows"], b["rows"])
        self.assertEqual(a["refused"], 1)
        bad = a["rows"][a["objects"].index(BAD_OBJECT)]
        self.assertEqual(bad["status"], "refused", bad)
        for row in a["rows"]:
            if row["object"] == BAD_OBJECT:
                continue
            self.assertEqual(row["status"], "checked", row)
            self.assertEqual([m["method"] for m in row["methods"]], ["sat"])
            self.assertEqual(row["methods"][0]["missed"], 0, row)
            # Every pair at every state checked: the closing's grasp steps and the squeeze's.
            self.assertGreater(row["states"], row["steps"], row)
            self.assertEqual(row["methods"][0]["checks"] % row["states"], 0, row)
            self.assertLessEqual(row["steps_with_contact"], row["steps"], row)
            self.assertTrue(row["fitted"], row)
        self.assertGreater(sum(row.get("cgal_hits", 0) for row in a["rows"]), 0,
                           "some object was touched: something was checked")
        # The merged table, printed from the shard files directly.
        shard_files = [os.path.join(parts, f"objects.shard-{i}-of-2.json") for i in range(2)]
        r = graspcd("validate", "--merge", *shard_files)
        self.assertEqual(r.returncode, 2, r.stderr)
        for rel in (*SMALL_OBJECTS, BAD_OBJECT):
            self.assertIn(rel, r.stdout)
        self.assertIn("# result: no missed or false collision; 3 objects checked, 1 refused",
                      r.stdout)
        # A shard missing is named with its objects.
        r = graspcd("validate", "--merge", shard_files[0])
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("shard 1 of 2 (objects.shard-1-of-2.json) is missing", r.stderr)
        self.assertIn(a["objects"][1], r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)

    def test_object_set_study_through_slurm_equals_one_unsharded_run(self):
        cup = os.path.join(MODELS, "objects", "mujoco", "cube_cup.obj")
        if not os.path.isfile(cup):
            self.skipTest(f"{cup} is absent: the real objects are not here")
        listed = os.path.join(WORK, "objset-objects.txt")
        with open(listed, "w") as f:
            f.write(f"{cup} scale=0.5 name=cup\n")
        args = f"--list {listed} --hands robotiq --grasps 2 --seed 5 --configurations graspcd"
        whole = os.path.join(WORK, "objset-whole", "objset.json")
        r = subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "study", "run_objset.py"),
                            GRASPCD, *args.split(), "--workers", "1", "--out", whole],
                           capture_output=True, text=True, timeout=600)
        self.assertEqual(r.returncode, 0, r.stderr)
        parts = os.path.join(WORK, "objset-parts")
        merge, states = self.array_and_merge("cluster/objset.sbatch",
                                             {"OUT": parts, "OBJSET_ARGS": args})
        self.assertEqual(len(states), 3, states)
        self.assert_completed(states)
        a = load(whole)
        b = load(os.path.join(parts, "objset.json"))
        self.assertEqual(b["merged_from"], 2)
        self.assertEqual(a["plan"], b["plan"])

        def verdicts(doc):
            return [(p["index"], bool(p.get("skipped")),
                     {k: (v["outcome"], v.get("held")) for k, v in p.get("runs", {}).items()})
                    for p in doc["placements"]]

        self.assertEqual(verdicts(a), verdicts(b))
        self.assertEqual(len(a["placements"]), 2)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
