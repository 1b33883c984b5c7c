"""Where RL researchers already are (issue #70): rapid_harness.Env as a Gymnasium environment and a
sweep's prior datasets as Minari datasets.

Gymnasium and Minari are not Debian packages, so CI runs what does not need them: the properties
Gymnasium's check_env asserts, checked by the module's own tests (bounds, dtypes, reproducible
resets and steps, np_random, the attributes), and the exported datasets read back field by field
and transition by transition. With gymnasium (and minari) importable, the classes below that need
them run too: check_env on every registered id, a scenario file's registration, minari.load_dataset
and recover_environment (docs/python.md names the versions they were run against). Run by CTest
with Debian's /usr/bin/python3, PYTHONPATH=<build folder> and RAPID_BIN=<the rapid binary>."""

import importlib.util
import json
import os
import shutil
import subprocess
import tempfile
import unittest
import warnings

import numpy as np

import rapid_harness as rh

HAVE_GYMNASIUM = importlib.util.find_spec("gymnasium") is not None
HAVE_MINARI = HAVE_GYMNASIUM and importlib.util.find_spec("minari") is not None
RAPID = os.environ["RAPID_BIN"]
BUILD = os.path.dirname(os.path.abspath(RAPID))


def random_episode_steps(env, decisions, seed):
    """(obs, action, reward, next_obs, terminated, truncated) of `decisions` random actions."""
    rng = np.random.default_rng(seed)
    obs, _ = env.reset(seed=seed)
    out = []
    for _ in range(decisions):
        action = rng.uniform(-1, 1, env.action_space.shape).astype(np.float32)
        nxt, reward, terminated, truncated, _ = env.step(action)
        out.append((obs, action, reward, nxt, terminated, truncated))
        obs = nxt
        if terminated or truncated:
            obs, _ = env.reset()
    return out


class GymnasiumContract(unittest.TestCase):
    """What Gymnasium's check_env asserts, checked without gymnasium."""

    def test_observations_stay_inside_the_declared_bounds(self):
        for scenario in ("merge", "pendulum"):
            env = rh.Env(scenario)
            space = env.observation_space
            self.assertEqual((space.dtype, float(space.low.min()), float(space.high.max())), (np.float32, -1.0, 1.0))
            for obs, action, _, nxt, _, _ in random_episode_steps(env, 300, 4):
                for o in (obs, nxt):
                    self.assertEqual(o.dtype, np.float32)
                    self.assertTrue(space.contains(o), f"{scenario}: {o} outside [-1, 1]")
                self.assertTrue(env.action_space.contains(action))
            env.close()

    def test_the_same_seed_gives_the_same_episode_and_np_random(self):
        env = rh.Env("merge")
        runs = []
        for _ in range(2):
            obs, info = env.reset(seed=11)
            draws = env.np_random.integers(1 << 30, size=4)
            steps = [env.step(np.array([0.4, -0.2], np.float32)) for _ in range(20)]
            runs.append((obs, draws, steps))
        (obs_a, draws_a, steps_a), (obs_b, draws_b, steps_b) = runs
        np.testing.assert_array_equal(obs_a, obs_b)
        np.testing.assert_array_equal(draws_a, draws_b)
        for a, b in zip(steps_a, steps_b):
            np.testing.assert_array_equal(a[0], b[0])
            self.assertEqual(a[1:], b[1:])
        env.reset(seed=12)
        self.assertFalse(np.array_equal(env.np_random.integers(1 << 30, size=4), draws_a))
        env.close()

    def test_the_attributes_gymnasium_reads(self):
        env = rh.Env("pendulum")
        self.assertEqual(env.metadata["render_modes"], [])
        self.assertIsNone(env.render_mode)
        self.assertIsNone(env.spec)
        self.assertIs(env.unwrapped, env)
        obs, info = env.reset(seed=0, options={})
        self.assertEqual(info, {})
        with self.assertRaisesRegex(ValueError, "do not render"):
            rh.Env("pendulum", render_mode="human")
        env.close()

    @unittest.skipIf(HAVE_GYMNASIUM, "gymnasium is importable")
    def test_without_gymnasium_the_module_works_and_says_what_needs_it(self):
        self.assertIs(rh.Env.__mro__[1], object)
        with self.assertRaisesRegex(ImportError, "register_scenario needs gymnasium"):
            rh.register_scenario(os.path.join(BUILD, "networks", "merge", "scenario.json"))


