"""What the rclpy test clients share: every wait bounded by its own limit and, all together, by the
client's budget of wall time; and the one RESULT=<json> line the test reads before the client ends."""

import json
import time

import rclpy


class Budget:
    """Waits of `node` (spinning it) within `budget_s` seconds of wall time from now; `client` names
    the client in the SystemExit that a wait past its limit raises."""

    def __init__(self, node, budget_s: float, client: str):
        self.node, self.budget_s, self.client = node, budget_s, client
        self.deadline = time.monotonic() + budget_s

    def until(self, predicate, what, timeout_s: float | None = None) -> None:
        """Spins until predicate(); SystemExit naming `what` (a text, or a function giving it when the
        wait fails) past timeout_s or the budget."""
        deadline = self.deadline if timeout_s is None else min(time.monotonic() + timeout_s, self.deadline)
        while not predicate():
            if time.monotonic() > deadline:
                limit = (
                    f"the budget of {self.budget_s:g} s"
                    if timeout_s is None
                    else f"{timeout_s:g} s (or the client's budget of {self.budget_s:g} s)"
                )
                raise SystemExit(f"{self.client}: {what() if callable(what) else what}: not within {limit}")
            rclpy.spin_once(self.node, timeout_sec=0.05)


def report(node, result: dict) -> None:
    """Prints RESULT=<json> and leaves the graph."""
    print("RESULT=" + json.dumps(result), flush=True)
    node.destroy_node()
    rclpy.shutdown()
