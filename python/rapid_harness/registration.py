"""Gymnasium ids for the harness's environments (docs/python.md §Gymnasium).

Importing rapid_harness registers `rapid/<scenario>-<profile>-v0` for every built-in scenario and
profile; `register_scenario` registers a scenario file. The ids and keyword arguments come from the
C++ side (experiments/run/gymnasium_spec.hpp), which also writes them into exported Minari datasets,
so `recover_environment()` of such a dataset builds the environment registered here.
"""

import os

from . import _core
from .env import gymnasium


def _register(spec):
    """Registers a spec (a dict as EnvSpec.to_json writes it); the same id again is refused unless
    it means the same environment."""
    known = gymnasium.registry.get(spec["id"])
    if known is not None:
        if known.entry_point == spec["entry_point"] and known.kwargs == spec["kwargs"]:
            return spec["id"]
        raise ValueError(f"{spec['id']} is registered already, for {known.kwargs}")
    gymnasium.register(
        id=spec["id"],
        entry_point=spec["entry_point"],
        max_episode_steps=spec["max_episode_steps"],
        nondeterministic=spec["nondeterministic"],
        kwargs=spec["kwargs"],
    )
    return spec["id"]


def register_builtin_scenarios():
    """rapid/<scenario>-<profile>-v0 for every built-in scenario and each profile it has (nothing
    without gymnasium)."""
    if gymnasium is None:
        return
    for scenario in _core.scenarios():
        for profile in _core.profiles():
            try:
                _core.config(scenario, profile)
            except ValueError:  # the pendulum has no flow profile
                continue
            _register(_core.gymnasium_env_spec(scenario, profile))


def register_scenario(path, profile="short", config=None):
    """Registers a scenario file (docs/scenarios.md) in a profile, with `config` (config keys) on top,
    as rapid/<its name>-<profile>-v0, and returns the id for gymnasium.make. The file is checked
    first: a wrong one raises ValueError and registers nothing."""
    if gymnasium is None:
        raise ImportError("register_scenario needs gymnasium, which this Python cannot import")
    path = os.path.abspath(path)
    _core.config(path, profile, config)  # checks the file, the profile and the keys
    return _register(_core.gymnasium_env_spec(path, profile, config))
