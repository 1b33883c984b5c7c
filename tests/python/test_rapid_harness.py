"""The Python module's API (docs/python.md): Gymnasium's Env contract, reproducible resets, clear
errors, and the evaluation protocol. Run by CTest with Debian's /usr/bin/python3 and
PYTHONPATH=<build folder>."""

import json
import os
import tempfile
import unittest

import numpy as np

import rapid_harness as rh


class PendulumEnv(unittest.TestCase):
    def setUp(self):
        self.env = rh.Env("pendulum")

    def tearDown(self):
        self.env.close()

    def test_spaces_are_boxes_of_float32(self):
        act, obs = self.env.action_space, self.env.observation_space
        self.assertEqual(act.shape, (1,))
        self.assertEqual(act.dtype, np.float32)
        np.testing.assert_array_equal(act.low, [-1.0])
        np.testing.assert_array_equal(act.high, [1.0])
        self.assertEqual(obs.shape, (3,))
        self.assertEqual(obs.dtype, np.float32)
        self.assertTrue(act.contains(act.sample()))

    def test_reset_and_step_return_gymnasium_tuples(self):
        obs, info = self.env.reset(seed=3)
        self.assertIsInstance(obs, np.ndarray)
        self.assertEqual((obs.dtype, obs.shape), (np.float32, (3,)))
        self.assertEqual(info, {})
        self.assertTrue(self.env.observation_space.contains(obs))
        step = self.env.step(np.zeros(1, dtype=np.float32))
        self.assertEqual(len(step), 5)
        nxt, reward, terminated, truncated, info = step
        self.assertEqual((nxt.dtype, nxt.shape), (np.float32, (3,)))
        self.assertIsInstance(reward, float)
        self.assertIs(terminated, False)
        self.assertIs(truncated, False)
        self.assertEqual(set(info), {"collision", "ego_speed", "lane_changes", "lane_change_failed"})
        self.assertIsNot(nxt, obs)  # a fresh array per step: keeping one is safe

    def rollout(self, seed, steps=30):
        obs, _ = self.env.reset(seed=seed)
        out = [obs]
        for t in range(steps):
            obs, reward, _, _, _ = self.env.step([np.sin(t)])  # a list is an action too
            out.extend([obs, np.float32(reward)])
        return out

    def test_reset_with_a_seed_is_reproducible(self):
        a, b, c = self.rollout(5), self.rollout(5), self.rollout(6)
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y)
        self.assertFalse(np.array_equal(a[0], c[0]))

    def test_reset_without_a_seed_starts_the_next_episode(self):
        first, _ = self.env.reset(seed=1)
        second, _ = self.env.reset()
        self.assertFalse(np.array_equal(first, second))
        again, _ = self.env.reset(seed=1)
        np.testing.assert_array_equal(first, again)

    def test_the_horizon_truncates_and_does_not_terminate(self):
        self.env.reset(seed=0)
        for t in range(1, self.env.horizon + 1):
            _, _, terminated, truncated, _ = self.env.step([0.0])
            self.assertFalse(terminated)
            if truncated:
                break
        self.assertEqual(t, self.env.horizon)
        with self.assertRaisesRegex(RuntimeError, r"call reset\(\) first"):
            self.env.step([0.0])

    def test_bad_actions_are_refused_by_name(self):
        with self.assertRaisesRegex(RuntimeError, r"call reset\(\) first"):
            self.env.step([0.0])
        self.env.reset(seed=0)
        with self.assertRaisesRegex(ValueError, r"^step: expected an action of shape \(1,\), got \(2,\)$"):
            self.env.step(np.zeros(2))
        with self.assertRaisesRegex(ValueError, "NaN or inf"):
            self.env.step([float("nan")])
        with self.assertRaisesRegex(ValueError, "non-negative"):
            self.env.reset(seed=-1)
        with self.assertRaisesRegex(ValueError, "no options"):
            self.env.reset(options={"x": 1})

    def test_the_benchmarks_cpp_loop_steps_the_same_environment(self):
        self.assertGreater(self.env._cpp_steps(250, np.zeros(1, np.float32)), 0.0)  # past the horizon: it resets
        with self.assertRaisesRegex(RuntimeError, "reset"):
            self.env.step(np.zeros(1, np.float32))  # its episode is not the caller's

    def test_a_closed_environment_says_so(self):
        self.env.close()
        with self.assertRaisesRegex(RuntimeError, "closed"):
            self.env.reset()


