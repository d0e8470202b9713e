"""Writes small bags with rosbags whose metrics are known in closed form."""

from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

import numpy as np
from rosbags.rosbag1 import Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

TS = get_typestore(Stores.ROS1_NOETIC)
TS.register(get_types_from_msg("Header header\nfloat64[] motor_speed\n", "mav_msgs/msg/MotorSpeed"))
T = TS.types


def header(t: float, frame: str = "world"):
    sec = int(t)
    return T["std_msgs/msg/Header"](
        seq=0, stamp=T["builtin_interfaces/msg/Time"](sec=sec, nanosec=int(round((t - sec) * 1e9))), frame_id=frame
    )


def vec(x, y, z):
    return T["geometry_msgs/msg/Vector3"](x=x, y=y, z=z)


def pose_stamped(t, p):
    P = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=p[0], y=p[1], z=p[2]), orientation=T["geometry_msgs/msg/Quaternion"](x=0, y=0, z=0, w=1)
    )
    return T["geometry_msgs/msg/PoseStamped"](header=header(t), pose=P)


def twist_stamped(t, w):
    return T["geometry_msgs/msg/TwistStamped"](header=header(t), twist=T["geometry_msgs/msg/Twist"](linear=vec(0, 0, 0), angular=vec(*w)))


def trajectory(t, points: Sequence[tuple[float, float, float]]):
    pts = []
    for x, y, z in points:
        tr = T["geometry_msgs/msg/Transform"](translation=vec(x, y, z), rotation=T["geometry_msgs/msg/Quaternion"](x=0, y=0, z=0, w=1))
        pts.append(
            T["trajectory_msgs/msg/MultiDOFJointTrajectoryPoint"](
                transforms=[tr], velocities=[], accelerations=[], time_from_start=T["builtin_interfaces/msg/Duration"](sec=0, nanosec=0)
            )
        )
    return T["trajectory_msgs/msg/MultiDOFJointTrajectory"](header=header(t), joint_names=["base_link"], points=pts)


def wrench(t):
    return T["geometry_msgs/msg/WrenchStamped"](
        header=header(t, "a--b"), wrench=T["geometry_msgs/msg/Wrench"](force=vec(0, 0, 10), torque=vec(0, 0, 0))
    )


def write_flight(
    path: Path,
    position: Callable[[float], tuple[float, float, float]],
    angular: Callable[[float], tuple[float, float, float]],
    waypoints: Iterable[tuple[float, tuple]],
    collisions: Iterable[float] = (),
    prefix: str = "firefly/",
    duration: float = 40.0,
    compression: str | None = None,
    old_motor_topic: bool = False,
) -> Path:
    writer = Writer(path)
    if compression:
        writer.set_compression(getattr(Writer.CompressionFormat, compression.upper()))
    with writer as w:
        c_pose = w.add_connection(f"{prefix}ground_truth/pose", "geometry_msgs/msg/PoseStamped", typestore=TS)
        c_twist = w.add_connection(f"{prefix}ground_truth/twist", "geometry_msgs/msg/TwistStamped", typestore=TS)
        c_wp = w.add_connection(f"{prefix}command/trajectory", "trajectory_msgs/msg/MultiDOFJointTrajectory", typestore=TS)
        c_wr = w.add_connection(f"{prefix}wrench", "geometry_msgs/msg/WrenchStamped", typestore=TS)
        c_m = w.add_connection("/motors", "mav_msgs/msg/MotorSpeed", typestore=TS) if old_motor_topic else None
        events = []
        n = int(round(duration * 100))
        for k in range(1, n + 1):
            t = k * 0.01
            events.append((t, c_pose, "geometry_msgs/msg/PoseStamped", pose_stamped(t, position(t))))
            events.append((t, c_twist, "geometry_msgs/msg/TwistStamped", twist_stamped(t, angular(t))))
            if c_m is not None:
                events.append(
                    (t, c_m, "mav_msgs/msg/MotorSpeed", T["mav_msgs/msg/MotorSpeed"](header=header(t), motor_speed=np.full(6, 543.0)))
                )
        for t, point in waypoints:
            events.append((t, c_wp, "trajectory_msgs/msg/MultiDOFJointTrajectory", trajectory(t, [point])))
        for t in collisions:
            events.append((t, c_wr, "geometry_msgs/msg/WrenchStamped", wrench(t)))
        for t, conn, msgtype, msg in sorted(events, key=lambda e: e[0]):
            w.write(conn, int(round(t * 1e9)), TS.serialize_ros1(msg, msgtype))
    return path


