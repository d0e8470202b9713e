"""Bounded waits on a condition, for the tests (support re-exports them) and their rospy clients
alike: each returns as soon as the condition holds, and a wait that runs out says what did not
happen. In a client's process every wait is also bounded, all together, by the client's budget
(set_budget: run_client's timeout less a margin to report), so that a wait fails with its own
message before the test's timeout ends the process."""

import time
from collections.abc import Callable
from typing import Any

_budget: tuple[float, float] | None = None  # (deadline on time.monotonic, budget [s]), a client's


def set_budget(budget_s: float) -> None:
    """Every wait from now on in this process ends within budget_s seconds of wall time from now."""
    global _budget
    _budget = (time.monotonic() + budget_s, budget_s)


def _deadline(timeout_s: float) -> tuple[float, bool]:
    """The wait's deadline, and whether the client's budget set it."""
    own = time.monotonic() + timeout_s
    return (_budget[0], True) if _budget is not None and _budget[0] < own else (own, False)


def poll(predicate: Callable[[], Any], timeout_s: float, period_s: float = 0.05) -> Any:
    """Calls `predicate` every period_s until it returns a true value, at most timeout_s of wall
    time (or what is left of the client's budget); its last value (false when the time ran out)."""
    deadline, _ = _deadline(timeout_s)
    while not (value := predicate()) and time.monotonic() < deadline:
        time.sleep(period_s)
    return value


def wait_until(predicate: Callable[[], Any], timeout_s: float, what: str, period_s: float = 0.05) -> Any:
    """`predicate`'s first true value (poll); after timeout_s of wall time (or the client's budget)
    an AssertionError says what did not happen."""
    _, by_budget = _deadline(timeout_s)
    value = poll(predicate, timeout_s, period_s)
    limit = f"the client's budget of {_budget[1]:g} s" if by_budget and _budget else f"{timeout_s:g} s"
    assert value, f"{what}: not within {limit}"
    return value


def wait_for_subscriber(publisher, timeout_s: float = 90.0, count: int = 1) -> None:
    """Until `count` subscribers are connected to a rospy publisher (the node that reads it is up)."""
    wait_until(
        lambda: publisher.get_num_connections() >= count,
        timeout_s,
        f"{count} subscriber(s) of {publisher.resolved_name}",
    )
