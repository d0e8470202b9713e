"""The ROS 2 closed loop's real-time factor, for `make bench` (run in scripts/ros2_env.bash's
environment): the ROS 2 front end (rotors_ros2_sim.py, as fast as possible, Lee in the world's step
loop) with an rclpy node that sends the hovering example's set point and subscribes to the
odometry, IMU and ground truth as a controller and a recorder would; sim seconds per wall second
from sim time `begin` to `end` s. Prints one JSON line.
    python scripts/ros2_rtf.py [begin_s] [end_s]"""

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import rclpy
from geometry_msgs.msg import Transform
from nav_msgs.msg import Odometry
from rclpy.parameter import Parameter
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

REPO = Path(__file__).resolve().parents[1]
begin_s, end_s = (float(sys.argv[1]), float(sys.argv[2])) if len(sys.argv) > 2 else (5.0, 105.0)
sim = subprocess.Popen(
    [sys.executable, str(REPO / "rotors_gazebo_compat" / "rotors_ros2" / "rotors_ros2_sim.py"), "--real-time-factor", "0", "--paused"],
    stdout=subprocess.DEVNULL,
    stderr=subprocess.DEVNULL,
)
rclpy.init()
node = rclpy.create_node("rtf_watch", parameter_overrides=[Parameter("use_sim_time", value=True)])
clock, counts = {"t": 0.0}, {"odometry": 0, "imu": 0, "ground_truth": 0}
node.create_subscription(Clock, "/clock", lambda m: clock.update(t=m.clock.sec + m.clock.nanosec * 1e-9), 10)
for key, msg_type, topic in (
    ("odometry", Odometry, "/firefly/odometry_sensor1/odometry"),
    ("ground_truth", Odometry, "/firefly/ground_truth/odometry"),
    ("imu", Imu, "/firefly/imu"),
):
    node.create_subscription(msg_type, topic, lambda m, k=key: counts.__setitem__(k, counts[k] + 1), 100)
pub = node.create_publisher(MultiDOFJointTrajectory, "/firefly/command/trajectory", 10)
deadline = time.monotonic() + 600
marks = {}
try:
    # the simulator starts paused: it runs once this node listens
    while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
    point = MultiDOFJointTrajectoryPoint(transforms=[Transform()])
    point.transforms[0].translation.z, point.transforms[0].rotation.w = 1.0, 1.0
    pub.publish(MultiDOFJointTrajectory(points=[point]))
    unpause = node.create_client(Empty, "/unpause_physics")
    while not unpause.service_is_ready() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
    unpause.call_async(Empty.Request())  # from here the world runs
    while clock["t"] < end_s and time.monotonic() < deadline and sim.poll() is None:
        rclpy.spin_once(node, timeout_sec=0.05)
        for name, t in (("begin", begin_s), ("end", end_s)):
            if name not in marks and clock["t"] >= t:
                marks[name] = (time.monotonic(), clock["t"])
finally:
    sim.send_signal(signal.SIGINT)
    try:
        sim.wait(timeout=30)
    except subprocess.TimeoutExpired:
        sim.kill()
if "end" not in marks:
    sys.exit(f"ros2_rtf: sim time reached only {clock['t']:.1f} s")
(w0, t0), (w1, t1) = marks["begin"], marks["end"]
print(json.dumps({"real_time_factor": (t1 - t0) / (w1 - w0), "received": counts}))
