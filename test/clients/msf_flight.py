"""Client functions of test_msf_flight.py."""

import time

import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from sensor_fusion_comm.srv import InitHeight, InitScale
from sensor_msgs.msg import Imu


def fly_through_band() -> dict:
    """After hovering at the origin: set points on command/pose into the band (x 1.0 at 30 s of sim
    time) and out again (x 2.2 2.5 s after the first was sent); the stamps they were sent at."""
    pub = rospy.Publisher("/firefly/command/pose", PoseStamped, queue_size=1, latch=True)

    def go(x, at):
        while rospy.Time.now().to_sec() < at:
            rospy.sleep(0.05)
        m = PoseStamped()
        m.header.stamp = rospy.Time.now()
        m.pose.position.x, m.pose.position.z, m.pose.orientation.w = x, 1.0, 1.0
        pub.publish(m)
        return m.header.stamp.to_sec()

    first = go(1.0, 30.0)
    return {"sent": [first, go(2.2, first + 2.5)]}


def refusals_and_nan_input() -> dict:
    """The estimator node /msf alone: a NaN IMU reading, initialize_msf_scale before any pose, a pose,
    initialize_msf_height below the minimum, initialize_msf_scale after the pose; the answers, and
    the first odometry after the next IMU reading (frames, stamp, position)."""
    rospy.wait_for_service("/msf/pose_sensor/initialize_msf_scale", timeout=20)
    imu_pub = rospy.Publisher("/msf_core/imu_state_input", Imu, queue_size=10)
    pose_pub = rospy.Publisher("/msf_updates/pose_input", PoseStamped, queue_size=10)
    deadline = time.monotonic() + 30
    while (imu_pub.get_num_connections() == 0 or pose_pub.get_num_connections() == 0) and time.monotonic() < deadline:
        time.sleep(0.05)  # until the estimator subscribes to both (30 s at most)

    def imu(t, az):
        m = Imu()
        m.header.stamp = rospy.Time(t)
        m.linear_acceleration.z = az
        imu_pub.publish(m)

    result = {}
    imu(1.0, float("nan"))
    time.sleep(0.5)
    init = rospy.ServiceProxy("/msf/pose_sensor/initialize_msf_scale", InitScale)
    height = rospy.ServiceProxy("/msf/pose_sensor/initialize_msf_height", InitHeight)
    result["init"] = init(1.0).result
    # a PoseStamped on pose_input (no covariance: pose_noise_meas_p/q), then initialise
    imu(1.0, 9.81)
    pose = PoseStamped()
    pose.header.stamp = rospy.Time(1.0)
    pose.pose.position.x, pose.pose.position.y, pose.pose.position.z = 1.0, 2.0, 0.5
    pose.pose.orientation.w = 1.0
    pose_pub.publish(pose)
    time.sleep(0.5)
    result["height"] = height(0.001).result
    result["init_after_pose"] = init(1.0).result
    sub_msgs = []
    _subscriber = rospy.Subscriber("/msf_core/odometry", Odometry, sub_msgs.append)  # held while waiting
    deadline = time.monotonic() + 30
    while _subscriber.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.05)  # until connected to the estimator's publisher (30 s at most)
    imu(1.01, 9.81)
    deadline = time.monotonic() + 5
    while not sub_msgs and time.monotonic() < deadline:
        time.sleep(0.05)
    o = sub_msgs[0]
    result["odom"] = [
        o.header.frame_id,
        o.child_frame_id,
        o.header.stamp.to_sec(),
        o.pose.pose.position.x,
        o.pose.pose.position.y,
        o.pose.pose.position.z,
    ]
    return result
