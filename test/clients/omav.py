"""Client functions of test_omav.py."""

import math

import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from std_msgs.msg import Float32

from clients.waits import wait_for_subscriber


def sample(seconds):
    """Rows [x, y, z, roll deg, pitch deg] of the omav's ground truth over `seconds` of sim time."""
    m = rospy.wait_for_message("/omav/ground_truth/odometry", Odometry, timeout=30)
    t0, rows = m.header.stamp.to_sec(), []
    while m.header.stamp.to_sec() < t0 + seconds:
        p, q = m.pose.pose.position, m.pose.pose.orientation
        roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
        rows.append([p.x, p.y, p.z, math.degrees(roll), math.degrees(pitch)])
        m = rospy.wait_for_message("/omav/ground_truth/odometry", Odometry, timeout=30)
    return rows


def hover_then_roll_20_degrees() -> dict:
    """2 s of the hover; the set point (0, 0, 1) rolled 20 deg, and 5 s of it after 5 s; the six
    tilt motors' positions."""
    result = {}
    result["hover"] = sample(2.0)
    pub = rospy.Publisher("/omav/command/pose", PoseStamped, queue_size=1, latch=True)
    wait_for_subscriber(pub)
    cmd = PoseStamped()
    cmd.pose.position.z = 1.0
    cmd.pose.orientation.x, cmd.pose.orientation.w = math.sin(math.radians(10)), math.cos(math.radians(10))
    pub.publish(cmd)
    t = rospy.wait_for_message("/omav/ground_truth/odometry", Odometry, timeout=30).header.stamp.to_sec()
    while rospy.wait_for_message("/omav/ground_truth/odometry", Odometry, timeout=30).header.stamp.to_sec() < t + 5:
        pass
    result["tilted"] = sample(5.0)
    result["arms"] = [rospy.wait_for_message(f"/omav/tilt_motor_{i}/position", Float32, timeout=30).data for i in range(6)]
    return result
