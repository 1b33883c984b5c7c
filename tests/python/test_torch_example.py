"""examples/python/ddpg_family_torch.py, a PyTorch DDPG / RAPID-RL / TD3+BC, as a grid's external
methods beside the C++ RAPID-RL (docs/bring-your-own.md): every run ends ok, takes as many actor
updates as the C++ schedule gives, and the same job gives the same record. Needs Debian's
python3-torch: skipped without it, unless RAPID_REQUIRE_TORCH=1 (scripts/test-python-examples, CI)."""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

try:
    import torch  # noqa: F401
    HAVE_TORCH = True
except ImportError:
    HAVE_TORCH = False

import rapid_harness as rh

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "examples", "python", "ddpg_family_torch.py"))
RAPID = os.environ.get("RAPID_BIN", os.path.join(os.environ.get("PYTHONPATH", "build"), "rapid"))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def torch_method(method, **entry):
    return {"command": [sys.executable, EXAMPLE, "--method", method], **entry}


@unittest.skipUnless(HAVE_TORCH or os.environ.get("RAPID_REQUIRE_TORCH") == "1", "python3-torch is not installed")
class TorchExample(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp()
        grid = {"name": "torch-example", "scenarios": ["pendulum"], "datasets": ["initial"], "seeds": [0],
                "algos": ["rapid-rl", "rapid-rl-torch", "td3-bc-torch", "ddpg-torch"],
                "config": {"steps": 600, "warmup_steps": 50, "eval_every": 300, "eval_episodes": 1, "last_k": 1,
                           "batch_size": 32},
                "reference": {"seed": 1000, "transitions": 1000}, "max_retries": 0,
                "external": {"rapid-rl-torch": torch_method("rapid-rl", reads=["epsilon", "bc_q_alpha"]),
                             "td3-bc-torch": torch_method("td3-bc"),
                             "ddpg-torch": torch_method("ddpg", uses_prior=False)}}
        path = os.path.join(cls.dir, "grid.json")
        with open(path, "w") as f:
            json.dump(grid, f)
        cls.out = os.path.join(cls.dir, "out")
        env = dict(os.environ, OMP_NUM_THREADS="1")
        cls.sweep = subprocess.run([RAPID, "sweep", path, "--out", cls.out, "--jobs", "2"], capture_output=True,
                                   text=True, env=env)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir)

    def cell(self, algo, dataset="initial"):
        return os.path.join(self.out, "jobs", "pendulum", dataset, algo, "seed0")

    def test_every_method_runs_and_reports(self):
        self.assertEqual(self.sweep.returncode, 0, self.sweep.stderr[-3000:])
        with open(os.path.join(self.out, "table.md")) as f:
            table = f.read()
        self.assertIn("| RAPID-RL | rapid-rl-torch | td3-bc-torch | ddpg-torch |", table)

    def test_the_update_schedule_is_the_cpp_ones(self):
        cpp = read_json(os.path.join(self.cell("rapid-rl"), "record.json"))
        torch_rapid = read_json(os.path.join(self.cell("rapid-rl-torch"), "record.json"))
        td3 = read_json(os.path.join(self.cell("td3-bc-torch"), "record.json"))
        self.assertEqual(torch_rapid["updates"], cpp["updates"])
        self.assertEqual(td3["updates"], cpp["updates"] // 2)  # TD3's actor moves every second step
        self.assertEqual([p["target_step"] for p in torch_rapid["eval"]], [p["target_step"] for p in cpp["eval"]])

    def test_the_same_job_gives_the_same_record(self):
        cell = self.cell("rapid-rl-torch")
        first = read_json(os.path.join(cell, "record.json"))
        again = subprocess.run([sys.executable, EXAMPLE, "--method", "rapid-rl", "--job", os.path.join(cell, "job.json")],
                               capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        self.assertEqual(again.returncode, 0, again.stderr)
        second = read_json(os.path.join(cell, "record.json"))
        for key in ("final", "eval", "train_episodes", "losses", "updates", "config_hash"):
            self.assertEqual(first[key], second[key], key)

    def test_a_wrong_method_is_one_line_and_exit_2(self):
        run = subprocess.run([sys.executable, EXAMPLE, "--method", "sac", "--job",
                              os.path.join(self.cell("rapid-rl-torch"), "job.json")], capture_output=True, text=True)
        self.assertEqual(run.returncode, 2)
        self.assertEqual(len(run.stderr.strip().splitlines()), 1, run.stderr)
        self.assertIn("sac", run.stderr)


if __name__ == "__main__":
    unittest.main()
