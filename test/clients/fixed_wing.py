"""Client functions of test_fixed_wing.py."""

import queue
import time

import rospy
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from mav_msgs.msg import RollPitchYawrateThrust
from nav_msgs.msg import Odometry


def joystick_flight_from_trim(pitch: float, thrust: float, qy: float, qw: float, v_trim: float) -> dict:
    """Latches the trimmed stick command (pitch = the elevator's normalized trim, thrust = the trim
    throttle) on /techpod/command/roll_pitch_yawrate_thrust; once the plugin listens and a second of
    sim time has passed, puts the techpod at the trim state (60 m high, orientation (0, qy, 0, qw),
    v_trim forward) with /gazebo/set_model_state and follows it for 10 s of sim time. Whether the
    reset succeeded, the height after the reset and 10 s later, and the distance flown and forward
    speed then.

    Nothing here waits on the flight before the reset: this process may start after the untrimmed
    launch has already glided to the ground (sim time runs 5 x wall time), so every wait is bounded
    by wall time or sim time and ends in an error that says what did not happen."""
    pub = rospy.Publisher("/techpod/command/roll_pitch_yawrate_thrust", RollPitchYawrateThrust, queue_size=1, latch=True)
    cmd = RollPitchYawrateThrust()
    cmd.pitch, cmd.thrust.x = pitch, thrust
    pub.publish(cmd)

    # one subscriber for the whole flight, every message queued: a new subscription per message (as
    # rospy.wait_for_message makes) misses the messages while it connects, at 5 x real time long
    # enough for the techpod to fly past the trim state's first metres before one is seen
    messages: queue.Queue = queue.Queue()
    rospy.Subscriber("/techpod/ground_truth/odometry", Odometry, messages.put, queue_size=None)

    def odometry():
        try:
            return messages.get(timeout=60)
        except queue.Empty:
            raise RuntimeError("no /techpod/ground_truth/odometry within 60 s of wall time") from None

    deadline = time.monotonic() + 60.0
    while pub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            raise RuntimeError("the fixed-wing plugin did not subscribe to the command topic within 60 s")
        time.sleep(0.05)
    m = odometry()
    connected = m.header.stamp.to_sec()
    while m.header.stamp.to_sec() < connected + 1.0:  # the latched command has reached the plugin
        m = odometry()
    state = ModelState(model_name="techpod")
    state.pose.position.z = 60.0
    state.pose.orientation.y, state.pose.orientation.w = qy, qw
    state.twist.linear.x = v_trim
    rospy.wait_for_service("/gazebo/set_model_state", timeout=30)
    while not messages.empty():  # what came before the reset (the reset's own step follows)
        messages.get_nowait()
    reply = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(state)
    if not reply.success:
        raise RuntimeError(f"/gazebo/set_model_state refused the trim state: {reply.status_message}")
    first = odometry()
    before = first.header.stamp.to_sec()
    while first.pose.pose.position.x > 5.0 or abs(first.pose.pose.position.z - 60.0) > 1.0:
        if first.header.stamp.to_sec() > before + 5.0:
            raise RuntimeError("5 s of sim time after /gazebo/set_model_state, the techpod is not at the trim state")
        first = odometry()
    m = first
    while m.header.stamp.to_sec() < first.header.stamp.to_sec() + 10.0:
        m = odometry()
    return dict(
        reset=reply.success,
        z0=first.pose.pose.position.z,
        z=m.pose.pose.position.z,
        x=m.pose.pose.position.x,
        vx=m.twist.twist.linear.x,
    )
