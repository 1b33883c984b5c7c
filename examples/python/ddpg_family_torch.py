#!/usr/bin/env python3
"""The harness's DDPG-family agent in PyTorch, run by a sweep as an external method (docs/sweeps.md):

    python3 ddpg_family_torch.py --method {ddpg,rapid-rl,td3-bc} --job JOBDIR/job.json

The same algorithm as the C++ one, so that the two can be tested for equivalence: the backbone of
algos/actor_critic.cpp, the imitation weights of algos/rapid_rl.hpp and algos/td3_bc.hpp, and the
training loop of experiments/run/trainer.cpp. Only the random streams differ (numpy and torch
instead of the harness's xoshiro): same seed, same traffic, other noise and batches.
"""
import argparse
import copy
import math
import sys

import numpy as np
import torch
from torch import nn

import rapid_harness as rh

# Keys beyond the shared ones: the backbone's switches and the method keys this file implements. A
# method reads only its registry row's keys plus the shared critic_layer_norm and init; each key it
# does not read holds the backbone's neutral value. The rows, recipes (the published values, e.g.
# td3-bc's) and neutral values come from the harness itself, rh.algorithm(name) and
# rh.neutral_values(), so they cannot drift from the C++.
IMPLEMENTED = ("critic_layer_norm", "init", "critic_ensemble", "critic_subset", "policy_delay", "target_noise",
               "target_noise_clip", "bc_q_alpha", "epsilon")
METHODS = ("ddpg", "rapid-rl", "td3-bc")


def fail(message):
    print(f"ddpg_family_torch: {message}", file=sys.stderr)
    sys.exit(2)


def diverged(rec, why, n_updates):
    """A NaN or inf loss or weight ends the run as diverged, recorded as a C++ run records it (trainer.cpp)."""
    rec.finish(status="diverged", error="training diverged " + why, updates=n_updates)
    print(f"ddpg_family_torch: diverged: training diverged {why}", file=sys.stderr)
    sys.exit(1)


def method_settings(method, config, own):
    """Each key from the grid's `keys` (method_config), else the config, else the recipe, else neutral."""
    row = rh.algorithm(method)
    reads = set(row["keys"]) | {"critic_layer_norm", "init"}
    if set(own) - reads:
        fail(f"--method {method} reads no key {', '.join(sorted(set(own) - reads))}; reads {', '.join(sorted(reads))}")
    neutral = rh.neutral_values()
    return {key: own.get(key, config.get(key, row["recipe"].get(key, neutral[key]))) if key in reads else neutral[key]
            for key in IMPLEMENTED}


def mlp(inputs, hidden, outputs, init, layer_norm=False, tanh=False):
    """Linear [-> LayerNorm] -> ReLU per hidden layer, a Linear out [-> tanh] (core/mlp.cpp Mlp::make)."""
    layers, width = [], inputs
    for h in hidden:
        layers += [nn.Linear(width, h)] + ([nn.LayerNorm(h, eps=1e-5)] if layer_norm else []) + [nn.ReLU()]
        width = h
    layers.append(nn.Linear(width, outputs))
    if tanh:
        layers.append(nn.Tanh())
    net = nn.Sequential(*layers)
    linears = [m for m in net if isinstance(m, nn.Linear)]
    with torch.no_grad():  # Mlp::init's three schemes
        for i, lin in enumerate(linears):
            if init == "xavier":  # Glorot-uniform weights, zero biases
                nn.init.xavier_uniform_(lin.weight)
                lin.bias.zero_()
                continue
            # ddpg and pytorch: weights and biases U(±1/√fan_in); ddpg's last layer U(±3e-3).
            bound = 3e-3 if init == "ddpg" and i == len(linears) - 1 else 1.0 / math.sqrt(lin.in_features)
            lin.weight.uniform_(-bound, bound)
            lin.bias.uniform_(-bound, bound)
    return net


