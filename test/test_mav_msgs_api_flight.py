"""A RotorS user's controller, written against the mav_msgs C++ API only (test/mav_msgs_api_user),
builds here and hovers the firefly as the book's figure shows (section 3.6: 0.040 m)."""

from pathlib import Path

from support import RosGraph, stop_launch, wait_sim_time
from support.books_hover import assert_hovers_like_the_book


def test_mav_msgs_api_controller_hovers_within_books_figure(ros: RosGraph):
    proc = ros.start(["roslaunch", "-p", str(ros.port), "mav_msgs_api_user", "user_controller_hovering.launch"], "launch")
    try:
        wait_sim_time(ros, 21.0)
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert "FATAL" not in log, log[-3000:]
    bag = next(Path(ros.env["ROS_HOME"]).glob("user_controller_*.bag"))
    assert_hovers_like_the_book(bag, "user controller (mav_msgs API)")
