"""A controller node written against RotorS' rotors_control library API (common.h, parameters_ros.h,
lee_position_controller.h and the lee_position_controller library; test/rotors_control_api_user)
builds here as a user's package and hovers the firefly as the book's figure shows (section 3.6:
0.040 m).

RotorS' own lee_position_controller_node.cpp is not shipped (never copied code). Built with
ROTORS_UPSTREAM_CONTROL_NODES pointing at a RotorS checkout's rotors_control/src/nodes, the package
also holds upstream_lee_position_controller_node, and this test flies it too (docs/controllers.md
gives the figures of such a run)."""
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import REPO, WS, RosGraph, stop_launch, wait_sim_time

sys.path.insert(0, str(REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "src"))
from rotors_evaluation.bag_data import load_flight  # noqa: E402
from rotors_evaluation.metrics import rms_error  # noqa: E402

NODES = ["user_lee_position_controller_node"]
if (WS / "devel" / "lib" / "rotors_control_api_user" / "upstream_lee_position_controller_node").is_file():
    NODES.append("upstream_lee_position_controller_node")


@pytest.mark.parametrize("node", NODES)
def test_a_node_on_rotors_control_api_hovers_within_the_books_figure(ros: RosGraph, node: str):
    proc = ros.start(["roslaunch", "-p", str(ros.port), "rotors_control_api_user", "user_lee_hovering.launch",
                      f"node:={node}"], "launch")
    try:
        wait_sim_time(ros, 21.0)
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert "FATAL" not in log and "could not find parameter" not in log, log[-3000:]
    bag = next(Path(ros.env["ROS_HOME"]).glob(f"{node}_*.bag"))
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench",
                       "/motor_speed")
    wp = data.waypoints[0]
    assert np.allclose(wp.position, [0, 0, 1])
    pos_rms = rms_error(data.position.window(wp.t + 5, wp.t + 15), wp.position)
    print(f"{node} (RotorS' rotors_control API): position RMS {pos_rms:.4f} m over 10 s (book: 0.040 m)")
    assert abs(pos_rms - 0.040) <= 0.005, pos_rms
    assert rms_error(data.angular_velocity.window(wp.t + 5, wp.t + 15), np.zeros(3)) < 1e-3