class Agent:
    def __init__(self, method, obs_dim, act_dim, config, s):
        self.method, self.act_dim, self.s = method, act_dim, s
        self.gamma, self.tau = config["gamma"], config["tau"]
        self.actor = mlp(obs_dim, config["actor_hidden"], act_dim, s["init"], tanh=True)
        self.critics = nn.ModuleList(
            mlp(obs_dim + act_dim, config["critic_hidden"], 1, s["init"], s["critic_layer_norm"])
            for _ in range(s["critic_ensemble"]))
        self.actor_target, self.critics_target = copy.deepcopy(self.actor), copy.deepcopy(self.critics)
        self.actor_opt = torch.optim.Adam(self.actor.parameters(), lr=config["actor_lr"], foreach=True)
        # One Adam over all members equals one per member (Adam is per parameter).
        self.critic_opt = torch.optim.Adam(self.critics.parameters(), lr=config["critic_lr"], foreach=True)
        self.critic_steps = 0

    def act(self, obs):
        with torch.no_grad():
            return self.actor(torch.from_numpy(np.asarray(obs, dtype=np.float32))).numpy()

    def bc_weights(self, rew):
        """w_i of the imitation term: the only place the methods differ (a constant of the step)."""
        if self.method == "rapid-rl":
            return torch.relu(rew - self.s["epsilon"])
        if self.method == "td3-bc":  # F.mse_loss also averages over the action's entries
            return torch.full_like(rew, 1.0 / self.act_dim)
        return torch.zeros_like(rew)

    def actor_step(self, b, stats):
        obs, act, rew, _, _, n_prior = b
        pi = self.actor(obs)
        q_pi = self.critics[0](torch.cat([obs, pi], 1)).squeeze(1)  # the first critic only (TD3's Q1)
        # λ = α / mean|Q(s, π(s))| only for an imitating method with bc_q_alpha on; no gradient through it.
        lam = 1.0
        if self.s["bc_q_alpha"] > 0 and self.method != "ddpg":
            lam = self.s["bc_q_alpha"] / max(q_pi.detach().abs().mean().item(), 1e-3)
        sq_err = (pi - act).pow(2).sum(1)
        loss = -lam * q_pi.mean() + (self.bc_weights(rew) * sq_err).sum() / len(rew)
        self.actor_opt.zero_grad(set_to_none=True)
        loss.backward()  # also leaves gradients on the critics: critic_step clears them first
        self.actor_opt.step()
        e = sq_err.detach()
        stats.update(actor=loss.item(), bc_prior=e[:n_prior].mean().item() if n_prior else math.nan,
                     bc_online=e[n_prior:].mean().item() if n_prior < len(e) else math.nan)

    def critic_step(self, b, stats):
        obs, act, rew, next_obs, not_terminal, _ = b
        with torch.no_grad():  # y = r + γ(1 − terminal)·min_subset Q'(s', π'(s') [+ clipped noise])
            next_act = self.actor_target(next_obs)
            if self.s["target_noise"] > 0:  # TD3's target policy smoothing
                clip = self.s["target_noise_clip"]
                noise = (torch.randn_like(next_act) * self.s["target_noise"]).clamp(-clip, clip)
                next_act = (next_act + noise).clamp(-1.0, 1.0)
            members = range(len(self.critics))
            if self.s["critic_subset"] < len(self.critics):  # drawn afresh per step (CriticEnsemble::draw_subset)
                members = torch.randperm(len(self.critics))[: self.s["critic_subset"]].tolist()
            sa2 = torch.cat([next_obs, next_act], 1)
            next_q = torch.stack([self.critics_target[i](sa2).squeeze(1) for i in members]).min(0).values
            y = rew + self.gamma * not_terminal * next_q
        sa = torch.cat([obs, act], 1)
        q = torch.stack([c(sa).squeeze(1) for c in self.critics])
        loss = (q - y).pow(2).mean()  # the mean over members and columns, as critic_step's 1/(N·B)
        self.critic_opt.zero_grad(set_to_none=True)
        loss.backward()
        self.critic_opt.step()
        stats.update(critic=loss.item(), q_mean=q.detach().mean().item())

    def soft_update(self):
        with torch.no_grad():
            for net, target in ((self.actor, self.actor_target), (self.critics, self.critics_target)):
                for p, pt in zip(net.parameters(), target.parameters()):
                    pt.mul_(1.0 - self.tau).add_(p, alpha=self.tau)

    def update(self, batch):
        """One learning step; returns its stats and whether the actor moved."""
        stats = {}
        if self.method == "td3-bc":  # TD3's order: critics, then every policy_delay-th step actor and targets
            self.critic_step(batch, stats)
            self.critic_steps += 1
            moved = self.critic_steps % self.s["policy_delay"] == 0
            if moved:
                self.actor_step(batch, stats)
                self.soft_update()
            return stats, moved
        # Algorithm 1's order: the actor (against the critic before its step), the critic, the targets.
        self.actor_step(batch, stats)
        self.critic_step(batch, stats)
        self.soft_update()
        return stats, True

    def finite(self):
        return all(torch.isfinite(p).all() for net in (self.actor, self.critics) for p in net.parameters())


