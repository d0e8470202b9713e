"""Client functions of test_hil_interface.py."""

import time

import rospy
from mav_msgs.msg import Actuators


def normalized_controls() -> dict:
    """The last Actuators.normalized on /techpod/command/motor_speed within 4 s (None without one)."""
    got = []
    rospy.Subscriber("/techpod/command/motor_speed", Actuators, lambda m: got.append(list(m.normalized)))
    time.sleep(4.0)
    return {"normalized": got[-1] if got else None}
