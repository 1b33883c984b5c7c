"""The RAPID-RL harness's scenarios, prior datasets and evaluation protocol from Python
(docs/python.md).

The compiled part is rapid_harness._core (python/rapid_module.cpp). This package adds the
Gymnasium side: `Env` is a `gymnasium.Env` when gymnasium can be imported, and importing the package
registers `rapid/<scenario>-<profile>-v0` for every built-in scenario and profile, so that
`gymnasium.make("rapid/merge-flow-v0")` works. Without gymnasium the package works as before.
"""

# First: _core says which interpreter and numpy it was built for when it cannot load.
from . import _core
from ._core import (
    DatasetError,
    RunRecord,
    algorithm,
    config,
    evaluate,
    load_dataset,
    load_job,
    neutral_values,
    profiles,
    save_dataset,
    scenarios,
)
from .env import Box, Env
from .registration import register_builtin_scenarios, register_scenario

__all__ = [
    "Box",
    "DatasetError",
    "Env",
    "RunRecord",
    "algorithm",
    "config",
    "evaluate",
    "load_dataset",
    "load_job",
    "neutral_values",
    "profiles",
    "register_scenario",
    "save_dataset",
    "scenarios",
]

register_builtin_scenarios()
