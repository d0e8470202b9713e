"""Client functions of test_visual_odometry.py."""

import json
import math
import time

import rospy
from geometry_msgs.msg import Transform, Twist
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

from clients.waits import wait_for_subscriber


def send_trajectory(points_file: str, due_s: float) -> dict:
    """The path of points_file (JSON rows: p, v, a, yaw, rate, t) as one MultiDOFJointTrajectory
    stamped due_s, latched on /firefly/command/trajectory once the controller and the hovering
    example listen."""
    pub = rospy.Publisher("/firefly/command/trajectory", MultiDOFJointTrajectory, queue_size=1, latch=True)
    wait_for_subscriber(pub, count=2)  # the controller and the hovering example's latch
    msg = MultiDOFJointTrajectory()
    msg.header.stamp = rospy.Time.from_sec(due_s)
    for q in json.loads(open(points_file).read()):
        point = MultiDOFJointTrajectoryPoint()
        tf = Transform()
        tf.translation.x, tf.translation.y, tf.translation.z = q["p"]
        tf.rotation.z, tf.rotation.w = math.sin(q["yaw"] / 2), math.cos(q["yaw"] / 2)
        velocity, acceleration = Twist(), Twist()
        velocity.linear.x, velocity.linear.y, velocity.linear.z = q["v"]
        velocity.angular.z = q["rate"]
        acceleration.linear.x, acceleration.linear.y, acceleration.linear.z = q["a"]
        point.transforms, point.velocities, point.accelerations = [tf], [velocity], [acceleration]
        point.time_from_start = rospy.Duration.from_sec(q["t"])
        msg.points.append(point)
    pub.publish(msg)
    time.sleep(2.0)
    return {}
