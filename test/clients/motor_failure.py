"""Client functions of test_motor_failure.py."""

import rospy
from rotors_comm.srv import SetMotorFailure


def failure_requests() -> dict:
    """Three set_motor_failure calls as soon as the service is up: motor 6 (not a motor), a speed
    factor of 1.5, and motor 1 failed from 40 s, announced 0.2 s later; [success, message] of each
    and the sim time after them."""
    rospy.wait_for_service("/firefly/set_motor_failure", timeout=60)
    fail = rospy.ServiceProxy("/firefly/set_motor_failure", SetMotorFailure)
    result = {}
    result["calls"] = [[r.success, r.message] for r in (fail(6, 0.0, 0.0, 0.0), fail(1, 1.5, 0.0, 0.0), fail(1, 0.0, 40.0, 0.2))]
    result["t"] = rospy.Time.now().to_sec()
    return result