class WrongInputs(unittest.TestCase):
    def test_a_wrong_scenario_name_is_one_line(self):
        with self.assertRaises(ValueError) as e:
            rh.Env("nope")
        message = str(e.exception)
        self.assertNotIn("\n", message)
        self.assertTrue(message.startswith("unknown scenario 'nope'; expected one of cut-in, lane-drop, merge"), message)

    def test_a_wrong_config_key_or_value_is_named(self):
        with self.assertRaisesRegex(ValueError, "'nope'"):
            rh.Env("pendulum", config={"nope": 1})
        with self.assertRaisesRegex(ValueError, "gamma"):
            rh.Env("pendulum", config={"gamma": "high"})
        with self.assertRaisesRegex(ValueError, "dict"):
            rh.Env("pendulum", config=[1])

    def test_the_lists_match_the_harness(self):
        self.assertEqual(rh.scenarios(), ["cut-in", "lane-drop", "merge", "pendulum"])
        self.assertIn("flow", rh.profiles())

    def test_the_config_is_the_one_a_run_resolves(self):
        flow = rh.config("merge", "flow")
        # The flow profile's shared keys under merge's own (its descriptor's "profiles" entry).
        self.assertEqual((flow["epsilon"], flow["steps"], flow["network"]), (-0.15, 30000, "long"))
        self.assertIsInstance(flow["inflow"], float)
        self.assertEqual(rh.config("merge", "flow", {"steps": 5})["steps"], 5)
        self.assertNotIn("inflow", rh.config("merge"), "a short built-in leaves its scenario keys to their defaults")
        with self.assertRaisesRegex(ValueError, "^scenario 'pendulum' has no 'flow' profile$"):
            rh.config("pendulum", "flow")
        with self.assertRaisesRegex(ValueError, "^unknown scenario 'nope'"):
            rh.config("nope")


class AnotherInterpreter(unittest.TestCase):
    def test_an_interpreter_without_numpy_is_told_which_one_the_module_wants(self):
        # Issue #67: under pyenv's python3 (no Debian numpy) the import said only "initialization
        # failed". An interpreter that cannot import numpy is simulated by blocking the import.
        import subprocess
        import sys
        code = "import sys; sys.modules['numpy'] = None; import rapid_harness"
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        last = r.stderr.strip().splitlines()[-1]
        self.assertIn("ImportError: rapid_harness needs numpy, which " + sys.executable, last)
        self.assertIn("the module was built for /usr/bin/python3 (Python ", last)


class DrivingEnv(unittest.TestCase):
    def test_merge_steps_in_sumo_and_reproduces_its_traffic(self):
        env = rh.Env("merge")
        try:
            runs = []
            for _ in range(2):
                obs, _ = env.reset(seed=7)
                trail = [obs]
                for _ in range(5):
                    obs, reward, terminated, truncated, info = env.step(np.array([0.3, 0.0], dtype=np.float32)[: env.action_space.shape[0]])
                    self.assertTrue(np.all(np.isfinite(obs)))
                    self.assertIsInstance(info["collision"], bool)
                    self.assertGreaterEqual(info["ego_speed"], 0.0)
                    # The reward's terms add up to it (velocity less the penalties; the reward is float32).
                    t = info["reward_terms"]
                    total = -t["collision"] if info["collision"] else t["velocity"] - t["gap"] - t["follower"] - t["failed_lane_change"]
                    self.assertAlmostEqual(total, reward, places=5)
                    trail += [obs, reward]
                    if terminated or truncated:
                        break
                runs.append(trail)
            for x, y in zip(*runs):
                np.testing.assert_array_equal(x, y)
        finally:
            env.close()


    def test_a_collision_terminates(self):
        # Standing still on merge's highway, the ego is hit from behind: a true end, not a time limit.
        env = rh.Env("merge")
        try:
            env.reset(seed=0)
            for t in range(1, env.horizon + 1):
                _, reward, terminated, truncated, info = env.step(np.zeros(env.action_space.shape, dtype=np.float32))
                if terminated or truncated:
                    break
            self.assertTrue(terminated)
            self.assertFalse(truncated)
            self.assertTrue(info["collision"])
            self.assertAlmostEqual(-info["reward_terms"]["collision"], reward, places=5)
            self.assertLess(t, env.horizon)
            self.assertLess(reward, 0.0)
        finally:
            env.close()

    def test_a_second_simulation_is_refused_not_mixed_in(self):
        first, second = rh.Env("merge"), rh.Env("lane-drop")
        try:
            first.reset(seed=0)
            second.reset(seed=0)  # libsumo's one simulation is now the lane-drop's
            with self.assertRaisesRegex(RuntimeError, "one simulation per process"):
                first.step(np.zeros(first.action_space.shape, dtype=np.float32))
            first.reset(seed=0)  # takes the simulation back
            first.step(np.zeros(first.action_space.shape, dtype=np.float32))
        finally:
            first.close()
            second.close()


