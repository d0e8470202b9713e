"""Client functions of test_gimbal.py."""

import math
import time

import rospy
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64

from clients.waits import wait_for_subscriber


def pitch_and_roll_beyond_the_joints() -> dict:
    """Latches 3.0 rad on the gimbal's pitch and roll commands (beyond both joints' limits); once the
    joints stand at their limits, the gimbal's yaw, roll and pitch status and the body's orientation q_WB."""
    pub = rospy.Publisher("/firefly/gimbal_pitch_cmd", Float64, queue_size=1, latch=True)
    wait_for_subscriber(pub)
    pub.publish(Float64(3.0))  # beyond the pitch joint's 90 deg: clamped
    roll = rospy.Publisher("/firefly/gimbal_roll_cmd", Float64, queue_size=1, latch=True)
    wait_for_subscriber(roll)
    roll.publish(Float64(3.0))  # beyond the roll joint's 45 deg: clamped
    result = {}

    def status(axis):
        return rospy.wait_for_message(f"/firefly/gimbal_{axis}_status", Float64, timeout=30).data

    # until roll and pitch stop at their joints' limits (pi/4, pi/2: the test checks how closely),
    # 60 s of wall time at most
    deadline = time.monotonic() + 60
    while abs(status("roll") - math.pi / 4) > 5e-3 or abs(status("pitch") - math.pi / 2) > 5e-3:
        if time.monotonic() > deadline:
            break
        time.sleep(0.1)
    for axis in ("yaw", "roll", "pitch"):
        result[axis] = status(axis)
    q = rospy.wait_for_message("/firefly/ground_truth/odometry", Odometry, timeout=30).pose.pose.orientation
    result["q_WB"] = [q.x, q.y, q.z, q.w]
    return result
