"""Flights the tests fly through roslaunch and read back from their bags: logged flights, ground
truth, RotorS' evaluation scripts, contacts, and two flights compared message for message."""

import subprocess
import sys
from pathlib import Path

from rosbags.rosbag1 import Reader

import clients.sim
from rotors_evaluation.bag_data import FlightBag, load_flight
from support import REPO, RosGraph, launch, send_hover_pose, stop_launch, wait_sim_time

INPUT_TOPIC = "firefly/command/pose"  # the test's own input; rospy numbers its header.seq per publisher

SETPOINT_TOPICS = {"firefly/command/trajectory"}  # recorded when they arrive, which may be before or after unpausing


def lcp_errors(log: Path) -> int:
    return sum("LCP internal error" in line for line in log.read_text(errors="replace").splitlines())


def ground_truth(ros: RosGraph, ns: str) -> dict:
    return ros.run_client(clients.sim.ground_truth, ns=ns)


EVAL = REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "scripts"


def contacts_with(bag: Path, mav: str, other: str, after_s: float) -> list:
    b = FlightBag(bag)
    try:
        return [t_ns * 1e-9 for msg, _, t_ns in b.messages(f"{mav}/wrench") if other in msg.header.frame_id and t_ns * 1e-9 > after_s]
    finally:
        b.close()


def fly_logged(ros: RosGraph, launch_file: str, until_s: float, *args: str):
    """A firefly launch with logging in lockstep, as fast as possible, until `until_s` of sim time;
    asserts that no LCP error was printed and returns the bag and its flight data."""
    proc = launch(ros, "rotors_gazebo", launch_file, "enable_logging:=true", "lockstep:=true", "real_time_factor:=0", *args)
    try:
        wait_sim_time(ros, until_s)
    finally:
        stop_launch(proc)
    assert lcp_errors(Path(proc.log_path)) == 0
    bag = next(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    return bag, load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench")


def evaluate(script: str, bag: Path, *args: str) -> str:
    res = subprocess.run(
        [sys.executable, str(EVAL / script), "-b", str(bag), "--mav_name", "firefly", *args], capture_output=True, text=True
    )
    print(res.stdout)
    assert res.returncode == 0, res.stderr
    return res.stdout


def fly_once(ros: RosGraph, tag: str, *launch_args: str) -> Path:
    """Hovers at (0, 0, 1) for 6 s of sim time in lockstep; the bag it wrote."""
    proc = ros.start(
        ["roslaunch", "-p", str(ros.port), str(REPO / "test/launch/lockstep_determinism.launch"), f"log_file:={tag}", *launch_args],
        f"launch_{tag}",
    )
    try:
        ready = ros.wait_for(lambda: "Successfully spawned" in Path(proc.log_path).read_text(), 60)
        assert ready, Path(proc.log_path).read_text()[-2000:]
        send_hover_pose(ros, then=clients.sim.unpause_physics)  # the set point was delivered while paused
        wait_sim_time(ros, 6.0)
        ros.run(["rosservice", "call", "/gazebo/pause_physics"])
    finally:
        stop_launch(proc)
    return next(Path(ros.env["ROS_HOME"]).glob(f"{tag}_*.bag"))


def messages(bag: Path, until_s: float):
    """(topic, time, payload) of everything the flight recorded (not the robot description the bag
    plugin writes first: it names the run's bag file); the input command and the waypoint node's set
    point without their headers (seq and stamp are the publishing node's, which is not a lockstep
    participant: it stamps with the sim time it has seen when it wakes, which a busy machine can
    delay by a step; the Lee controller's due time, and so the flight, does not depend on it)."""
    out = []
    with Reader(bag) as r:
        for conn, t, raw in r.messages():
            if t <= until_s * 1e9 and not conn.topic.endswith("robot_description"):
                payload = bytes(raw)
                if conn.topic == INPUT_TOPIC or conn.topic in SETPOINT_TOPICS:  # Header = seq, sec, nsec, frame_id (uint32 length + bytes)
                    frame_len = int.from_bytes(payload[12:16], "little")
                    payload = payload[16 + frame_len :]
                out.append((conn.topic, t, payload))
    return sorted(out)


def assert_identical_flights(a, b) -> None:
    """Two message lists of fly_once flights: a real flight's topics, the same messages bit for bit."""
    assert len(a) > 3000
    topics = {m[0] for m in a}
    assert {"firefly/imu", "firefly/command/motor_speed", "firefly/ground_truth/pose"} <= topics
    assert len(a) == len(b)
    diff = [i for i, (x, y) in enumerate(zip(a, b)) if x != y]
    assert not diff, f"{len(diff)} messages differ, first: {a[diff[0]][:2]} vs {b[diff[0]][:2]}"
