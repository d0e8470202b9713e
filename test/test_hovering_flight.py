"""End to end, as the book's sections 3.3 and 3.6: the firefly hovering example with logging,
evaluated with hovering_eval. Runs in lockstep, faster than real time."""

import subprocess
from pathlib import Path

import numpy as np
import pytest

import clients.hovering_flight
from rotors_evaluation.bag_data import FlightBag, load_flight
from rotors_evaluation.metrics import rms_error
from support import RosGraph, launch, stop_launch, wait_sim_time

# Topics of a spawned firefly (RotorS' rotors_gazebo/launch/mav_hovering_example.launch and spawn_mav.launch).
ROTORS_TOPICS = [
    "/firefly/command/motor_speed",
    "/firefly/command/trajectory",
    "/firefly/command/pose",
    "/firefly/gazebo/command/motor_speed",
    "/firefly/motor_speed",
    *[f"/firefly/motor_speed/{i}" for i in range(6)],
    "/firefly/joint_states",
    "/firefly/imu",
    "/firefly/ground_truth/imu",
    *[
        f"/firefly/{s}/{t}"
        for s in ("ground_truth", "odometry_sensor1")
        for t in ("odometry", "pose", "pose_with_covariance", "position", "transform")
    ],
    "/tf",
    "/clock",
    "/gazebo/model_states",
]