# ---- RotorS before mav_msgs 3.0 (2014-2015): names and types of that generation ----------------
OLD_TYPES = {
    "mav_msgs/msg/CommandTrajectoryPositionYaw": "Header header\ngeometry_msgs/Vector3 position\n"
    "geometry_msgs/Vector3 velocity\ngeometry_msgs/Vector3 acceleration\ngeometry_msgs/Vector3 jerk\n"
    "geometry_msgs/Vector3 snap\nfloat64 yaw\nfloat64 yaw_rate\n",
    "mav_msgs/msg/CommandMotorSpeed": "Header header\nfloat32[] motor_speed\n",
    "mav_msgs/msg/CommandTrajectoryVelocityYawrate": "Header header\ngeometry_msgs/Vector3 velocity\n" "float64 yaw_rate\n",
}
for _name, _definition in OLD_TYPES.items():
    TS.register(get_types_from_msg(_definition, _name))
T = TS.types


def write_old_rotors_flight(
    path: Path,
    position: Callable[[float], tuple[float, float, float]],
    waypoints: Iterable[tuple[float, tuple]],
    collisions: Iterable[float] = (),
    mav: str = "asymmetric_quadrotor",
    set_point_type: str = "CommandTrajectoryPositionYaw",
    duration: float = 40.0,
) -> Path:
    """The layout of RotorS' own test bag: ground truth without the MAV prefix, /motors as
    MotorSpeed, /<mav>/collisions, set points on /<mav>/command/trajectory_position_yaw, and the
    controller's mav_msgs/CommandMotorSpeed. Angular velocity (0.08, 0, 0) throughout."""
    sp_type = f"mav_msgs/msg/{set_point_type}"
    with Writer(path) as w:
        c_pose = w.add_connection("/ground_truth/pose", "geometry_msgs/msg/PoseStamped", typestore=TS)
        c_twist = w.add_connection("/ground_truth/twist", "geometry_msgs/msg/TwistStamped", typestore=TS)
        c_motors = w.add_connection("/motors", "mav_msgs/msg/MotorSpeed", typestore=TS)
        c_cmd = w.add_connection(f"/{mav}/command/motor_speed", "mav_msgs/msg/CommandMotorSpeed", typestore=TS)
        c_coll = w.add_connection(f"/{mav}/collisions", "geometry_msgs/msg/WrenchStamped", typestore=TS)
        c_sp = w.add_connection(f"/{mav}/command/trajectory_position_yaw", sp_type, typestore=TS)
        events = []
        for k in range(1, int(round(duration * 100)) + 1):
            t = k * 0.01
            events.append((t, c_pose, "geometry_msgs/msg/PoseStamped", pose_stamped(t, position(t))))
            events.append((t, c_twist, "geometry_msgs/msg/TwistStamped", twist_stamped(t, (0.08, 0.0, 0.0))))
            speeds = np.full(4, 600.0)
            events.append((t, c_motors, "mav_msgs/msg/MotorSpeed", T["mav_msgs/msg/MotorSpeed"](header=header(t), motor_speed=speeds)))
            events.append(
                (
                    t,
                    c_cmd,
                    "mav_msgs/msg/CommandMotorSpeed",
                    T["mav_msgs/msg/CommandMotorSpeed"](header=header(t), motor_speed=speeds.astype(np.float32)),
                )
            )
        for t, (x, y, z) in waypoints:
            if set_point_type == "CommandTrajectoryPositionYaw":
                msg = T[sp_type](
                    header=header(t),
                    position=vec(x, y, z),
                    velocity=vec(0, 0, 0),
                    acceleration=vec(0, 0, 0),
                    jerk=vec(0, 0, 0),
                    snap=vec(0, 0, 0),
                    yaw=0.0,
                    yaw_rate=0.0,
                )
            else:
                msg = T[sp_type](header=header(t), velocity=vec(x, y, z), yaw_rate=0.0)
            events.append((t, c_sp, sp_type, msg))
        for t in collisions:
            events.append((t, c_coll, "geometry_msgs/msg/WrenchStamped", wrench(t)))
        for t, conn, msgtype, msg in sorted(events, key=lambda e: e[0]):
            w.write(conn, int(round(t * 1e9)), TS.serialize_ros1(msg, msgtype))
    return path


