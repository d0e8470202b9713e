"""Motor failure injection (RotorS issue 511): the firefly hovering at (0, 0, 1) loses motor 1 at
40 s sim time (service set_motor_failure). The simulator stops that rotor, announces the fault on
motor_failure 0.2 s later (a failure detection's delay), the Lee controller re-allocates without it, and the hexacopter keeps flying on five
rotors; disturbance_eval shows the disturbance. Bad requests are refused with one line."""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

import clients.motor_failure
from rotors_evaluation.bag_data import FlightBag, load_flight
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time

EVAL = REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "scripts" / "disturbance_eval.py"


def test_hexacopter_keeps_flying_with_one_motor_out(ros: RosGraph):
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_hovering_example.launch",
        "enable_logging:=true",
        "lockstep:=true",
        "real_time_factor:=20",
        "log_file:=motor_failure",
    )
    try:
        # one client, as soon as the MAV is spawned: the calls take milliseconds, well before 40 s
        got = ros.run_client(clients.motor_failure.failure_requests)
        calls = got["calls"]
        assert got["t"] < 39.0, got
        assert calls[0] == [False, "motor_number 6 is not a motor of firefly (0..5)"]
        assert calls[1] == [False, "speed_factor 1.5 must be in [0, 1] (0: failed, 1: healthy)"]
        assert calls[2] == [True, "firefly motor 1 at 0 of its command from 40 s, announced 0.2 s later"]
        wait_sim_time(ros, 61.0)
        announced = ros.run(["rostopic", "echo", "-n", "1", "/firefly/motor_failure"]).stdout
    finally:
        stop_launch(proc)
    assert "motor_number: 1" in announced and "speed_factor: 0.0" in announced and "secs: 40\n    nsecs: 200000000" in announced
    log = Path(proc.log_path).read_text()
    assert "motor 1 at 0.00 of its command: allocation updated" in log, log[-3000:]

    bag = next(Path(ros.env["ROS_HOME"]).glob("motor_failure_*.bag"))
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench", "/motor_speed")
    motors = data.motor_speeds.window(45.0, 60.0).values
    assert np.abs(motors[:, 1]).max() < 1.0, "the failed rotor still turns"
    # the opposite rotor (4) has no share left at hover: the other four carry a quarter each
    assert np.abs(motors[:, 4]).mean() < 0.1 * np.abs(motors[:, 0]).mean()
    error = np.linalg.norm(data.position.window(40.0, 60.0).values - [0.0, 0.0, 1.0], axis=1)
    before = np.linalg.norm(data.position.window(30.0, 40.0).values - [0.0, 0.0, 1.0], axis=1)
    print(f"motor 1 out at 40 s: largest position error {error.max():.3f} m (before: {before.max():.3f} m), " f"final {error[-1]:.3f} m")
    assert error.max() < 0.5 and error[-1] < 0.1
    # yaw is what the five rotors give up: it may drift (one sign of yaw torque is out of reach)
    bag_data = FlightBag(bag)
    q = [m.pose.orientation for m, _, t in bag_data.messages("firefly/ground_truth/pose") if 59.9 < t * 1e-9 <= 60.0]
    bag_data.close()
    yaw_60 = math.atan2(2 * (q[-1].w * q[-1].z + q[-1].x * q[-1].y), 1 - 2 * (q[-1].y ** 2 + q[-1].z ** 2))
    print(f"yaw at 60 s: {yaw_60:.3f} rad (held at 0 before the failure)")
    assert not np.any(data.collision_times > 10.0)  # contacts only while resting on the ground before take-off

    res = subprocess.run(
        [sys.executable, str(EVAL), "-b", str(bag), "-n", "firefly", "--plot", "False", "--json", "-"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert res.returncode == 0, res.stderr
    print(res.stdout[: res.stdout.index("{")])
    summary = json.loads(res.stdout[res.stdout.index("{") :])
    assert summary["settling_time"] is not None and 0.0 < summary["settling_time"] < 10.0