@unittest.skipUnless(HAVE_GYMNASIUM, "gymnasium is not importable (not a Debian package)")
class WithGymnasium(unittest.TestCase):
    def test_check_env_passes_on_every_registered_id(self):
        import gymnasium
        from gymnasium.utils.env_checker import check_env

        ids = sorted(i for i in gymnasium.registry if i.startswith("rapid/"))
        self.assertEqual(ids, sorted(f"rapid/{s}-{p}-v0" for s in ("cut-in", "lane-drop", "merge") for p in ("flow", "short"))
                         + ["rapid/pendulum-short-v0"])
        for env_id in ids:
            env = gymnasium.make(env_id)
            self.assertIsInstance(env.unwrapped, gymnasium.Env)
            self.assertIsInstance(env.unwrapped, rh.Env)
            with warnings.catch_warnings():
                warnings.simplefilter("error")  # a warning of check_env fails the test
                check_env(env.unwrapped)
            env.close()

    def test_make_imports_the_module_from_the_id(self):
        code = "import gymnasium; e = gymnasium.make('rapid_harness:rapid/merge-short-v0'); print(e.unwrapped.name)"
        r = subprocess.run([os.sys.executable, "-c", code], capture_output=True, text=True)
        self.assertEqual((r.returncode, r.stdout.strip()), (0, "merge"), r.stderr)

    def test_a_scenario_file_registers_under_its_own_name(self):
        import gymnasium

        with tempfile.TemporaryDirectory() as d:
            shutil.copytree(os.path.join(BUILD, "networks"), os.path.join(d, "networks"))
            path = os.path.join(d, "networks", "merge", "scenario.json")
            with open(path) as f:
                descriptor = json.load(f)
            descriptor["name"] = "my-merge"
            with open(path, "w") as f:
                json.dump(descriptor, f)
            env_id = rh.register_scenario(path, "short", {"inflow": 1200})
            self.addCleanup(gymnasium.registry.pop, env_id)  # the other tests see the built-in ids alone
            self.assertEqual(env_id, "rapid/my-merge-short-v0")
            self.assertEqual(rh.register_scenario(path, "short", {"inflow": 1200}), env_id)  # the same again: fine
            with self.assertRaisesRegex(ValueError, "registered already"):
                rh.register_scenario(path, "short", {"inflow": 900})
            env = gymnasium.make(env_id)
            self.assertEqual(env.unwrapped.name, "my-merge")
            env.close()
            with self.assertRaises(ValueError):
                rh.register_scenario(os.path.join(d, "nowhere.json"))


