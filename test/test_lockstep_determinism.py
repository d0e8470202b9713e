"""Lockstep makes runs repeatable: two runs with the same seeds write identical bags, message for
message and bit for bit in the payloads."""

import os
import struct
import subprocess
from pathlib import Path

import pytest
from rosbags.rosbag1 import Reader

from rotors_evaluation.bag_data import FlightBag
from support import RosGraph, stop_launch, wait_sim_time
from support.flights import SETPOINT_TOPICS, assert_identical_flights, fly_once, messages


def test_two_lockstep_runs_write_identical_bags(ros: RosGraph):
    assert_identical_flights(messages(fly_once(ros, "run_a"), 5.5), messages(fly_once(ros, "run_b"), 5.5))


def fly_hovering_example(ros: RosGraph, tag: str, cpu_hog: bool) -> Path:
    """The book's hovering example as a user starts it (its waypoint node included), seeded, in
    lockstep and as fast as possible, to 8 s of sim time (the waypoint is due at 5 s); with cpu_hog
    a busy process per core competes for the CPU the whole time. The bag it wrote."""
    hogs = [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(os.cpu_count() or 2)] if cpu_hog else []
    proc = ros.start(
        [
            "roslaunch",
            "-p",
            str(ros.port),
            "rotors_gazebo",
            "mav_hovering_example.launch",
            "gui:=false",
            "lockstep:=true",
            "real_time_factor:=0",
            "enable_logging:=true",
            f"log_file:={tag}",
            "random_seed:=42",
        ],
        f"launch_{tag}",
    )
    try:
        wait_sim_time(ros, 8.0)
        ros.run(["rosservice", "call", "/gazebo/pause_physics"])
    finally:
        stop_launch(proc)
        for hog in hogs:
            hog.kill()
            hog.wait()
    return next(Path(ros.env["ROS_HOME"]).glob(f"{tag}_*.bag"))


# the long tier, which runs one test at a time: in the quick tier's two workers its busy processes
# would compete with the other worker's tests, some of which assert on wall-clock behaviour
@pytest.mark.long
def test_hovering_example_repeats_bit_for_bit_beside_cpu_hog(ros: RosGraph):
    quiet, loaded = fly_hovering_example(ros, "quiet", False), fly_hovering_example(ros, "loaded", True)
    for bag in (quiet, loaded):  # lockstep waited for every step
        b = FlightBag(bag)
        try:
            assert b.unwaited("firefly") is None, b.unwaited("firefly")
        finally:
            b.close()
    a, b = (
        sorted((topic, None if topic in SETPOINT_TOPICS else t, payload) for topic, t, payload in messages(bag, 7.5))
        for bag in (quiet, loaded)
    )
    assert any(m[0] in SETPOINT_TOPICS for m in a)  # the waypoint node's set point is in the flight
    assert_identical_flights(a, b)
    # the MAV took off at the waypoint's due time: still on the ground before 5 s, climbing after
    with Reader(quiet) as r:
        z = [
            (t / 1e9, struct.unpack_from("<d", bytes(raw), len(bytes(raw)) - 40)[0])
            for conn, t, raw in r.messages()
            if conn.topic == "firefly/ground_truth/pose"
        ]
    assert max(h for t, h in z if t < 4.9) < 0.2 and max(h for t, h in z if 6.0 < t < 7.5) > 0.5


def test_python_module_hover_bit_for_bit_as_ros_in_lockstep(ros: RosGraph):
    # the same seed, world, vehicle, controller yaml and waypoint timing, once as ROS nodes in
    # lockstep and once in one Python loop (rotors_sim, no ROS master): the plugins' IMU, odometry
    # and rotor-speed messages are the same bytes, every motor command the same numbers, and the
    # ground-truth positions the same bits (the bag plugin writes its own PoseStamped of the link
    # pose, whose quaternion it converts itself: compared to 1e-15, not bitwise)
    import struct

    from mav_msgs.msg import Actuators

    from rotors_sim.examples import hovering_example

    bag = fly_hovering_example(ros, "ros_side", False)
    until_s = 7.5
    same_bytes = ("firefly/imu", "firefly/odometry_sensor1/odometry", "firefly/motor_speed")
    recorded = {topic: [] for topic in (*same_bytes, "firefly/ground_truth/pose", "firefly/command/motor_speed")}
    with Reader(bag) as r:
        for conn, t, raw in r.messages():
            if conn.topic in recorded and 0 < t <= until_s * 1e9:
                recorded[conn.topic].append((t / 1e9, bytes(raw)))
    flight = hovering_example(random_seed=42, duration_s=until_s, record=tuple("/" + t for t in (*same_bytes, "firefly/ground_truth/pose")))

    def ours(topic):
        return [payload for name, t, payload in flight.messages if name == "/" + topic]

    for topic in same_bytes:
        mine, theirs = ours(topic), [payload for t, payload in recorded[topic]]
        print(f"{topic}: ROS {len(theirs)} messages, Python {len(mine)}")
        assert len(theirs) > 500 and len(mine) == len(theirs)
        diff = [i for i, (a, b) in enumerate(zip(mine, theirs)) if a != b]
        assert not diff, f"{topic}: {len(diff)} of {len(theirs)} messages differ, first at index {diff[0]}"
    mine, theirs = ours("firefly/ground_truth/pose"), [p[-56:] for t, p in recorded["firefly/ground_truth/pose"]]
    assert len(mine) == len(theirs) > 500
    assert all(a[:24] == b[:24] for a, b in zip(mine, theirs))  # positions: the same bits
    worst_q = max(max(abs(x - y) for x, y in zip(struct.unpack("<4d", a[24:]), struct.unpack("<4d", b[24:]))) for a, b in zip(mine, theirs))
    assert worst_q < 1e-15
    theirs = [Actuators().deserialize(p).angular_velocities for t, p in recorded["firefly/command/motor_speed"]]
    mine = [tuple(speeds) for t, speeds in flight.commands if t <= until_s]
    print(
        f"motor commands: ROS {len(theirs)}, Python {len(mine)}; ground-truth quaternions within {worst_q:.1e}; "
        f"z at {until_s} s: {flight.position_W[-1][2]:.6f} m"
    )
    assert len(theirs) > 500 and abs(len(mine) - len(theirs)) <= 1
    diff = [i for i, (a, b) in enumerate(zip(mine, theirs)) if a != b]
    assert not diff, f"{len(diff)} motor commands differ, first at index {diff[0]}"
    assert max(max(s) for s in mine) > 400  # it flew
