"""Client functions of test_waypoint_file_flight.py."""

import time

import rospy
from geometry_msgs.msg import Transform
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

from clients.waits import wait_for_subscriber


def bad_trajectories() -> dict:
    """Three bad messages on /firefly/command/trajectory: no points, a NaN position, a quaternion of
    norm 2."""
    pub = rospy.Publisher("/firefly/command/trajectory", MultiDOFJointTrajectory, queue_size=10)
    wait_for_subscriber(pub)
    pub.publish(MultiDOFJointTrajectory())  # no points
    time.sleep(0.3)  # the controller keeps only the latest command (queue 1)
    t = Transform()
    t.translation.x = float("nan")
    t.rotation.w = 1.0
    pub.publish(MultiDOFJointTrajectory(points=[MultiDOFJointTrajectoryPoint(transforms=[t])]))
    time.sleep(0.3)
    t = Transform()
    t.translation.x = 5.0
    t.rotation.w = 2.0  # not a unit quaternion
    pub.publish(MultiDOFJointTrajectory(points=[MultiDOFJointTrajectoryPoint(transforms=[t])]))
    time.sleep(1.0)
    return {}
