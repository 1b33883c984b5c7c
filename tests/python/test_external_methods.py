"""A method outside the harness in a grid (docs/sweeps.md §External methods): the sweep runs its
command with the job, resumes, reruns it when its script changes, reports it like any other
algorithm, and says why an attempt failed. Run by CTest with PYTHONPATH=<build folder> and
RAPID_BIN=<the rapid binary>."""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rapid_harness as rh

HERE = os.path.dirname(os.path.abspath(__file__))
RAPID = os.environ.get("RAPID_BIN", os.path.join(os.environ.get("PYTHONPATH", "build"), "rapid"))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def grid(external, algos, **extra):
    g = {"name": "external-test", "scenarios": ["pendulum"], "datasets": ["initial"], "algos": algos, "seeds": [0, 1],
         "config": {"steps": 400, "warmup_steps": 0, "eval_every": 200, "eval_episodes": 1, "last_k": 1, "batch_size": 32},
         "reference": {"seed": 1000, "transitions": 600}, "max_retries": 0, "external": external}
    g.update(extra)
    return g


class ExternalMethodInAGrid(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        shutil.copy(os.path.join(HERE, "fixtures", "constant_method.py"), self.dir)
        self.script = os.path.join(self.dir, "constant_method.py")

    def tearDown(self):
        shutil.rmtree(self.dir)

    def write_grid(self, document, name="grid.json"):
        path = os.path.join(self.dir, name)
        with open(path, "w") as f:
            json.dump(document, f)
        return path

    def rapid(self, *args):
        return subprocess.run([RAPID, *args], capture_output=True, text=True, cwd=self.dir)

    def constant(self, **keys):
        return {"constant": {"command": [sys.executable, "constant_method.py"], "keys": keys}}

    def test_runs_resumes_reports_and_reruns_when_the_script_changes(self):
        path = self.write_grid(grid(self.constant(action=0.5), ["ddpg", "constant"]))
        out = os.path.join(self.dir, "out")
        run = self.rapid("sweep", path, "--out", out, "--jobs", "2")
        self.assertEqual(run.returncode, 0, run.stderr + run.stdout)
        cell = os.path.join(out, "jobs", "pendulum", "initial", "constant", "seed0")
        job = rh.load_job(os.path.join(cell, "job.json"))
        record = read_json(os.path.join(cell, "record.json"))
        # The job the command got is the cell's: its dataset file, the resolved config, its folder.
        self.assertEqual((job["scenario"], job["algo"], job["seed"], job["dataset"]), ("pendulum", "constant", 0, "initial"))
        self.assertTrue(job["dataset_path"].endswith("datasets/pendulum/initial.h5") and os.path.isabs(job["dataset_path"]))
        self.assertEqual(job["config"], rh.config("pendulum", "short", grid({}, [])["config"]))
        self.assertEqual(job["command"], [sys.executable, self.script])
        self.assertEqual((record["status"], record["config_hash"]), ("ok", job["config_hash"]))
        self.assertEqual(record["method_config"], {"action": 0.5})
        self.assertEqual(record["provenance"]["script"]["path"], self.script)
        # Reported as a column of its own, with a colour.
        with open(os.path.join(out, "table.md")) as f:
            table = f.read()
        self.assertIn("| DDPG | constant |", table)
        summary = read_json(os.path.join(out, "summary.json"))
        row = [a for a in summary["algorithms"] if a["name"] == "constant"]
        self.assertEqual(len(row), 1)
        self.assertTrue(row[0]["uses_prior"] and row[0]["colour"])
        with open(os.path.join(out, "report.html")) as f:
            self.assertIn('<th scope="col">constant</th>', f.read())
        # Resumes: nothing to run again.
        again = self.rapid("sweep", path, "--out", out, "--no-summary")
        self.assertIn("0 jobs run", again.stdout + again.stderr)
        # An edited script makes its runs stale (and only its), and they run again.
        with open(self.script, "a") as f:
            f.write("# edited\n")
        status = self.rapid("status", out)
        self.assertRegex(status.stdout, r"stale\s+2")
        rerun = self.rapid("sweep", path, "--out", out, "--no-summary")
        self.assertEqual(rerun.returncode, 0, rerun.stderr)
        self.assertIn("2 jobs run", rerun.stdout + rerun.stderr)

    def test_the_command_finds_the_module_without_pythonpath(self):
        # Issue #67: the command runs in its job's folder, so it failed with ModuleNotFoundError
        # unless the user set an absolute PYTHONPATH. The runner puts the module's folder (its
        # own build folder) first on the command's PYTHONPATH, keeping what the user had after it.
        path = self.write_grid(grid(self.constant(), ["constant"], seeds=[0]))
        out = os.path.join(self.dir, "out")
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        run = subprocess.run([RAPID, "sweep", path, "--out", out, "--no-summary"], capture_output=True, text=True,
                             cwd=self.dir, env=env)
        self.assertEqual(run.returncode, 0, run.stderr + run.stdout)
        env["PYTHONPATH"] = "relative/elsewhere"
        run = subprocess.run([RAPID, "sweep", path, "--out", os.path.join(self.dir, "again"), "--no-summary"],
                             capture_output=True, text=True, cwd=self.dir, env=env)
        self.assertEqual(run.returncode, 0, run.stderr + run.stdout)

    def test_a_failing_command_is_a_failed_attempt_with_its_last_stderr_line(self):
        path = self.write_grid(grid(self.constant(fail=True), ["constant"], seeds=[0]))
        out = os.path.join(self.dir, "out")
        run = self.rapid("sweep", path, "--out", out, "--no-summary")
        self.assertEqual(run.returncode, 1)
        status = self.rapid("status", out).stdout
        self.assertIn("constant's command exited with code 3: constant_method: told to fail", status)

    def test_a_valid_record_from_a_failed_attempt_is_not_ok(self):
        # Issue #67: the sweep said failed, but status, summarize and the next sweep took the run as
        # ok and never ran it again. A run is ok only when its attempt is.
        path = self.write_grid(grid(self.constant(fail_after_record=True), ["constant"], seeds=[0]))
        out = os.path.join(self.dir, "out")
        self.assertEqual(self.rapid("sweep", path, "--out", out, "--no-summary").returncode, 1)
        status = self.rapid("status", out).stdout
        self.assertRegex(status, r"failed\s+1")
        self.assertIn("failed after writing its record", status)
        self.rapid("summarize", out, "--no-plots")
        self.assertEqual(read_json(os.path.join(out, "summary.json"))["status_counts"].get("ok", 0), 0)
        again = self.rapid("sweep", path, "--out", out, "--no-summary")
        self.assertEqual(again.returncode, 1)
        self.assertIn("1 jobs run", again.stdout + again.stderr)

    def test_a_huge_stderr_line_is_shown_cut_short(self):
        # Issue #67: a 20 MB line on the method's stderr was copied whole into outcome.json, the
        # sweep's output and every `rapid status`. Its log keeps it; the one-line reports do not.
        path = self.write_grid(grid(self.constant(shout=5_000_000), ["constant"], seeds=[0]))
        out = os.path.join(self.dir, "out")
        run = self.rapid("sweep", path, "--out", out, "--no-summary")
        self.assertEqual(run.returncode, 1)
        self.assertLess(len(run.stdout), 5000, run.stdout[:300])
        outcome = read_json(os.path.join(out, "jobs", "pendulum", "initial", "constant", "seed0", "outcome.json"))
        self.assertLess(len(outcome["error"]), 1000)
        self.assertRegex(outcome["error"], r"exited with code 3: x+ … \(\d+ bytes more\)")
        status = self.rapid("status", out)
        self.assertLess(len(status.stdout), 5000, status.stdout[:300])
        self.assertIn("bytes more)", status.stdout)

    def test_a_command_that_writes_no_record_fails(self):
        path = self.write_grid(grid(self.constant(no_record=True), ["constant"], seeds=[0]))
        out = os.path.join(self.dir, "out")
        self.assertEqual(self.rapid("sweep", path, "--out", out, "--no-summary").returncode, 1)
        self.assertIn("wrote no record.json", self.rapid("status", out).stdout)

    def test_a_record_from_an_edited_script_is_refused_before_it_is_written(self):
        path = self.write_grid(grid(self.constant(), ["constant"], seeds=[0]))
        out = os.path.join(self.dir, "out")
        self.assertEqual(self.rapid("sweep", path, "--out", out, "--no-summary").returncode, 0)
        job = os.path.join(out, "jobs", "pendulum", "initial", "constant", "seed0", "job.json")
        with open(self.script, "a") as f:
            f.write("# edited\n")
        with self.assertRaisesRegex(ValueError, "config_hash"):
            rh.RunRecord.from_job(job)

    def test_the_method_keys_it_reads_are_the_grids_to_set(self):
        external = self.constant()
        external["constant"]["reads"] = ["epsilon"]
        path = self.write_grid(grid(external, ["constant"], seeds=[0], algo_config={"pendulum": {"constant": {"epsilon": 0.3}}}))
        out = os.path.join(self.dir, "out")
        self.assertEqual(self.rapid("sweep", path, "--out", out, "--no-summary").returncode, 0)
        job = rh.load_job(os.path.join(out, "jobs", "pendulum", "initial", "constant", "seed0", "job.json"))
        self.assertEqual(job["config"]["epsilon"], 0.3)
        # Without "reads", ε is another algorithm's key: the grid may not set it for this method.
        path = self.write_grid(grid(self.constant(), ["constant"], algo_config={"pendulum": {"constant": {"epsilon": 0.3}}}))
        run = self.rapid("sweep", path, "--out", os.path.join(self.dir, "never"))
        self.assertEqual(run.returncode, 2)
        self.assertIn("'constant' does not read 'epsilon'", run.stderr)

    def test_a_file_that_is_no_job_is_refused(self):
        not_a_job = self.write_grid({"schema": "rapid.run/1"}, "record.json")
        for read in (rh.load_job, rh.RunRecord.from_job):
            with self.assertRaisesRegex(ValueError, "not a job file"):
                read(not_a_job)
        truncated = self.write_grid({"schema": "rapid.job/1", "scenario": "pendulum"}, "job.json")
        with self.assertRaisesRegex(ValueError, "job .*job.json: .*algo"):
            rh.RunRecord.from_job(truncated)

    def test_wrong_external_entries_are_one_line_and_exit_2(self):
        cases = [
            ({"ddpg": {"command": [sys.executable, "constant_method.py"]}}, ["ddpg"], "external.ddpg: 'ddpg' is the harness's own"),
            ({"constant": {"command": []}}, ["constant"], "external.constant.command: expected a non-empty array"),
            ({"constant": {"command": ["python3", "missing.py"]}}, ["constant"], "external.constant.command: names no script"),
            ({"constant": {"command": [sys.executable, "constant_method.py"], "keys": [1]}}, ["constant"],
             "external.constant.keys: expected an object"),
            ({"constant": {"command": [sys.executable, "constant_method.py"], "prior": True}}, ["constant"],
             "external.constant.prior: unknown key"),
            (self.constant(), ["ddpg"], "external.constant: 'constant' is not one of the grid's algos"),
            ({"constant": {"command": [sys.executable, "constant_method.py"], "reads": ["steps"]}}, ["constant"],
             "external.constant.reads: \"steps\" is not a method key"),
            ({}, ["constant"], "algos[0]: unknown algorithm 'constant'"),
        ]
        for external, algos, message in cases:
            with self.subTest(message=message):
                path = self.write_grid(grid(external, algos))
                out = os.path.join(self.dir, "never")
                run = self.rapid("sweep", path, "--out", out)
                self.assertEqual(run.returncode, 2, run.stderr)
                self.assertIn(message, run.stderr)
                self.assertEqual(len(run.stderr.strip().splitlines()), 1, run.stderr)
                self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
