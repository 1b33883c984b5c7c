"""Every code block of docs/python.md and docs/bring-your-own.md runs as written (issue #67: the
argparse line of bring-your-own.md crashed, and a grid's Python method needed a PYTHONPATH the docs
never mentioned). Each block is taken from the page itself, so an edit that breaks one fails here;
a new block fails until this file says how it runs. Run by CTest with Debian's /usr/bin/python3,
PYTHONPATH=<build folder> and RAPID_BIN=<the rapid binary>; the blocks run without PYTHONPATH
where the page says they need none."""

import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
RAPID = os.environ["RAPID_BIN"]
BUILD = os.path.dirname(os.path.abspath(RAPID))


def blocks(page):
    """(language, text) of every fenced code block of docs/PAGE."""
    with open(os.path.join(SOURCE, "docs", page)) as f:
        return re.findall(r"```(\w*)\n(.*?)```", f.read(), re.S)


def without_pythonpath():
    return {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


class DocumentedCode(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.dir)

    def run_in_dir(self, argv, env=None):
        return subprocess.run(argv, capture_output=True, text=True, cwd=self.dir, env=env)

    def test_python_md(self):
        found = blocks("python.md")
        self.assertEqual([lang for lang, _ in found], ["", "sh", "python", "python", "python"],
                         "a new block: say here how it runs")
        # The shell block names the build folder as `build`, from the checkout's top.
        os.symlink(BUILD, os.path.join(self.dir, "build"))
        r = self.run_in_dir(["bash", "-c", found[0][1]], env=without_pythonpath())
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stdout, r"^\(\d+,\) ")
        # The export block, on a sweep folder of one pendulum dataset (SWEEP_DIR) into a root here.
        root = self.export_a_pendulum_dataset(found[1][1])
        # The Stable-Baselines3 and CleanRL examples need packages Debian does not have: each is
        # compiled, and run where its imports are there, on the pendulum's dataset instead of merge's.
        for name, (_, code), needs in (("sb3_example", found[2], ["gymnasium", "minari", "stable_baselines3", "torch"]),
                                       ("cleanrl_example", found[3], ["gymnasium", "minari", "torch"])):
            compile(code, name, "exec")
            if not all(importlib.util.find_spec(n) for n in needs):
                continue
            code = code.replace("rapid/merge-flow/medium-v0", "rapid/pendulum-short/medium-v0")
            code = code.replace("rapid/merge-flow-v0", "rapid/pendulum-short-v0").replace('"merge", "flow"', '"pendulum", "short"')
            code = code.replace('"flow"', '"short"')
            r = self.run_in_dir([sys.executable, "-c", code], env=dict(os.environ, MINARI_DATASETS_PATH=root, OMP_NUM_THREADS="1"))
            self.assertEqual(r.returncode, 0, name + ": " + r.stderr[-3000:])
            self.assertIn("'return_mean'", r.stdout, name)
        # The run record block, as a script (the record hashes the running script), writes
        # runs/merge-zero-0/record.json where it runs.
        with open(os.path.join(self.dir, "record_example.py"), "w") as f:
            f.write(found[4][1])
        r = self.run_in_dir([sys.executable, "record_example.py"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(self.dir, "runs", "merge-zero-0", "record.json")) as f:
            record = json.load(f)
        self.assertEqual((record["status"], record["cell"]["algo"], record["final"]["episodes"]), ("ok", "zero-torch", 3))

    def export_a_pendulum_dataset(self, block):
        """Runs the export block on a sweep folder holding one pendulum dataset; returns the root."""
        sweep = os.path.join(self.dir, "sweep")
        os.makedirs(os.path.join(sweep, "datasets", "pendulum"))
        with open(os.path.join(sweep, "grid.json"), "w") as f:
            json.dump({"name": "g", "scenarios": ["pendulum"], "datasets": ["medium"], "algos": ["rlpd"], "seeds": [0]}, f)
        import numpy as np
        import rapid_harness as rh
        env, rng, rows = rh.Env("pendulum"), np.random.default_rng(0), []
        obs, _ = env.reset(seed=0)
        for _ in range(400):
            action = rng.uniform(-1, 1, 1).astype(np.float32)
            nxt, reward, terminated, truncated, _ = env.step(action)
            rows.append((obs, action, reward, nxt, terminated, truncated))
            obs = nxt if not (terminated or truncated) else env.reset()[0]
        env.close()
        keys = ["observations", "actions", "rewards", "next_observations", "terminals", "timeouts"]
        arrays = {k: np.array([row[i] for row in rows], np.float32 if i < 4 else bool) for i, k in enumerate(keys)}
        rh.save_dataset(os.path.join(sweep, "datasets", "pendulum", "medium.h5"), arrays)
        root = os.path.join(self.dir, "minari")
        script = block.replace("SWEEP_DIR", sweep).replace("~/.minari/datasets", root)
        r = self.run_in_dir(["bash", "-c", script])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("rapid/pendulum-short/medium-v0  2 episodes, 400 steps", r.stdout)
        return root

    def test_bring_your_own_md(self):
        found = blocks("bring-your-own.md")
        self.assertEqual([lang for lang, _ in found], ["python", "json"], "a new block: say here how it runs")
        # The script, as an external method of a small grid, from a shell without PYTHONPATH.
        with open(os.path.join(self.dir, "mine.py"), "w") as f:
            f.write(found[0][1])
        grid = {"name": "documented", "scenarios": ["pendulum"], "datasets": ["initial"], "algos": ["mine"],
                "seeds": [0], "config": {"steps": 400, "warmup_steps": 0, "eval_every": 200, "eval_episodes": 1,
                                         "batch_size": 32},
                "reference": {"seed": 1000, "transitions": 600}, "max_retries": 0,
                "external": {"mine": {"command": ["/usr/bin/python3", "mine.py"]}}}
        with open(os.path.join(self.dir, "small.json"), "w") as f:
            json.dump(grid, f)
        out = os.path.join(self.dir, "out")
        r = self.run_in_dir([RAPID, "sweep", "small.json", "--out", out, "--no-summary"], env=without_pythonpath())
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        with open(os.path.join(out, "jobs", "pendulum", "initial", "mine", "seed0", "record.json")) as f:
            record = json.load(f)
        self.assertEqual(record["status"], "ok")
        self.assertEqual([e["step"] for e in record["eval"]], [0, 200, 400])
        # The grid, in a folder beside the checkout's examples/ as its relative command says: it
        # loads, and its method's config resolves (running it needs python3-torch and hours).
        os.makedirs(os.path.join(self.dir, "grids"))
        os.symlink(os.path.join(SOURCE, "examples"), os.path.join(self.dir, "examples"))
        with open(os.path.join(self.dir, "grids", "mine.json"), "w") as f:
            f.write(found[1][1])
        r = self.run_in_dir([RAPID, "run", "--scenario", "merge", "--algo", "rapid-rl-torch", "--grid", "grids/mine.json",
                             "--print-config"])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("epsilon", r.stdout)


if __name__ == "__main__":
    unittest.main()