class Buffer:
    """Transitions in numpy; an online one is a ring of `capacity` (core/replay_buffer.hpp)."""

    def __init__(self, obs_dim, act_dim, capacity):
        self.obs, self.next_obs = np.zeros((2, capacity, obs_dim), np.float32)
        self.act = np.zeros((capacity, act_dim), np.float32)
        self.rew, self.not_terminal = np.zeros((2, capacity), np.float32)
        self.size = self.next = 0

    @classmethod
    def from_dataset(cls, d):
        b = cls(d["observations"].shape[1], d["actions"].shape[1], len(d["rewards"]))
        b.obs[:], b.act[:], b.next_obs[:] = d["observations"], d["actions"], d["next_observations"]
        b.rew[:], b.not_terminal[:] = d["rewards"], ~d["terminals"]  # timeouts bootstrap
        b.size = len(b.rew)
        return b

    def add(self, obs, act, rew, next_obs, terminal):
        i = self.next
        self.obs[i], self.act[i], self.next_obs[i] = obs, act, next_obs
        self.rew[i], self.not_terminal[i] = rew, not terminal
        self.next, self.size = (i + 1) % len(self.rew), min(self.size + 1, len(self.rew))

    def sample(self, rng, n):  # uniform with replacement
        i = rng.integers(0, self.size, n)
        return [self.obs[i], self.act[i], self.rew[i], self.next_obs[i], self.not_terminal[i]]


def sample_batch(rng, prior, online, batch_size):
    """B/2 prior columns first, then B − B/2 online (SymmetricSampler); all online without a prior."""
    n_prior = batch_size // 2 if prior else 0
    parts = online.sample(rng, batch_size - n_prior)
    if prior:
        parts = [np.concatenate(pair) for pair in zip(prior.sample(rng, n_prior), parts)]
    return [torch.from_numpy(x) for x in parts] + [n_prior]


