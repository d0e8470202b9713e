"""mav_with_waypoint_publisher.launch with a waypoint file; bad trajectories are ignored with a
warning; gui:=true without a display is one line and the simulation carries on."""

import math
from pathlib import Path

import pytest

import clients.waypoint_file_flight
from support import RosGraph, launch, stop_launch, wait_sim_time
from support.flights import ground_truth


def test_waypoint_file_is_flown_and_bad_trajectories_are_ignored(ros: RosGraph, tmp_path: Path):
    wp = tmp_path / "waypoints.txt"
    wp.write_text("4 1 0 1 0\n10 1 1 1.5 90\n")  # wait_time x y z yaw_deg
    ros.env.pop("DISPLAY", None)
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_with_waypoint_publisher.launch",
        "gui:=true",
        f"waypoint_file:={wp}",
        "lockstep:=true",
        "real_time_factor:=10",
    )
    try:
        # the publisher waits for the simulation and 30 s of sim time; point 0 holds 4 s, then point 1
        wait_sim_time(ros, 48.0)
        s = ground_truth(ros, "firefly")
        ros.run_client(clients.waypoint_file_flight.bad_trajectories)
        wait_sim_time(ros, 55.0)
        after = ground_truth(ros, "firefly")
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert "Read 2 waypoints." in log
    assert (s["x"], s["y"], s["z"]) == (pytest.approx(1.0, abs=0.02), pytest.approx(1.0, abs=0.02), pytest.approx(1.54, abs=0.01))
    assert math.degrees(2 * math.atan2(s["qz"], s["qw"])) == pytest.approx(90.0, abs=1.0)
    assert "ignoring trajectory: message has no points" in log
    assert "point 0 has NaN or inf" in log
    assert "quaternion has norm 2.000000, not 1" in log
    assert math.dist((after["x"], after["y"], after["z"]), (s["x"], s["y"], s["z"])) < 0.01  # ignored
    assert "rviz cannot open a display" in log
