"""A RotorS user's controller, written against the mav_msgs C++ API only (test/mav_msgs_api_user),
builds here and hovers the firefly as the book's figure shows (section 3.6: 0.040 m)."""
import sys
from pathlib import Path

import numpy as np

from conftest import REPO, RosGraph, stop_launch, wait_sim_time

sys.path.insert(0, str(REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "src"))
from rotors_evaluation.bag_data import load_flight  # noqa: E402
from rotors_evaluation.metrics import rms_error  # noqa: E402


def test_user_controller_on_the_mav_msgs_api_hovers_within_the_books_figure(ros: RosGraph):
    proc = ros.start(["roslaunch", "-p", str(ros.port), "mav_msgs_api_user", "user_controller_hovering.launch"],
                     "launch")
    try:
        wait_sim_time(ros, 21.0)
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert "FATAL" not in log, log[-3000:]
    bag = next(Path(ros.env["ROS_HOME"]).glob("user_controller_*.bag"))
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench",
                       "/motor_speed")
    wp = data.waypoints[0]
    assert np.allclose(wp.position, [0, 0, 1])
    pos_rms = rms_error(data.position.window(wp.t + 5, wp.t + 15), wp.position)
    print(f"user controller (mav_msgs API): position RMS {pos_rms:.4f} m over 10 s (book: 0.040 m)")
    assert abs(pos_rms - 0.040) <= 0.005, pos_rms
    assert rms_error(data.angular_velocity.window(wp.t + 5, wp.t + 15), np.zeros(3)) < 1e-3