def train(job, method):
    config, seed = job["config"], job["seed"]
    s = method_settings(method, config, job["method_config"] or {})
    if method == "rapid-rl" and s["epsilon"] is None:
        fail("rapid-rl needs config key 'epsilon'")
    torch.manual_seed(seed)
    torch.set_num_threads(1)
    # Independent streams, as the C++ run has (core/rng.hpp): exploration and batch sampling.
    explore_rng, sample_rng = np.random.default_rng([seed, 2]), np.random.default_rng([seed, 3])
    scenario, profile = job["scenario"], job["profile"]
    env = rh.Env(scenario, profile, config)
    rec = rh.RunRecord.from_job(job["path"])  # starts the record's clock, as run_job.cpp's t0
    obs_dim, act_dim = env.observation_space.shape[0], env.action_space.shape[0]
    prior = Buffer.from_dataset(rh.load_dataset(job["dataset_path"])) if method != "ddpg" else None
    agent = Agent(method, obs_dim, act_dim, config, s)
    online = Buffer(obs_dim, act_dim, min(config["buffer_capacity"], config["steps"]))
    steps, B, E = config["steps"], config["batch_size"], config["eval_episodes"]
    F = config.get("final_eval_episodes", 0)
    first_update = max(config["warmup_steps"], B - B // 2 if prior else B, 1)  # trainer.cpp first_update_step
    window, n_updates, done = [], 0, 0

    def evaluate(n):
        if not agent.finite():  # rh.evaluate refuses NaN actions; the C++ run would diverge at its next update
            diverged(rec, f"at step {done}: a network weight is NaN or inf", n_updates)
        return rh.evaluate(agent.act, scenario, profile, config, episodes=n)

    def head(r, n):  # the first n of an evaluation's episodes (trainer.cpp head_of)
        if n == r["episodes"]:
            return r
        if r["collision_rate"] not in (0.0, 1.0):  # the rate of a head is not known: run those n again
            return evaluate(n)  # (deterministic: the same episodes, the same returns)
        return dict(r, returns=r["returns"][:n], episodes=n)

    rec.add_eval(0, evaluate(E))  # step 0, before the first training episode
    next_eval, final = config["eval_every"], None
    obs, _ = env.reset(seed=seed)  # the traffic of the first training episode of a C++ run with this seed
    ep_start, ep_return, ep_length, ep_collided = 0, 0.0, 0, False
    for t in range(steps):
        if t < config["warmup_steps"]:
            action = explore_rng.uniform(-1.0, 1.0, act_dim).astype(np.float32)
        else:
            action = np.clip(agent.act(obs) + explore_rng.normal(0.0, config["noise_std"], act_dim), -1.0, 1.0)
            action = action.astype(np.float32)
            if not np.isfinite(action).all():  # env.step refuses it; the C++ run's loss of this step is NaN
                diverged(rec, f"at step {t + 1}: a network weight is NaN or inf", n_updates)
        next_obs, reward, terminated, truncated, info = env.step(action)
        online.add(obs, action, reward, next_obs, terminated)
        ep_return, ep_length, ep_collided = ep_return + reward, ep_length + 1, ep_collided or info["collision"]
        obs, done = next_obs, t + 1
        if done >= first_update:
            stats, moved = agent.update(sample_batch(sample_rng, prior, online, B))
            n_updates += moved
            critic_loss, actor_loss = stats["critic"], stats.get("actor", 0.0)
            if not (math.isfinite(critic_loss) and math.isfinite(actor_loss)):
                diverged(rec, f"at step {done}: critic loss {critic_loss}, actor loss {actor_loss}", n_updates)
            window.append(stats)
        if done % config["bc_log_every"] == 0 and window:  # the window's means; the actor's over its steps
            if not agent.finite():
                diverged(rec, f"at step {done}: a network weight is NaN or inf", n_updates)
            means = {k: float(np.mean([w[k] for w in window if k in w] or [math.nan]))
                     for k in ("critic", "actor", "q_mean", "bc_prior", "bc_online")}
            rec.add_losses(done, **means)
            window = []
        last = done == steps
        # Evaluations only at episode boundaries (trainer.cpp end_episode): one simulation per process.
        if terminated or truncated or last:
            if terminated or truncated:
                rec.add_train_episode(ep_start, ep_return, ep_length, ep_collided)
            if done >= next_eval or last:
                target = steps if last else min(next_eval, steps)  # the multiple of eval_every it stands for
                while next_eval <= done:
                    next_eval += config["eval_every"]
                if last and F > 0:  # one evaluation serves the curve's last point and the final score
                    r = evaluate(max(E, F))
                    rec.add_eval(done, head(r, E), target_step=target)
                    final = head(r, F)
                else:
                    rec.add_eval(done, evaluate(E), target_step=target)
            if not last:
                obs, _ = env.reset()  # the next training episode (and the simulation back after an evaluation)
                ep_start, ep_return, ep_length, ep_collided = done, 0.0, 0, False
    rec.finish(final=final, updates=n_updates)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.error = fail  # one line, exit 2
    parser.add_argument("--method", required=True)
    parser.add_argument("--job", required=True)
    args = parser.parse_args()
    if args.method not in METHODS:
        fail(f"unknown --method '{args.method}'; expected one of {', '.join(METHODS)}")
    job = rh.load_job(args.job)
    job["path"] = args.job
    if args.method != "ddpg" and job["dataset_path"] is None:
        fail(f"--method {args.method} needs a prior dataset; the job has none (give the grid's entry a dataset)")
    if args.method == "ddpg" and job["dataset_path"] is not None:
        fail("--method ddpg takes no dataset (give the grid's external entry \"uses_prior\": false)")
    train(job, args.method)


if __name__ == "__main__":
    main()