class MinariDatasets(unittest.TestCase):
    """A sweep folder of one pendulum dataset, exported by `rapid dataset export`."""

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp()
        sweep = os.path.join(cls.dir, "sweep")
        os.makedirs(os.path.join(sweep, "datasets", "pendulum"))
        with open(os.path.join(sweep, "grid.json"), "w") as f:
            json.dump({"name": "g", "scenarios": ["pendulum"], "datasets": ["medium"], "algos": ["rlpd"], "seeds": [0]}, f)
        env = rh.Env("pendulum")
        steps = random_episode_steps(env, 450, 5)  # two whole episodes of 200, then 50 cut where the data stop
        env.close()
        cls.arrays = {
            "observations": np.stack([s[0] for s in steps]),
            "actions": np.stack([s[1] for s in steps]),
            "rewards": np.array([s[2] for s in steps], np.float32),
            "next_observations": np.stack([s[3] for s in steps]),
            "terminals": np.array([s[4] for s in steps]),
            "timeouts": np.array([s[5] for s in steps]),
        }
        cls.source = os.path.join(sweep, "datasets", "pendulum", "medium.h5")
        rh.save_dataset(cls.source, cls.arrays, {"scenario": "pendulum", "seed": "5"})
        cls.root = os.path.join(cls.dir, "minari")
        r = subprocess.run([RAPID, "dataset", "export", sweep, "--format", "minari", "--out", cls.root],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        cls.export_output = r.stdout
        cls.folder = os.path.join(cls.root, "rapid", "pendulum-short", "medium-v0")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir)

    def test_the_export_cuts_episodes_at_their_ends_and_where_the_data_stop(self):
        self.assertIn("rapid/pendulum-short/medium-v0  3 episodes, 450 steps", self.export_output)

    def test_load_dataset_reads_the_folder_as_the_file_it_came_from(self):
        back = rh.load_dataset(self.folder)
        for key, value in self.arrays.items():
            np.testing.assert_array_equal(back[key], value, key)
            self.assertEqual(back[key].dtype, value.dtype, key)
        self.assertEqual(back["metadata"], rh.load_dataset(self.source)["metadata"])

    def test_the_metadata_name_the_spaces_the_environment_and_where_the_data_came_from(self):
        with open(os.path.join(self.folder, "data", "metadata.json")) as f:
            meta = json.load(f)
        env = rh.Env("pendulum")
        for key, space in (("observation_space", env.observation_space), ("action_space", env.action_space)):
            box = json.loads(meta[key])
            self.assertEqual((box["type"], box["dtype"], tuple(box["shape"])), ("Box", "float32", space.shape))
            np.testing.assert_array_equal(np.array(box["low"], np.float32), space.low)
            np.testing.assert_array_equal(np.array(box["high"], np.float32), space.high)
        spec = json.loads(meta["env_spec"])
        self.assertEqual((spec["id"], spec["entry_point"]), ("rapid/pendulum-short-v0", "rapid_harness:Env"))
        self.assertEqual(spec["kwargs"], {"scenario": "pendulum", "profile": "short"})
        self.assertEqual(spec, rh._core.gymnasium_env_spec("pendulum", "short"))
        self.assertEqual((meta["total_episodes"], meta["total_steps"], meta["data_format"]), (3, 450, "hdf5"))
        self.assertEqual(meta["rapid"]["source_file"], os.path.abspath(self.source))
        self.assertEqual(meta["rapid"]["d4rl_metadata"], {"scenario": "pendulum", "seed": "5"})
        env.close()

    @unittest.skipUnless(HAVE_MINARI, "minari is not importable (not a Debian package)")
    def test_minari_loads_it_and_recovers_the_environment(self):
        import minari

        os.environ["MINARI_DATASETS_PATH"] = self.root
        ds = minari.load_dataset("rapid/pendulum-short/medium-v0")
        episodes = list(ds.iterate_episodes())
        self.assertEqual([len(e.rewards) for e in episodes], [200, 200, 50])
        joined = {
            "observations": np.concatenate([e.observations[:-1] for e in episodes]),
            "next_observations": np.concatenate([e.observations[1:] for e in episodes]),
            "actions": np.concatenate([e.actions for e in episodes]),
            "rewards": np.concatenate([e.rewards for e in episodes]),
            "terminals": np.concatenate([e.terminations for e in episodes]),
            "timeouts": np.concatenate([e.truncations for e in episodes]),
        }
        for key, value in joined.items():
            np.testing.assert_array_equal(value, self.arrays[key], key)
        env = ds.recover_environment()
        self.assertEqual((env.spec.id, env.unwrapped.name), ("rapid/pendulum-short-v0", "pendulum"))
        self.assertEqual(env.observation_space, ds.observation_space)
        env.close()


if __name__ == "__main__":
    unittest.main()