class Datasets(unittest.TestCase):
    def arrays(self, n=50):
        rng = np.random.default_rng(0)
        return {
            "observations": rng.standard_normal((n, 3)).astype(np.float32),
            "actions": rng.uniform(-1, 1, (n, 1)).astype(np.float32),
            "rewards": rng.standard_normal(n).astype(np.float32),
            "next_observations": rng.standard_normal((n, 3)).astype(np.float32),
            "terminals": np.arange(n) == 24,
            "timeouts": np.arange(n) == n - 1,
        }

    def test_a_dataset_round_trips_through_the_harness_file_format(self):
        data = self.arrays()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "prior.h5")
            rh.save_dataset(path, data, {"scenario": "pendulum"})
            back = rh.load_dataset(path)
        for key, value in data.items():
            self.assertEqual(back[key].dtype, value.dtype, key)
            np.testing.assert_array_equal(back[key], value, key)
        self.assertEqual(back["metadata"]["scenario"], "pendulum")
        self.assertFalse(back["observations"].flags["OWNDATA"])  # a view of the read dataset, not a copy
        observations = back["observations"]
        del back
        np.testing.assert_array_equal(observations, data["observations"])  # the view keeps its dataset alive

    def test_wrong_arrays_and_files_are_named(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "prior.h5")
            data = self.arrays()
            del data["rewards"]
            with self.assertRaisesRegex(ValueError, "missing 'rewards'"):
                rh.save_dataset(path, data)
            data = self.arrays()
            data["actions"] = data["actions"][:10]
            with self.assertRaisesRegex(ValueError, "actions"):
                rh.save_dataset(path, data)
            data = self.arrays()
            data["rewards"][3] = np.nan
            with self.assertRaises(rh.DatasetError):
                rh.save_dataset(path, data)
            self.assertFalse(os.path.exists(path))  # nothing half-written
            with self.assertRaisesRegex(ValueError, "nowhere.h5"):
                rh.load_dataset(os.path.join(d, "nowhere.h5"))


class Evaluate(unittest.TestCase):
    def test_a_python_policy_is_scored_by_the_evaluation_protocol(self):
        zero = lambda obs: np.zeros(1, dtype=np.float32)
        first = rh.evaluate(zero, "pendulum", episodes=3)
        self.assertEqual(first["episodes"], 3)
        self.assertEqual(len(first["returns"]), 3)
        self.assertAlmostEqual(first["return_mean"], float(np.mean(first["returns"])), places=9)
        self.assertAlmostEqual(first["return_std"], float(np.std(first["returns"])), places=9)
        self.assertEqual(first, rh.evaluate(zero, "pendulum", episodes=3))  # the same seeds every time
        # The episodes are the evaluation seeds, not a training episode's traffic.
        env = rh.Env("pendulum")
        obs, _ = env.reset(seed=0)
        seen = []
        rh.evaluate(lambda o: seen.append(o) or np.zeros(1), "pendulum", episodes=1)
        self.assertFalse(np.array_equal(seen[0], obs))
        env.close()

    def test_a_wrong_policy_output_is_named(self):
        with self.assertRaisesRegex(ValueError, "must return 1 numbers"):
            rh.evaluate(lambda obs: np.zeros(2), "pendulum", episodes=1)
        with self.assertRaisesRegex(ValueError, "at least 1"):
            rh.evaluate(lambda obs: np.zeros(1), "pendulum", episodes=0)


