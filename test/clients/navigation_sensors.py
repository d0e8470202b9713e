"""Client functions of test_navigation_sensors.py."""

import math
import time

import rospy
from geometry_msgs.msg import PoseStamped, TwistStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import FluidPressure, MagneticField, NavSatFix

from clients.waits import poll


def fly_and_log() -> dict:
    """Logs GPS, ground speed, magnetometer, barometer and ground-truth odometry (stamp first in each
    row) while the firefly flies to (6, -4, 3) turned 0.8 rad about z, for 8 s of sim time."""
    log = {k: [] for k in ("gps", "speed", "mag", "baro", "odom")}
    rospy.Subscriber(
        "/firefly/gps",
        NavSatFix,
        lambda m: log["gps"].append(
            [m.header.stamp.to_sec(), m.latitude, m.longitude, m.altitude, m.status.status, m.status.service, m.header.frame_id]
        ),
    )
    rospy.Subscriber(
        "/firefly/ground_speed",
        TwistStamped,
        lambda m: log["speed"].append([m.header.stamp.to_sec(), m.twist.linear.x, m.twist.linear.y, m.twist.linear.z]),
    )
    rospy.Subscriber(
        "/firefly/magnetic_field",
        MagneticField,
        lambda m: log["mag"].append([m.header.stamp.to_sec(), m.magnetic_field.x, m.magnetic_field.y, m.magnetic_field.z]),
    )
    rospy.Subscriber("/firefly/air_pressure", FluidPressure, lambda m: log["baro"].append([m.header.stamp.to_sec(), m.fluid_pressure]))
    rospy.Subscriber(
        "/firefly/ground_truth/odometry",
        Odometry,
        lambda m: log["odom"].append(
            [
                m.header.stamp.to_sec(),
                m.pose.pose.position.x,
                m.pose.pose.position.y,
                m.pose.pose.position.z,
                m.pose.pose.orientation.x,
                m.pose.pose.orientation.y,
                m.pose.pose.orientation.z,
                m.pose.pose.orientation.w,
                m.twist.twist.linear.x,
                m.twist.twist.linear.y,
                m.twist.twist.linear.z,
            ]
        ),
    )
    pub = rospy.Publisher("/firefly/command/pose", PoseStamped, queue_size=1, latch=True)
    poll(lambda: pub.get_num_connections() > 0, 30)  # the controller subscribing (latched: it would get the pose later too)
    cmd = PoseStamped()
    cmd.pose.position.x, cmd.pose.position.y, cmd.pose.position.z = 6.0, -4.0, 3.0
    cmd.pose.orientation.z, cmd.pose.orientation.w = math.sin(0.4), math.cos(0.4)
    pub.publish(cmd)
    t0 = rospy.Time.now().to_sec()
    while rospy.Time.now().to_sec() < t0 + 8.0:
        time.sleep(0.05)
    return dict(log)
