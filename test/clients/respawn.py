"""Client functions of test_respawn.py."""

import time

import rospy
from mav_msgs.msg import Actuators

from clients.waits import wait_for_subscriber


def spin_motors(n: int) -> dict:
    """Commands n rotors of /mav at 300 rad/s until all turn at more than 299 rad/s (20 s at most);
    the rotor speeds last read."""
    pub = rospy.Publisher("/mav/command/motor_speed", Actuators, queue_size=1)
    wait_for_subscriber(pub)
    speeds = []
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        pub.publish(Actuators(angular_velocities=[300.0] * n))
        m = rospy.wait_for_message("/mav/motor_speed", Actuators, timeout=10)
        speeds = [abs(w) for w in m.angular_velocities]
        if speeds and min(speeds) > 299.0:
            break
    return {"speeds": speeds}
