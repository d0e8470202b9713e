"""Client functions of test_sensor_plugins.py."""

import time

import numpy as np
import rospy
from gazebo_msgs.msg import ModelStates
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from rotors_comm.msg import WindSpeed
from sensor_msgs.msg import Image, Imu, PointCloud2
from std_srvs.srv import Empty


def odometry_counts_and_imu() -> dict:
    """Odometry messages of the boxes 'white' and 'black' in 2 s, and the mean of the last 50 IMU
    z accelerations of 'white'."""
    counts = {"white": 0, "black": 0}
    _subscribers = [
        rospy.Subscriber(f"/{n}/odometry", Odometry, lambda m, n=n: counts.__setitem__(n, counts[n] + 1)) for n in counts
    ]  # held while counting
    imu = []
    _sub_imu = rospy.Subscriber("/white/imu", Imu, lambda m: imu.append(m.linear_acceleration.z))  # held too
    time.sleep(2.0)
    result = dict(counts)
    result["imu_z"] = sum(imu[-50:]) / max(len(imu[-50:]), 1)
    return result


def wind_on_a_falling_kite() -> dict:
    """Unpauses, reads the kite's published wind speed, pauses once the clock passes 1 s: the wind's
    y, the sim time and the kite's y then."""
    result = {}
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    speed = rospy.wait_for_message("/kite/wind_speed", WindSpeed, timeout=10)
    result["wind_y"] = speed.velocity.y
    while rospy.wait_for_message("/clock", Clock).clock.to_sec() < 1.0:
        pass
    rospy.ServiceProxy("/gazebo/pause_physics", Empty)()
    t = rospy.wait_for_message("/clock", Clock).clock.to_sec()
    m = rospy.wait_for_message("/gazebo/model_states", ModelStates)
    result["t"] = t
    result["y"] = m.pose[m.name.index("kite")].position.y
    return result


def depth_cameras() -> dict:
    """The rig's exact depth image (centre patch: min, max, encoding, frame), 8 noisy ones (centre
    patch: mean, std) and the size of the noisy camera's point cloud."""

    def centre(topic, n):
        out = []
        for _ in range(n):
            m = rospy.wait_for_message(topic, Image, timeout=30)
            d = np.frombuffer(m.data, dtype=np.float32).reshape(m.height, m.width)
            out.append(d[50:70, 70:90].ravel())
        return np.concatenate(out), m

    exact, m = centre("/rig/exact/depth/image_raw", 1)
    noisy, _ = centre("/rig/kinect/depth/image_raw", 8)
    result = dict(
        exact_min=float(exact.min()),
        exact_max=float(exact.max()),
        encoding=m.encoding,
        frame=m.header.frame_id,
        noisy_mean=float(noisy.mean()),
        noisy_std=float(noisy.std()),
    )
    cloud = rospy.wait_for_message("/rig/kinect/points", PointCloud2, timeout=30)
    result["cloud"] = [cloud.width, cloud.height]
    return result
