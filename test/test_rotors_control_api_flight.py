"""A controller node written against RotorS' rotors_control library API (common.h, parameters_ros.h,
lee_position_controller.h and the lee_position_controller library; test/rotors_control_api_user)
builds here as a user's package and hovers the firefly as the book's figure shows (section 3.6:
0.040 m).

RotorS' own lee_position_controller_node.cpp is not shipped (never copied code). Built with
ROTORS_UPSTREAM_CONTROL_NODES pointing at a RotorS checkout's rotors_control/src/nodes, the package
also holds upstream_lee_position_controller_node, and this test flies it too (docs/controllers.md
gives the figures of such a run)."""

from pathlib import Path

import pytest

from support import WS, RosGraph, stop_launch, wait_sim_time
from support.books_hover import assert_hovers_like_the_book

NODES = ["user_lee_position_controller_node"]
if (WS / "devel" / "lib" / "rotors_control_api_user" / "upstream_lee_position_controller_node").is_file():
    NODES.append("upstream_lee_position_controller_node")


@pytest.mark.parametrize("node", NODES)
def test_rotors_control_api_node_hovers_within_books_figure(ros: RosGraph, node: str):
    proc = ros.start(["roslaunch", "-p", str(ros.port), "rotors_control_api_user", "user_lee_hovering.launch", f"node:={node}"], "launch")
    try:
        wait_sim_time(ros, 21.0)
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert "FATAL" not in log and "could not find parameter" not in log, log[-3000:]
    bag = next(Path(ros.env["ROS_HOME"]).glob(f"{node}_*.bag"))
    assert_hovers_like_the_book(bag, f"{node} (RotorS' rotors_control API)")
