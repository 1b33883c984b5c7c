"""rapid_harness.Env: a scenario as a Gymnasium environment (docs/python.md).

A thin subclass of `gymnasium.Env` (of `object` when gymnasium cannot be imported) over the C++
environment of rapid_harness._core, which does the work: the same environment a `rapid run` trains
in. What Gymnasium asks of an environment and the C++ one has no use for lives here: the spaces,
`metadata`, `render_mode`, `spec` and `np_random`.
"""

import numpy as np

from . import _core

try:
    import gymnasium
except ImportError:  # Debian has no gymnasium package: the module works without it
    gymnasium = None


class Box:
    """A box of float32 vectors with gymnasium.spaces.Box's attributes (low, high, shape, dtype),
    standing in for it where gymnasium is not installed."""

    def __init__(self, low, high):
        self.low = np.asarray(low, dtype=np.float32)
        self.high = np.asarray(high, dtype=np.float32)
        self.shape = self.low.shape
        self.dtype = np.dtype(np.float32)
        self._rng = np.random.default_rng()

    def seed(self, seed=None):
        self._rng = np.random.default_rng(seed)
        return [seed]

    def sample(self):
        """Uniform where bounded, standard normal where unbounded (as gymnasium samples)."""
        bounded = np.isfinite(self.low) & np.isfinite(self.high)
        x = self._rng.standard_normal(self.shape)
        x[bounded] = self._rng.uniform(self.low[bounded], self.high[bounded])
        return x.astype(np.float32)

    def contains(self, x):
        x = np.asarray(x)
        return x.shape == self.shape and bool(np.all(x >= self.low)) and bool(np.all(x <= self.high))

    __contains__ = contains

    def __repr__(self):
        return f"Box({self.low.min()}, {self.high.max()}, {self.shape}, float32)"


def _box(n, bound):
    low, high = np.full(n, -bound, np.float32), np.full(n, bound, np.float32)
    if gymnasium is not None:
        return gymnasium.spaces.Box(low, high, (n,), np.float32)
    return Box(low, high)


class Env(gymnasium.Env if gymnasium is not None else object):
    """A scenario (a built-in name or a scenario file's path) in a config profile, with `config` (a
    dict of config keys) on top, as a Gymnasium environment. Observations lie in [-1, 1] (every
    feature is normalised and clipped), actions in [-1, 1]. A collision terminates an episode; the
    horizon truncates it."""

    metadata = {"render_modes": []}
    spec = None  # gymnasium.make sets it

    def __init__(self, scenario, profile="short", config=None, render_mode=None):
        if render_mode is not None:
            raise ValueError(
                f"render_mode: {render_mode!r}: the harness's environments do not render; "
                "record a trace instead (docs/traces.md)"
            )
        self.render_mode = None
        self._env = _core.Env(scenario, profile, config)
        self.observation_space = _box(self._env.obs_dim, _core.OBSERVATION_BOUND)
        self.action_space = _box(self._env.act_dim, 1.0)
        self._rng = None

    def reset(self, *, seed=None, options=None):
        """(obs, info): seed=k starts over from the traffic a `rapid run` with seed k trains on (its
        first training episode) and seeds np_random; reset() goes on to the next episode."""
        result = self._env.reset(seed=seed, options=options)  # first: it checks the seed and options
        if gymnasium is not None:
            super().reset(seed=seed)
        elif seed is not None:
            self._rng = np.random.default_rng(seed)
        return result

    def step(self, action):
        """(obs, reward, terminated, truncated, info)."""
        return self._env.step(action)

    def close(self):
        self._env.close()

    if gymnasium is None:

        @property
        def np_random(self):
            """A numpy Generator seeded by reset(seed=...) (the environment's own randomness is
            the simulator's, seeded by the same seed)."""
            if self._rng is None:
                self._rng = np.random.default_rng()
            return self._rng

        @property
        def unwrapped(self):
            return self

    @property
    def horizon(self):
        """Decisions per episode."""
        return self._env.horizon

    @property
    def name(self):
        """The scenario's name."""
        return self._env.name

    def _cpp_steps(self, decisions, action, seed=0):
        """Benchmark baseline: seconds for `decisions` steps taken in C++ (scripts/bench-python-step)."""
        return self._env._cpp_steps(decisions, action, seed)
