"""The built-in scenarios' descriptors (envs/networks/<scenario>/scenario.json, docs/scenarios.md):
their display names and road edges, read from the files rather than repeated here."""

import glob
import json
import os

NETWORKS = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "envs", "networks")


def builtin_descriptors():
    """name -> descriptor of every built-in driving scenario (empty if the sources are not beside)."""
    found = {}
    for path in sorted(glob.glob(os.path.join(NETWORKS, "*", "scenario.json"))):
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        found[d["name"]] = d
    return found


def scenario_labels():
    """name -> the label a figure shows (the pendulum has no descriptor)."""
    labels = {name: d.get("display_name", name) for name, d in builtin_descriptors().items()}
    labels["pendulum"] = "Pendulum"
    return labels


def scenario_edges():
    """name -> the set of edge ids of its road."""
    return {name: set(d["road"]) for name, d in builtin_descriptors().items()}
