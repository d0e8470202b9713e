"""Client functions of test_planner_flight.py."""

import time

import rospy
from geometry_msgs.msg import PoseStamped

from clients.waits import wait_for_subscriber


def send_goal(x: float, y: float, z: float) -> dict:
    """The goal (x, y, z) in the world frame, latched on /firefly/goal once the planner listens."""
    pub = rospy.Publisher("/firefly/goal", PoseStamped, queue_size=1, latch=True)
    goal = PoseStamped()
    goal.header.frame_id = "world"
    goal.pose.position.x, goal.pose.position.y, goal.pose.position.z = x, y, z
    goal.pose.orientation.w = 1.0
    wait_for_subscriber(pub)
    pub.publish(goal)
    time.sleep(0.5)
    return {}
