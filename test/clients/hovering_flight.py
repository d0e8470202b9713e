"""Client functions of test_hovering_flight.py."""

import rospy
from mav_msgs.msg import Actuators
from sensor_msgs.msg import Imu, JointState


def imu_joints_and_rotor_speeds() -> dict:
    """The ground-truth IMU's acceleration, the joint velocities by name, the rotor speeds."""
    result = {}
    m = rospy.wait_for_message("/firefly/ground_truth/imu", Imu, timeout=10)
    result["gt_acc"] = [m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z]
    js = rospy.wait_for_message("/firefly/joint_states", JointState, timeout=10)
    result["joints"] = dict(zip(js.name, js.velocity))
    result["omega"] = list(rospy.wait_for_message("/firefly/motor_speed", Actuators, timeout=10).angular_velocities)
    return result