class Algorithms(unittest.TestCase):
    def test_a_row_gives_the_keys_and_the_published_recipe(self):
        td3 = rh.algorithm("td3-bc")
        self.assertTrue(td3["uses_prior"])
        self.assertIn("policy_delay", td3["keys"])
        # TD3+BC's published values (sfujim/TD3_BC), as the C++ runs take them.
        self.assertEqual((td3["recipe"]["bc_q_alpha"], td3["recipe"]["policy_delay"], td3["recipe"]["critic_layer_norm"]),
                         (2.5, 2, False))
        self.assertEqual(rh.algorithm("rapid-rl")["keys"], ["epsilon", "bc_q_alpha"])
        self.assertFalse(rh.algorithm("ddpg")["uses_prior"])
        with self.assertRaisesRegex(ValueError, "unknown algorithm 'sac'"):
            rh.algorithm("sac")

    def test_the_neutral_values_are_the_backbones(self):
        neutral = rh.neutral_values()
        # A run that sets none of these is the paper's DDPG backbone: one LayerNorm critic, its own
        # initialisation, no smoothing, no delay, no Q-weighted imitation (algos/actor_critic.hpp).
        self.assertEqual({k: neutral[k] for k in ("critic_layer_norm", "init", "critic_ensemble", "critic_subset",
                                                  "policy_delay", "target_noise", "bc_q_alpha")},
                         {"critic_layer_norm": True, "init": "ddpg", "critic_ensemble": 1, "critic_subset": 1,
                          "policy_delay": 1, "target_noise": 0.0, "bc_q_alpha": 0.0})
        self.assertIsInstance(neutral["critic_ensemble"], int)
        self.assertIsNone(neutral["epsilon"])  # RAPID-RL's ε has no neutral value: a config must give it
        for name in ("rapid-rl", "td3-bc", "rlpd-sac", "q-filter"):
            for key in rh.algorithm(name)["keys"]:
                self.assertIn(key, neutral)


