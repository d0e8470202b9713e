"""Client functions of test_autopilot_launch.py."""

import time

import rospy
from geometry_msgs.msg import Pose
from sensor_msgs.msg import Joy


def betaflight_rc_climb(log_path: str) -> dict:
    """Once the launch log (log_path) says the firmware answers (60 s wall at most): RC on /iris/rc
    (sensor_msgs/Joy) held for spans of sim time, the firmware's clock: disarmed while it calibrates,
    armed at idle, a climb at 1850 us, disarmed. The highest ground-truth z of the climb."""
    # the launch unpauses the world once the firmware is up (at most 60 s wall)
    deadline = time.monotonic() + 60
    while "Betaflight answers" not in open(log_path, errors="replace").read():
        if time.monotonic() > deadline:
            break
        time.sleep(0.2)
    pub = rospy.Publisher("/iris/rc", Joy, queue_size=1)
    z = {"max": 0.0}

    def on_pose(msg):
        z["max"] = max(z["max"], msg.position.z)

    rospy.Subscriber("/iris/ground_truth/pose", Pose, on_pose)

    def sticks(throttle, armed, seconds):  # for `seconds` of sim time: the firmware's clock
        end = rospy.get_time() + seconds
        wall_deadline = time.monotonic() + 10 * seconds + 30
        while rospy.get_time() < end and time.monotonic() < wall_deadline:
            pub.publish(Joy(axes=[0.0, 0.0, throttle, 0.0, 1.0 if armed else -1.0, 0.6]))
            time.sleep(0.02)

    result = {}
    sticks(-1.0, False, 7.0)  # the firmware calibrates its gyro and leaves its boot grace (sim time)
    sticks(-1.0, True, 2.0)  # armed at idle
    sticks(0.7, True, 2.0)  # 1850 us: climb
    result["z_max"] = z["max"]
    sticks(-1.0, False, 1.0)
    return result
