"""Lockstep makes runs repeatable: two runs with the same seeds write identical bags, message for
message and bit for bit in the payloads."""
from pathlib import Path

from rosbags.rosbag1 import Reader

from conftest import REPO, RosGraph, send_hover_pose, stop_launch, wait_sim_time


def fly_once(ros: RosGraph, tag: str, *launch_args: str) -> Path:
    """Hovers at (0, 0, 1) for 6 s of sim time in lockstep; the bag it wrote."""
    proc = ros.start(["roslaunch", "-p", str(ros.port), str(REPO / "test/launch/lockstep_determinism.launch"),
                      f"log_file:={tag}", *launch_args], f"launch_{tag}")
    try:
        ready = ros.wait_for(lambda: "Successfully spawned" in Path(proc.log_path).read_text(), 60)
        assert ready, Path(proc.log_path).read_text()[-2000:]
        send_hover_pose(ros, then="""
            from std_srvs.srv import Empty
            rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()  # the set point was delivered while paused
        """)
        wait_sim_time(ros, 6.0)
        ros.run(["rosservice", "call", "/gazebo/pause_physics"])
    finally:
        stop_launch(proc)
    return next(Path(ros.env["ROS_HOME"]).glob(f"{tag}_*.bag"))


INPUT_TOPIC = "firefly/command/pose"  # the test's own input; rospy numbers its header.seq per publisher


def messages(bag: Path, until_s: float):
    """(topic, time, payload) of everything recorded; the input command without its header
    (seq and stamp are the publishing client's, not the simulation's)."""
    out = []
    with Reader(bag) as r:
        for conn, t, raw in r.messages():
            if t <= until_s * 1e9:
                payload = bytes(raw)
                if conn.topic == INPUT_TOPIC:  # Header = seq, sec, nsec, frame_id (uint32 length + bytes)
                    frame_len = int.from_bytes(payload[12:16], "little")
                    payload = payload[16 + frame_len:]
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


def test_two_lockstep_runs_write_identical_bags(ros: RosGraph):
    assert_identical_flights(messages(fly_once(ros, "run_a"), 5.5), messages(fly_once(ros, "run_b"), 5.5))
