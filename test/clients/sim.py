"""The simulation's clock and the firefly's hover set point: client functions the tests share
(support.wait_sim_time and send_hover_pose among them)."""

import time

import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from clients import call
from clients.waits import wait_for_subscriber


def wait_sim_time(t_s: float, timeout_s: float) -> dict:
    """Blocks until /clock reaches t_s (exits with one line after timeout_s of wall time); the sim
    time seen."""
    deadline = time.monotonic() + timeout_s
    t = 0.0
    while t < t_s:
        if time.monotonic() > deadline:
            raise SystemExit(f"sim time stuck at {t:.2f} s")
        try:
            t = rospy.wait_for_message("/clock", Clock, timeout=5).clock.to_sec()
        except rospy.ROSException:
            pass
    return {"t": t}


def clock_now(timeout_s: float | None = None) -> dict:
    """The sim time of the next /clock message (waiting for it at most timeout_s, or for ever)."""
    return {"t": rospy.wait_for_message("/clock", Clock, timeout=timeout_s).clock.to_sec()}


def send_hover_pose(then: str = "", then_kwargs: dict | None = None) -> dict:
    """Sends the set point (0, 0, 1) latched on /firefly/command/pose once the controller listens,
    then calls the client function `then` ("clients.module:name") with then_kwargs while the
    latched message lives; what it returned ({} without one)."""
    pub = rospy.Publisher("/firefly/command/pose", PoseStamped, queue_size=1, latch=True)
    wait_for_subscriber(pub)  # the controller is up and listens to poses
    cmd = PoseStamped()
    cmd.pose.position.z = 1.0
    cmd.pose.orientation.w = 1.0
    pub.publish(cmd)
    time.sleep(1.0)
    return call(then, then_kwargs or {}) if then else {}


def unpause_physics() -> dict:
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    return {}


def ground_truth(ns: str) -> dict:
    """The ground-truth position and orientation of the MAV in namespace ns."""
    m = rospy.wait_for_message(f"/{ns}/ground_truth/odometry", Odometry, timeout=20)
    p, q = m.pose.pose.position, m.pose.pose.orientation
    return dict(x=p.x, y=p.y, z=p.z, qx=q.x, qy=q.y, qz=q.z, qw=q.w)
