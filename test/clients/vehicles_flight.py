"""Client functions of test_vehicles_flight.py (its ground_truth: clients.sim)."""

import rospy
from mav_msgs.msg import Actuators
from nav_msgs.msg import Odometry

from clients.waits import wait_for_subscriber


def bad_motor_commands() -> dict:
    """A valid motor command (600 rad/s on each of the firefly's six rotors), then three bad ones
    (three speeds, a NaN, a negative speed): how far the MAV climbs in the 1 s after."""
    pub = rospy.Publisher("/firefly/command/motor_speed", Actuators, queue_size=10)
    wait_for_subscriber(pub)

    def z():
        return rospy.wait_for_message("/firefly/ground_truth/odometry", Odometry).pose.pose.position.z

    pub.publish(Actuators(angular_velocities=[600.0] * 6))  # valid: take off
    rospy.sleep(1.0)
    for bad in ([1.0, 2.0, 3.0], [600.0] * 5 + [float("nan")], [600.0] * 5 + [-1.0]):
        pub.publish(Actuators(angular_velocities=bad))
        rospy.sleep(0.2)
    z0 = z()
    rospy.sleep(1.0)
    return {"climb": z() - z0}  # still climbing on the valid command
