"""Waypoints as MultiDOFJointTrajectory messages, the waypoint file format, and the small ROS
helpers the example nodes share (unpausing the simulator, waiting for a subscriber)."""

import math
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import rosgraph
import rospy
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Transform, Twist
from std_srvs.srv import Empty
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint


@dataclass(frozen=True)
class Waypoint:
    x: float  # [m]
    y: float  # [m]
    z: float  # [m]
    yaw_rad: float
    wait_time_s: float = 0.0  # how long this point is held (file format)


def trajectory_point(wp: Waypoint, time_from_start_s: float) -> MultiDOFJointTrajectoryPoint:
    t = Transform()
    t.translation.x, t.translation.y, t.translation.z = wp.x, wp.y, wp.z
    t.rotation.z, t.rotation.w = math.sin(wp.yaw_rad / 2.0), math.cos(wp.yaw_rad / 2.0)
    return MultiDOFJointTrajectoryPoint(
        transforms=[t], velocities=[Twist()], accelerations=[Twist()], time_from_start=rospy.Duration(time_from_start_s)
    )


def trajectory(waypoints: Sequence[Waypoint]) -> MultiDOFJointTrajectory:
    """Point i is released sum_{j<i} wait_time_j after the first (RotorS' waypoint file semantics)."""
    msg = MultiDOFJointTrajectory()
    msg.header.stamp = rospy.Time.now()
    msg.joint_names = ["base_link"]
    t = 0.0
    for wp in waypoints:
        msg.points.append(trajectory_point(wp, t))
        t += wp.wait_time_s
    return msg


def sampled_trajectory(flight) -> MultiDOFJointTrajectory:
    """A sampled flight (rotors_gazebo.flight_paths.Trajectory) as one trajectory: each point with its
    position, yaw, velocity, yaw rate and acceleration (the Lee controller's feed-forward), at its time."""
    msg = MultiDOFJointTrajectory()
    msg.joint_names = ["base_link"]
    for i in range(len(flight.t_s)):
        t = Transform()
        t.translation.x, t.translation.y, t.translation.z = (float(c) for c in flight.p_W[i])
        t.rotation.z, t.rotation.w = math.sin(flight.yaw[i] / 2.0), math.cos(flight.yaw[i] / 2.0)
        velocity, acceleration = Twist(), Twist()
        velocity.linear.x, velocity.linear.y, velocity.linear.z = (float(c) for c in flight.v_W[i])
        velocity.angular.z = float(flight.yaw_rate[i])
        acceleration.linear.x, acceleration.linear.y, acceleration.linear.z = (float(c) for c in flight.a_W[i])
        msg.points.append(
            MultiDOFJointTrajectoryPoint(
                transforms=[t], velocities=[velocity], accelerations=[acceleration], time_from_start=rospy.Duration(float(flight.t_s[i]))
            )
        )
    return msg


def read_waypoint_file(path: Path) -> list[Waypoint]:
    """Whitespace-separated 5-tuples: wait_time[s] x[m] y[m] z[m] yaw[deg]; stops at the first
    incomplete tuple, as RotorS."""
    values = Path(path).read_text().split()
    out = []
    for i in range(0, len(values) - 4, 5):
        wait, x, y, z, yaw_deg = (float(v) for v in values[i : i + 5])
        out.append(Waypoint(x, y, z, math.radians(yaw_deg), wait))
    return out


def wait_for_model(name: str, timeout_s: float = 10.0) -> bool:
    """Waits (wall clock) until /gazebo/get_model_state knows model `name`. False, with a warning
    naming the model, after `timeout_s`."""
    deadline = time.monotonic() + timeout_s
    while not rospy.is_shutdown() and time.monotonic() < deadline:
        try:
            rospy.wait_for_service("/gazebo/get_model_state", timeout=max(deadline - time.monotonic(), 0.1))
            if rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)(model_name=name).success:
                return True
        except (rospy.ROSException, rospy.ServiceException):
            pass
        time.sleep(0.1)
    rospy.logwarn("Model '%s' is not in the simulation after %.0f s; going on without it.", name, timeout_s)
    return False


