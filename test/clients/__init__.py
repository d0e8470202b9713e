"""rospy client code of the integration tests, run by RosGraph.run_client (support/__init__.py) in a child
process after rospy.init_node: `ros.run_client(clients.wind.speed_pairs, count=20)` calls
speed_pairs(count=20) of clients/wind.py there and returns what it returned, a JSON-serialisable
dict. A child process per call, since rospy can be initialised once per process."""

import importlib

from clients.waits import set_budget


def call(function: str, kwargs: dict, budget_s: float | None = None):
    """Calls `function` ("clients.module:name") with `kwargs`; a function returning nothing gives {}.
    budget_s: every wait of this process (clients/waits.py) ends within it."""
    if budget_s is not None:
        set_budget(budget_s)
    module, _, name = function.partition(":")
    result = getattr(importlib.import_module(module), name)(**kwargs)
    return {} if result is None else result
