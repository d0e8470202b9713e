"""RotorS on ROS 2 (the ros2 tier: make test-ros2): the ROS 2 front end (rotors_gazebo_compat/
rotors_ros2/rotors_ros2_sim.py) in a network namespace with only the loopback interface, and a client written with
rclpy (PyPI's Jazzy wheels) that finds it with ROS 2's own graph queries, receives odometry and IMU at
their rates, stamped on sim time and framed as on ROS 1, flies the hovering example's set point and
resets the simulation."""

import json
import subprocess

import pytest

from support import REPO

pytestmark = pytest.mark.ros2


def on_loopback_graph(script: str, timeout_s: float) -> subprocess.CompletedProcess:
    """`script` (bash) in a network namespace of its own with only the loopback interface up
    (unshare --net), in scripts/ros2_env.bash's environment: nothing of the graph reaches the
    machine's network, whatever the DDS settings."""
    probe = subprocess.run(["unshare", "--net", "true"], capture_output=True, text=True)
    assert probe.returncode == 0, f"unshare --net is not permitted here: {probe.stderr.strip()}"
    body = f"set -e; ip link set lo up; source {REPO}/scripts/ros2_env.bash; {script}"
    return subprocess.run(["unshare", "--net", "bash", "-c", body], capture_output=True, text=True, timeout=timeout_s)


def test_an_rclpy_client_flies_the_hovering_example_on_ros2(tmp_path):
    assert (REPO / "build" / "ros2-venv" / "bin" / "python").exists(), "no build/ros2-venv: run make ros2-setup"
    sim_log = tmp_path / "sim.log"
    # the client's waits share a budget of 240 s; the simulator gets 10 s to stop after SIGINT, then
    # SIGKILL: both fit in the 300 s this test gives the whole graph
    res = on_loopback_graph(
        f"python {REPO}/rotors_gazebo_compat/rotors_ros2/rotors_ros2_sim.py --mav firefly --seed 3 > {sim_log} 2>&1 & sim=$!; "
        f"status=0; python {REPO}/test/ros2_clients/hover_client.py 240 || status=$?; "
        "kill -INT $sim; for _ in $(seq 100); do kill -0 $sim 2>/dev/null || break; sleep 0.1; done; "
        "kill -KILL $sim 2>/dev/null || true; exit $status",
        timeout_s=300,
    )
    lines = [line for line in res.stdout.splitlines() if line.startswith("RESULT=")]
    assert lines, f"the rclpy client failed ({res.returncode}):\n{res.stdout[-3000:]}\n{res.stderr[-3000:]}\n{sim_log.read_text()[-3000:]}"
    r = json.loads(lines[0][len("RESULT=") :])
    print(json.dumps(r, indent=1))
    assert "gazebo" in r["nodes"]
    assert r["topics"]["/firefly/odometry_sensor1/odometry"] == ["nav_msgs/msg/Odometry"]
    assert r["topics"]["/firefly/imu"] == ["sensor_msgs/msg/Imu"]
    assert r["topics"]["/clock"] == ["rosgraph_msgs/msg/Clock"]
    assert {"/reset_simulation", "/reset_world", "/pause_physics", "/unpause_physics"} <= set(r["services"])
    # basic.world steps at 100 Hz and the hovering example's odometry and IMU publish every step
    assert r["odometry_hz"] == pytest.approx(100.0, rel=1e-6) and r["imu_hz"] == pytest.approx(100.0, rel=1e-6)
    assert r["odometry_gaps"] == 0 and r["imu_gaps"] == 0  # none lost on the way
    assert r["odometry_frames"] == ["world", "firefly/odometry_sensor1"] and r["imu_frame"] == "firefly/imu_link"
    assert abs(r["imu_z_at_rest"] - 9.8) < 0.5  # on the ground: the specific force is -g
    assert abs(r["sim_time_now_minus_clock"]) < 0.1  # the client's clock follows /clock (use_sim_time)
    # hovering at (0, 0, 1) 0.040 m high, as on ROS 1 (test_python_hovering_example_hovers_at_ros_offset)
    assert abs(r["z_offset_last_2_s"] - 0.040) < 0.005, r
    assert r["clock_after_reset"] < 1.0 and r["z_after_reset"] < 0.2