def unpause_simulation(attempts: int = 12) -> bool:
    """Calls /gazebo/unpause_physics, retrying once a second (wall clock). In a namespace, first
    waits for the model of that name (RotorS spawns the MAV as its namespace), so that sim time does
    not run before the vehicle and its plugins (the bag recorder among them) exist."""
    model = rospy.get_namespace().strip("/")
    if model and "/" not in model:
        wait_for_model(model)
    for i in range(attempts):
        try:
            rospy.wait_for_service("/gazebo/unpause_physics", timeout=1.0)
            rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
            return True
        except (rospy.ROSException, rospy.ServiceException):
            rospy.loginfo("Wait for 1 second before trying to unpause Gazebo again.")
            time.sleep(1.0) if i + 1 < attempts else None
    return False


def registered_subscribers(topic: str) -> set[str]:
    """Nodes the master lists as subscribers of `topic` (resolved name)."""
    try:
        _, subscribers, _ = rosgraph.Master(rospy.get_name()).getSystemState()
    except (OSError, rosgraph.MasterException):
        return set()
    return next((set(nodes) for name, nodes in subscribers if name == topic), set())


def unconnected(pub: rospy.Publisher, registered: set[str]) -> set[str]:
    """The nodes of `registered` that have no connection to `pub` yet."""
    return registered - {c.endpoint_id for c in pub.impl.connections}


class SubscriberWatch:
    """Keeps the master's list of a topic's subscribers up to date in a background thread (wall
    clock, every `period_s`), so that waiting for them costs no master call at publishing time:
    with the simulator running faster than real time that call would cost sim time."""

    def __init__(self, pub: rospy.Publisher, period_s: float = 0.25):
        self.topic = pub.resolved_name
        self.registered: set[str] = registered_subscribers(self.topic)
        self._period_s = period_s
        threading.Thread(target=self._poll, daemon=True).start()

    def _poll(self) -> None:
        while not rospy.is_shutdown():
            time.sleep(self._period_s)
            self.registered = registered_subscribers(self.topic)


def wait_for_subscriber(
    pub: rospy.Publisher, announce: bool = True, watch: SubscriberWatch | None = None, others_timeout_s: float = 5.0
) -> bool:
    """Blocks (wall clock) until someone subscribes, so the one message is not lost (RotorS #358),
    then until every subscriber the master knows of is connected too (a bag recorder that registered
    beside the controller must not miss the waypoint); a registered node that does not connect within
    `others_timeout_s` is named and not waited for. Pass a SubscriberWatch made when the publisher
    was to keep the master out of this call."""
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():
        if announce:
            rospy.loginfo("There is no subscriber available, trying again in 1 second.")
        time.sleep(1.0)
    registered = watch.registered if watch else registered_subscribers(pub.resolved_name)
    deadline = time.monotonic() + others_timeout_s
    while not rospy.is_shutdown():
        missing = unconnected(pub, registered)
        if not missing:
            break
        if time.monotonic() > deadline:
            rospy.logwarn("%s: not waiting any longer for %s to connect", pub.resolved_name, ", ".join(sorted(missing)))
            break
        time.sleep(0.01)
        registered = watch.registered if watch else registered
    return not rospy.is_shutdown()


def publish_to_all(pub: rospy.Publisher, msg, linger_s: float = 3.0) -> None:
    """Publishes `msg` on a latched publisher and stays (wall clock, up to `linger_s`) until every
    subscriber the master lists now has connected and so has the message: a controller that
    registered after the last SubscriberWatch poll still gets it when it connects."""
    pub.publish(msg)
    deadline = time.monotonic() + linger_s
    missing: set[str] = set()
    while not rospy.is_shutdown() and time.monotonic() < deadline:
        missing = unconnected(pub, registered_subscribers(pub.resolved_name))
        if not missing:
            return
        time.sleep(0.05)
    if missing:
        rospy.logwarn(
            "%s: %s did not connect within %.0f s and may not have the message", pub.resolved_name, ", ".join(sorted(missing)), linger_s
        )
