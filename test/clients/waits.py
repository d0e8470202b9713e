"""Bounded waits on a condition, for the tests (support re-exports them) and their rospy clients
alike: each returns as soon as the condition holds, and a wait that runs out says what did not
happen."""

import time
from collections.abc import Callable
from typing import Any


def poll(predicate: Callable[[], Any], timeout_s: float, period_s: float = 0.05) -> Any:
    """Calls `predicate` every period_s until it returns a true value, at most timeout_s of wall
    time; its last value (false when the time ran out)."""
    deadline = time.monotonic() + timeout_s
    while not (value := predicate()) and time.monotonic() < deadline:
        time.sleep(period_s)
    return value


def wait_until(predicate: Callable[[], Any], timeout_s: float, what: str, period_s: float = 0.05) -> Any:
    """`predicate`'s first true value (poll); after timeout_s of wall time an AssertionError says
    what did not happen."""
    value = poll(predicate, timeout_s, period_s)
    assert value, f"{what}: not within {timeout_s:g} s"
    return value


def wait_for_subscriber(publisher, timeout_s: float = 90.0, count: int = 1) -> None:
    """Until `count` subscribers are connected to a rospy publisher (the node that reads it is up)."""
    wait_until(
        lambda: publisher.get_num_connections() >= count,
        timeout_s,
        f"{count} subscriber(s) of {publisher.resolved_name}",
    )
