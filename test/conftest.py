"""pytest's hooks and fixtures: the long tier's marker, and `ros`, an isolated ROS master per test
(support.RosGraph) torn down with everything the test started against it."""

from collections.abc import Iterator
from pathlib import Path

import pytest

from rotors_evaluation.processes import restore_sigint
from support import RosGraph


def pytest_configure(config):
    restore_sigint()  # run as a background job (nohup make test &), the ROS processes would ignore Ctrl-C
    config.addinivalue_line("markers", "long: the long tier (minutes each): run by make test-all and make test-long, " "not by make test")
    config.addinivalue_line("markers", "ros2: the ROS 2 front end with an rclpy client: run by make test-ros2 (after make ros2-setup)")


@pytest.fixture
def ros(tmp_path: Path) -> Iterator[RosGraph]:
    graph = RosGraph(tmp_path)
    try:
        yield graph
    finally:
        graph.stop()