def fly(ros: RosGraph, *args: str, until_s: float = 21.0):
    proc = launch(
        ros, "rotors_gazebo", "mav_hovering_example.launch", "enable_logging:=true", "lockstep:=true", "real_time_factor:=10", *args
    )
    try:
        wait_sim_time(ros, until_s)
        topics = ros.run(["rostopic", "list"]).stdout.split()
        imu = ros.run_client(clients.hovering_flight.imu_joints_and_rotor_speeds)
    finally:
        stop_launch(proc)
    bags = sorted(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    assert bags, Path(proc.log_path).read_text()[-3000:]
    return bags[-1], topics, imu, proc


def test_firefly_hovers_with_the_books_rms_and_logs_a_bag(ros: RosGraph, tmp_path: Path):
    bag, topics, imu, _ = fly(ros)
    missing = [t for t in ROTORS_TOPICS if t not in topics]
    assert not missing, f"topics missing: {missing}"

    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench", "/motor_speed")
    wp = data.waypoints[0]
    assert np.allclose(wp.position, [0, 0, 1]) and 5.0 <= wp.t < 5.5  # sent after 5 s of sim time
    # takes off after about 5 s: on the ground before, climbing after
    z = data.position.values[:, 2]
    assert z[data.position.t < 4.9].max() < 0.1
    assert z[(data.position.t > 7) & (data.position.t < 8)].min() > 0.8
    # book section 3.6: 0.040 m over 10-20 s; it is the controller's mass/gravity mismatch (ref. 9)
    window = data.position.window(wp.t + 5, wp.t + 15)
    pos_rms = rms_error(window, wp.position)
    assert abs(pos_rms - 0.040) <= 0.005, pos_rms
    assert abs(window.values[-1, 2] - 1.0398) < 0.001
    assert rms_error(data.angular_velocity.window(wp.t + 5, wp.t + 15), np.zeros(3)) < 1e-3
    # hover needs ~543.3 rad/s per rotor at the simulated 1.54503 kg (reference 7.2), signed by direction
    m = data.motor_speeds.window(15, 20).values
    assert np.allclose(np.abs(m).mean(axis=0), 543.3, atol=0.5), np.abs(m).mean(axis=0)
    assert np.all(np.sign(m.mean(axis=0)) == [1, -1, 1, -1, 1, -1])
    # the bag holds what the evaluation scripts need
    flight_bag = FlightBag(bag)
    for t in (
        "ground_truth/pose",
        "ground_truth/twist",
        "motor_speed",
        "imu",
        "odometry_sensor1/odometry",
        "command/motor_speed",
        "command/trajectory",
        "wrench",
    ):
        assert f"firefly/{t}" in flight_bag.topics, flight_bag.topics
    assert flight_bag.topics["firefly/ground_truth/pose"] == "geometry_msgs/msg/PoseStamped"
    flight_bag.close()
    # rviz spins the propellers: each rotor joint turns at the signed rotor speed / rotorVelocitySlowdownSim (10)
    joint_omega = [imu["joints"][f"firefly/rotor_{i}_joint"] * 10 for i in range(6)]
    assert np.allclose(joint_omega, imu["omega"], rtol=0.01), (joint_omega, imu["omega"])
    # noise-free IMU in hover reads +g on z
    assert imu["gt_acc"][2] == pytest.approx(9.8, abs=1e-3) and abs(imu["gt_acc"][0]) < 1e-3

    out = subprocess.run(
        [
            "rosrun",
            "rotors_evaluation",
            "hovering_eval.py",
            "-b",
            str(bag),
            "--save_plots",
            "True",
            "--plot",
            "False",
            "--mav_name",
            "firefly",
            "--plot_dir",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
        env=ros.env,
        check=True,
    ).stdout
    assert "Position RMS error: 0.040 m" in out, out
    assert "Angular velocity RMS error: 0.000 rad/s" in out
    assert "No collisions occurred - good job!" in out
    assert (tmp_path / "position.png").stat().st_size > 10000


def test_matched_controller_parameters_remove_the_offset(ros: RosGraph, tmp_path: Path):
    params = tmp_path / "matched.yaml"
    params.write_text("mass: 1.54503\ngravity: 9.8\n")  # the simulated mass and world gravity
    bag, _, _, _ = fly(ros, f"extra_controller_params:={params}")
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench")
    wp = data.waypoints[0]
    window = data.position.window(wp.t + 5, wp.t + 15)
    assert rms_error(window, wp.position) < 0.005
    assert abs(window.values[-1, 2] - 1.0) < 1e-3


def test_rosbag_record_of_hovering_example_evaluates_unchanged(ros: RosGraph, tmp_path: Path):
    """As a new user does: the hovering example without the bag plugin, `rosbag record -a` beside it,
    then hovering_eval.py and waypoints_eval.py on that bag. rosbag record holds no
    ground_truth/twist (only the bag plugin writes it) and ground_truth/pose is an unstamped
    geometry_msgs/Pose: the scripts take ground_truth/odometry instead and say so."""
    bag = tmp_path / "recorded.bag"
    recorder = ros.start(["rosbag", "record", "-a", "-O", str(bag), "__name:=recorder"], "rosbag_record")
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "lockstep:=true", "real_time_factor:=5")
    try:
        wait_sim_time(ros, 21.0)
    finally:
        stop_launch(recorder)
        stop_launch(proc)
    assert bag.is_file(), Path(recorder.log_path).read_text()[-2000:]
    recorded = FlightBag(bag)
    assert "firefly/ground_truth/twist" not in recorded.topics
    assert recorded.topics["firefly/ground_truth/pose"] == "geometry_msgs/msg/Pose"
    recorded.close()
    hover = subprocess.run(
        ["rosrun", "rotors_evaluation", "hovering_eval.py", "-b", str(bag), "--mav_name", "firefly", "--plot", "False"],
        capture_output=True,
        text=True,
        env=ros.env,
    )
    print(hover.stdout, hover.stderr)
    assert hover.returncode == 0, hover.stderr
    assert "Position RMS error: 0.040 m" in hover.stdout
    assert "note: pose from 'firefly/ground_truth/odometry' (nav_msgs/msg/Odometry)" in hover.stderr
    assert "note: twist from 'firefly/ground_truth/odometry' (nav_msgs/msg/Odometry)" in hover.stderr
    waypoints = subprocess.run(
        ["rosrun", "rotors_evaluation", "waypoints_eval.py", "-b", str(bag), "--mav_name", "firefly", "--plot", "False"],
        capture_output=True,
        text=True,
        env=ros.env,
    )
    print(waypoints.stdout, waypoints.stderr)
    assert waypoints.returncode == 0, waypoints.stderr
    assert "waypoint" in waypoints.stdout.lower()
