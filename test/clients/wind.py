"""Client functions of test_wind.py."""

import time

import numpy as np
import rospy
from geometry_msgs.msg import Vector3Stamped
from nav_msgs.msg import Odometry
from rotors_comm.msg import WindSpeed


def speed_pairs(count: int) -> dict:
    """`count` pairs of the next published wind speed and the next ground-truth odometry:
    [wind x, wind y, wind z, height]."""
    pairs = []
    for _ in range(count):
        w = rospy.wait_for_message("/firefly/wind_speed", WindSpeed, timeout=10)
        o = rospy.wait_for_message("/firefly/ground_truth/odometry", Odometry, timeout=10)
        pairs.append([w.velocity.x, w.velocity.y, w.velocity.z, o.pose.pose.position.z])
    return {"pairs": pairs}


def wind_from_a_topic() -> dict:
    """The wind (3, -1, 0) m/s latched on /firefly/wind_input, then a NaN one: the published wind's
    x and y after each."""
    pub = rospy.Publisher("/firefly/wind_input", WindSpeed, queue_size=1, latch=True)
    msg = WindSpeed()
    msg.velocity.x, msg.velocity.y = 3.0, -1.0
    pub.publish(msg)  # latched: the plugin gets it when it connects
    deadline = time.monotonic() + 30
    while True:  # until the plugin publishes the wind it took (30 s of wall time at most)
        w = rospy.wait_for_message("/firefly/wind_speed", WindSpeed, timeout=10)
        if (w.velocity.x, w.velocity.y) == (3.0, -1.0) or time.monotonic() > deadline:
            break
    bad = WindSpeed()
    bad.velocity.x = float("nan")
    pub.publish(bad)
    time.sleep(1.0)  # an observation window: the NaN must change nothing in it
    w2 = rospy.wait_for_message("/firefly/wind_speed", WindSpeed, timeout=10)
    return {"w": [w.velocity.x, w.velocity.y, w2.velocity.x, w2.velocity.y]}


def airspeed_against_wind_and_velocity() -> dict:
    """3 s of air_speed, ground-truth odometry and the wind plugin's wind, matched by stamp: the
    number of stamps in all three, the largest difference of air_speed from R_WB^T (v_wind - v),
    the last air_speed reading."""
    got = {"air": {}, "odom": {}, "wind": {}}

    def stamp(m):
        return m.header.stamp.to_nsec()

    rospy.Subscriber("/firefly/air_speed", Vector3Stamped, lambda m: got["air"].__setitem__(stamp(m), m))
    rospy.Subscriber("/firefly/ground_truth/odometry", Odometry, lambda m: got["odom"].__setitem__(stamp(m), m))
    rospy.Subscriber("/firefly/wind_speed", WindSpeed, lambda m: got["wind"].__setitem__(stamp(m), m))
    time.sleep(3.0)
    worst, n = 0.0, 0
    for t, air in list(got["air"].items()):
        if t not in got["odom"] or t not in got["wind"]:
            continue
        o, w = got["odom"][t].pose.pose, got["wind"][t].velocity
        q = o.orientation
        R = np.array(
            [
                [1 - 2 * (q.y**2 + q.z**2), 2 * (q.x * q.y - q.w * q.z), 2 * (q.x * q.z + q.w * q.y)],
                [2 * (q.x * q.y + q.w * q.z), 1 - 2 * (q.x**2 + q.z**2), 2 * (q.y * q.z - q.w * q.x)],
                [2 * (q.x * q.z - q.w * q.y), 2 * (q.y * q.z + q.w * q.x), 1 - 2 * (q.x**2 + q.y**2)],
            ]
        )
        # odometry's twist is in the body frame (RotorS' odometry); the world velocity is R v_B
        tw = got["odom"][t].twist.twist.linear
        v_W = R @ np.array([tw.x, tw.y, tw.z])
        expected = R.T @ (np.array([w.x, w.y, w.z]) - v_W)
        worst = max(worst, float(np.abs(expected - np.array([air.vector.x, air.vector.y, air.vector.z])).max()))
        n += 1
    result = {}
    result["n"] = n
    result["worst"] = worst
    last = got["air"][max(got["air"])].vector
    result["last"] = [last.x, last.y, last.z]
    return result