# ---- ROS 2 (what rosbag2_record.py writes: ground truth as odometry, CDR, MCAP or SQLite) -------
def write_ros2_flight(
    path: Path,
    position: Callable[[float], tuple[float, float, float]],
    angular: Callable[[float], tuple[float, float, float]],
    waypoints: Iterable[tuple[float, tuple]],
    storage: str = "mcap",
    duration: float = 40.0,
) -> Path:
    """A ROS 2 bag (directory `path`) of /firefly/ground_truth/odometry at 100 Hz and the waypoints
    on /firefly/command/trajectory, as the ROS 2 hovering example records them."""
    from rosbags.rosbag2 import StoragePlugin
    from rosbags.rosbag2 import Writer as Writer2

    ts = get_typestore(Stores.ROS2_JAZZY)
    t2 = ts.types

    def stamp(t):
        sec = int(t)
        return t2["std_msgs/msg/Header"](
            stamp=t2["builtin_interfaces/msg/Time"](sec=sec, nanosec=int(round((t - sec) * 1e9))), frame_id="world"
        )

    def v3(x, y, z):
        return t2["geometry_msgs/msg/Vector3"](x=x, y=y, z=z)

    identity = t2["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0)
    plugin = {"mcap": StoragePlugin.MCAP, "sqlite3": StoragePlugin.SQLITE3}[storage]
    with Writer2(path, version=9, storage_plugin=plugin) as w:
        c_odom = w.add_connection("/firefly/ground_truth/odometry", "nav_msgs/msg/Odometry", typestore=ts)
        c_wp = w.add_connection("/firefly/command/trajectory", "trajectory_msgs/msg/MultiDOFJointTrajectory", typestore=ts)
        events = []
        for k in range(1, int(round(duration * 100)) + 1):
            t = k * 0.01
            p = position(t)
            pose = t2["geometry_msgs/msg/PoseWithCovariance"](
                pose=t2["geometry_msgs/msg/Pose"](position=t2["geometry_msgs/msg/Point"](x=p[0], y=p[1], z=p[2]), orientation=identity),
                covariance=np.zeros(36),
            )
            twist = t2["geometry_msgs/msg/TwistWithCovariance"](
                twist=t2["geometry_msgs/msg/Twist"](linear=v3(0.0, 0.0, 0.0), angular=v3(*angular(t))), covariance=np.zeros(36)
            )
            msg = t2["nav_msgs/msg/Odometry"](header=stamp(t), child_frame_id="firefly/base_link", pose=pose, twist=twist)
            events.append((t, c_odom, "nav_msgs/msg/Odometry", msg))
        for t, (x, y, z) in waypoints:
            tr = t2["geometry_msgs/msg/Transform"](translation=v3(x, y, z), rotation=identity)
            point = t2["trajectory_msgs/msg/MultiDOFJointTrajectoryPoint"](
                transforms=[tr], velocities=[], accelerations=[], time_from_start=t2["builtin_interfaces/msg/Duration"](sec=0, nanosec=0)
            )
            msg = t2["trajectory_msgs/msg/MultiDOFJointTrajectory"](header=stamp(t), joint_names=[], points=[point])
            events.append((t, c_wp, "trajectory_msgs/msg/MultiDOFJointTrajectory", msg))
        for t, conn, msgtype, msg in sorted(events, key=lambda e: e[0]):
            w.write(conn, int(round(t * 1e9)), ts.serialize_cdr(msg, msgtype))
    return path
