"""Client functions of test_laser_flight.py."""

import time

import numpy as np
import rospy
from nav_msgs.msg import Odometry
from sensor_msgs import point_cloud2
from sensor_msgs.msg import LaserScan, PointCloud2, Range

from clients.waits import wait_until


def rotation(q):  # unit quaternion -> R_WB
    w, x, y, z = q.w, q.x, q.y, q.z
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def vlp16_clouds(lidar_above_base_m: float, points_file: str) -> dict:
    """40 clouds of /firefly/velodyne_points (120 s at most): the last one's fields, point step and
    frame, the median period, and of the last five the points per cloud, rings and time span; their
    points, put in the world with the ground-truth pose nearest in time (the lidar lidar_above_base_m
    above the base link), go to points_file."""
    result = {}
    poses = []
    rospy.Subscriber("/firefly/ground_truth/odometry", Odometry, lambda m: poses.append(m), queue_size=1000)
    clouds = []
    rospy.Subscriber("/firefly/velodyne_points", PointCloud2, lambda m: clouds.append(m), queue_size=100)
    deadline = time.monotonic() + 120
    while len(clouds) < 40 and time.monotonic() < deadline:
        time.sleep(0.05)
    c = clouds[-1]
    result["fields"] = [(f.name, f.offset, f.datatype, f.count) for f in c.fields]
    result["point_step"] = c.point_step
    result["frame"] = c.header.frame_id
    stamps = [m.header.stamp.to_sec() for m in clouds]
    result["period"] = float(np.median(np.diff(stamps)))
    rows = []
    rings, times = set(), []
    for cloud in clouds[-5:]:
        t = cloud.header.stamp.to_sec()
        odom = min(poses, key=lambda m: abs(m.header.stamp.to_sec() - t))
        p, q = odom.pose.pose.position, odom.pose.pose.orientation
        R = rotation(q)
        pts = np.array(list(point_cloud2.read_points(cloud, ("x", "y", "z", "ring", "time"))))
        rings.update(int(r) for r in pts[:, 3])
        times.extend([float(pts[:, 4].min()), float(pts[:, 4].max())])
        sensor = np.array([p.x, p.y, p.z]) + R @ np.array([0, 0, lidar_above_base_m])
        rows.append(pts[:, :3] @ R.T + sensor)
    result["points_per_cloud"] = len(rows[-1])
    result["rings"] = sorted(rings)
    result["time_span"] = [min(times), max(times)]
    np.savetxt(points_file, np.vstack(rows), fmt="%.5f")
    return result


def rangefinder_or_hokuyo() -> dict:
    """With a Hokuyo on the firefly (its robot_description): the last of 5 LaserScans' layout, its
    finite ranges and the mean scan period; else the rangefinder's last 20 readings, its limits, the
    ground-truth height and its period."""
    result = {}
    if rospy.has_param("/firefly/robot_description") and "hokuyo" in rospy.get_param("/firefly/robot_description"):
        scans = []
        rospy.Subscriber("/firefly/scan", LaserScan, lambda m: scans.append(m))
        wait_until(lambda: len(scans) >= 5, 90, "5 scans on /firefly/scan")
        s = scans[-1]
        result["scan"] = [s.angle_min, s.angle_max, s.angle_increment, len(s.ranges), s.range_min, s.range_max, s.header.frame_id]
        result["finite"] = sum(1 for r in s.ranges if r == r and abs(r) != float("inf"))
        # the mean over four periods (40 Hz on 10 ms steps: 30 and 20 ms alternate)
        result["period"] = (scans[-1].header.stamp - scans[-5].header.stamp).to_sec() / 4
    else:
        readings = []
        rospy.Subscriber("/firefly/lidar", Range, lambda m: readings.append(m))
        wait_until(lambda: len(readings) >= 20, 90, "20 ranges on /firefly/lidar")
        z = rospy.wait_for_message("/firefly/ground_truth/odometry", Odometry).pose.pose.position.z
        r = readings[-20:]
        result["ranges"] = [m.range for m in r]
        result["limits"] = [r[-1].min_range, r[-1].max_range, r[-1].radiation_type]
        result["z"] = z
        result["period"] = (r[-1].header.stamp - r[-2].header.stamp).to_sec()
    return result
