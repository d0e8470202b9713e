"""Client functions of test_fixed_wing.py."""

import rospy
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from mav_msgs.msg import RollPitchYawrateThrust
from nav_msgs.msg import Odometry


def joystick_flight_from_trim(pitch: float, thrust: float, qy: float, qw: float, v_trim: float) -> dict:
    """Latches the trimmed stick command (pitch = the elevator's normalized trim, thrust = the trim
    throttle) on /techpod/command/roll_pitch_yawrate_thrust; once the techpod is launched, the plugin
    listens and a second of flight has passed, puts it back at the trim state (60 m high, orientation
    (0, qy, 0, qw), v_trim forward) with /gazebo/set_model_state and follows it for 10 s of sim time.
    The launch speed, whether the reset succeeded, the height after the reset and 10 s later, and
    the distance flown and forward speed then."""
    pub = rospy.Publisher("/techpod/command/roll_pitch_yawrate_thrust", RollPitchYawrateThrust, queue_size=1, latch=True)
    cmd = RollPitchYawrateThrust()
    cmd.pitch, cmd.thrust.x = pitch, thrust
    pub.publish(cmd)

    def odometry():
        return rospy.wait_for_message("/techpod/ground_truth/odometry", Odometry, timeout=120)

    m = odometry()
    while m.twist.twist.linear.x < 10.0:  # launched
        m = odometry()
    launched = m
    while pub.get_num_connections() == 0 or m.header.stamp.to_sec() < launched.header.stamp.to_sec() + 1.0:
        m = odometry()
    state = ModelState(model_name="techpod")
    state.pose.position.z = 60.0
    state.pose.orientation.y, state.pose.orientation.w = qy, qw
    state.twist.linear.x = v_trim
    rospy.wait_for_service("/gazebo/set_model_state", timeout=30)
    reply = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(state)
    first = odometry()
    while first.pose.pose.position.x > 5.0:  # the first message after the reset
        first = odometry()
    m = first
    while m.header.stamp.to_sec() < first.header.stamp.to_sec() + 10.0:
        m = odometry()
    return dict(
        launched_vx=launched.twist.twist.linear.x,
        reset=reply.success,
        z0=first.pose.pose.position.z,
        z=m.pose.pose.position.z,
        x=m.pose.pose.position.x,
        vx=m.twist.twist.linear.x,
    )