class RunRecords(unittest.TestCase):
    """A Python method's record is a `rapid run` record: the same schema, cell, resolved config and
    final return, with a hash that covers the script and the method's own keys."""

    def write(self, d, method_config=None, script=__file__):
        zero = lambda obs: np.zeros(1, dtype=np.float32)
        rec = rh.RunRecord(os.path.join(d, "run"), "pendulum", "zero-torch", 3, config={"steps": 200, "final_eval_episodes": 3},
                           script=script, method_config=method_config or {"lr": 3e-4})
        rec.add_eval(0, rh.evaluate(zero, "pendulum", episodes=2))
        rec.add_train_episode(0, -1200.5, 200, False)
        rec.add_losses(100, critic=0.5, actor=-1.0)
        final = rh.evaluate(zero, "pendulum", episodes=3)
        path = rec.finish(final=final, updates=150)
        with open(path) as f:
            return json.load(f), final

    def test_the_record_has_the_harness_schema(self):
        with tempfile.TemporaryDirectory() as d:
            record, final = self.write(d)
        self.assertEqual(record["schema"], "rapid.run/1")
        self.assertEqual((record["status"], record["error"]), ("ok", None))
        self.assertEqual(record["cell"], {"scenario": "pendulum", "dataset": None, "algo": "zero-torch", "seed": 3})
        self.assertEqual(record["config"], rh.config("pendulum", config={"steps": 200, "final_eval_episodes": 3}))
        self.assertEqual(record["final"]["episode_returns"], final["returns"])
        self.assertAlmostEqual(record["final"]["return_mean"], final["return_mean"], places=9)
        self.assertEqual(record["updates"], 150)
        self.assertEqual([e["step"] for e in record["eval"]], [0])
        self.assertEqual(record["train_episodes"][0]["return"], -1200.5)
        self.assertEqual((record["losses"][0]["critic"], record["losses"][0]["q_mean"]), (0.5, None))  # not given: null
        self.assertEqual(record["method_config"], {"lr": 3e-4})
        self.assertEqual(record["provenance"]["script"]["path"], __file__)
        self.assertRegex(record["config_hash"], "^[0-9a-f]{16}$")

    def test_the_final_return_is_the_configs_as_for_a_cpp_run(self):
        # Issue #67: on the short profile (no final evaluation) the table mixed a Python method's
        # final evaluation with the C++ runs' mean of their last evaluations. The config decides.
        zero = lambda obs: np.zeros(1, dtype=np.float32)
        with tempfile.TemporaryDirectory() as d:
            rec = rh.RunRecord(os.path.join(d, "short"), "pendulum", "zero-torch", 0, config={"steps": 200, "last_k": 2},
                               script=__file__)
            evals = [rh.evaluate(zero, "pendulum", episodes=1 + i) for i in range(3)]
            for i, e in enumerate(evals):
                rec.add_eval(100 * i, e)
            with open(rec.finish(final=rh.evaluate(zero, "pendulum", episodes=5))) as f:
                final = json.load(f)["final"]
            self.assertAlmostEqual(final["return_mean"], (evals[1]["return_mean"] + evals[2]["return_mean"]) / 2, places=9)
            self.assertNotIn("episode_returns", final)  # the final evaluation given is not this config's final return
            rec = rh.RunRecord(os.path.join(d, "flow"), "pendulum", "zero-torch", 0, config={"final_eval_episodes": 4},
                               script=__file__)
            rec.add_eval(0, evals[0])
            with self.assertRaisesRegex(ValueError, r"final evaluation of 4 episodes \(final_eval_episodes\)"):
                rec.finish()
            rec = rh.RunRecord(os.path.join(d, "none"), "pendulum", "zero-torch", 0, script=__file__)
            with self.assertRaisesRegex(ValueError, "has at least one \\(add_eval\\)"):
                rec.finish(final=evals[0])

    def test_the_hash_covers_the_method_and_its_script(self):
        with tempfile.TemporaryDirectory() as d:
            base = self.write(d)[0]["config_hash"]
            self.assertEqual(self.write(d)[0]["config_hash"], base)
            self.assertNotEqual(self.write(d, method_config={"lr": 1e-3})[0]["config_hash"], base)
            other = os.path.join(d, "other.py")
            with open(other, "w") as f:
                f.write("# another script\n")
            self.assertNotEqual(self.write(d, script=other)[0]["config_hash"], base)

    def test_wrong_records_are_refused_by_name(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "run")
            with self.assertRaisesRegex(ValueError, "harness's own"):
                rh.RunRecord(out, "pendulum", "rapid-rl", 0)
            with self.assertRaisesRegex(ValueError, "not a name"):
                rh.RunRecord(out, "pendulum", "my method", 0)
            with self.assertRaisesRegex(ValueError, "^unknown scenario"):
                rh.RunRecord(out, "nope", "mine", 0)
            with self.assertRaisesRegex(ValueError, "script"):
                rh.RunRecord(out, "pendulum", "mine", 0, script=os.path.join(d, "missing.py"))
            rec = rh.RunRecord(out, "pendulum", "mine", 0, script=__file__)
            with self.assertRaisesRegex(ValueError, "final evaluation"):
                rec.finish()
            with self.assertRaisesRegex(ValueError, "status"):
                rec.finish(status="great")
            with self.assertRaisesRegex(ValueError, "says why"):
                rec.finish(status="failed")
            self.assertFalse(os.path.exists(out), "a refused record writes nothing")
            rec.finish(status="failed", error="diverged at step 7")
            with open(os.path.join(out, "record.json")) as f:
                self.assertEqual(json.load(f)["error"], "diverged at step 7")


if __name__ == "__main__":
    unittest.main()
