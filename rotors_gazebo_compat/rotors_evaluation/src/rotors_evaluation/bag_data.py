"""Reads the series the evaluation needs from a ROS 1 bag or a ROS 2 bag (its directory, or its
metadata.yaml, .mcap or .db3 file) with rosbags (pure Python).

Understands bags written by the simulator's bag plugin, bags from `rosbag record` (topics with a
leading slash; the ground truth taken from ground_truth/odometry when the bag has no
ground_truth/twist or holds ground_truth/pose unstamped, said in one line), compressed bags, and
bags of every RotorS generation: topics with or without the MAV prefix, the pre-2.0 names (`motors`,
`collisions`, `command/trajectory_position_yaw`) and types (mav_msgs/MotorSpeed, CommandMotorSpeed,
CommandTrajectoryPositionYaw and any other set point with `position` and `yaw` fields). Message
types are taken from the definitions stored in the bag. A topic of a type the evaluation cannot use
is one line naming the topic and the type.
"""

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np
from rosbags.rosbag1 import Reader, ReaderError
from rosbags.rosbag2 import Reader as Reader2
from rosbags.rosbag2 import ReaderError as ReaderError2
from rosbags.typesys import Stores, get_types_from_idl, get_types_from_msg, get_typestore


class BagError(Exception):
    """A problem with the bag, worded for the user (one line)."""


@dataclass
class Series:
    """Samples of a vector quantity: t [s] (N,), values (N, k)."""

    t: np.ndarray
    values: np.ndarray

    def window(self, begin: float, end: float) -> "Series":
        mask = (self.t > begin) & (self.t <= end)
        return Series(self.t[mask], self.values[mask])


@dataclass
class WaypointSample:
    t: float  # [s]
    position: np.ndarray  # (3,)
    yaw: float  # [rad]


@dataclass
class FlightData:
    path: Path
    position: Series  # (N, 3) [m]
    angular_velocity: Series  # (N, 3) [rad/s]
    waypoints: list[WaypointSample]
    collision_times: np.ndarray  # [s]
    motor_speeds: Series | None = None  # (N, rotors) [rad/s]
    topics: dict[str, str] = field(default_factory=dict)
    flight_end: Optional["FlightEnd"] = None  # where the simulation stopped, if the bag says so
    unwaited: Optional["Unwaited"] = None  # lockstep steps that were not waited for, if any


@dataclass
class FlightEnd:
    """The simulation was paused or stopped at t [s] and did not resume: what the bag holds after t
    is not a controlled flight (a controller that exited first, a simulator that shut down)."""

    t: float
    reason: str
    dropped_s: float = 0.0  # [s] of pose data recorded after t (left out of the evaluation)


@dataclass
class Unwaited:
    """Steps after which lockstep did not wait for a participant's answer (simulation_status): the
    flight depended on wall-clock timing and another run with the same seed may differ."""

    steps: int
    reason: str


STATUS_TOPIC = "/simulation_status"  # rotors_comm/SimulationStatus, written by the bag plugin
STATUS_RUNNING = 0


POSE_COMMAND_TOPIC = "/command/pose"
# Names older RotorS generations used for the same data (tried after the given topic).
OLD_TOPIC_NAMES = {
    "/motor_speed": ("/motors",),
    "/wrench": ("/collisions",),
    "/command/trajectory": (POSE_COMMAND_TOPIC, "/command/trajectory_position_yaw"),
}
# The same ground truth in the other forms the odometry plugin publishes (ROS topics a `rosbag record`
# holds; only the bag plugin writes ground_truth/twist), tried in this order when the bag lacks the
# asked topic or holds it unstamped (RotorS' ground_truth/pose is a geometry_msgs/Pose: its time
# would be the recorder's receive time).
GROUND_TRUTH_FORMS = {
    "/ground_truth/pose": ("/ground_truth/odometry", "/ground_truth/transform", "/ground_truth/position"),
    "/ground_truth/twist": ("/ground_truth/odometry",),
}
UNSTAMPED_TYPES = ("geometry_msgs/msg/Pose", "geometry_msgs/msg/Twist")
TWIST_TYPES = ("geometry_msgs/msg/TwistStamped", "nav_msgs/msg/Odometry", "geometry_msgs/msg/Twist")
POSE_TYPES = (
    "geometry_msgs/msg/PoseStamped",
    "geometry_msgs/msg/TransformStamped",
    "geometry_msgs/msg/PointStamped",
    "nav_msgs/msg/Odometry",
    "geometry_msgs/msg/Pose",
)


def _yaw(q) -> float:
    return float(np.arctan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z)))


def _stamp(msg, bag_time_ns: int) -> float:
    header = getattr(msg, "header", None)
    if header is not None and (header.stamp.sec or header.stamp.nanosec):
        return header.stamp.sec + header.stamp.nanosec * 1e-9
    return bag_time_ns * 1e-9


def _position(msg, msgtype: str) -> np.ndarray:
    if msgtype.endswith("PoseStamped"):
        p = msg.pose.position
    elif msgtype.endswith("TransformStamped"):
        p = msg.transform.translation
    elif msgtype.endswith("PointStamped"):
        p = msg.point
    elif msgtype.endswith("Odometry"):
        p = msg.pose.pose.position
    else:  # geometry_msgs/Pose
        p = msg.position
    return np.array([p.x, p.y, p.z])


def _set_points(msg, msgtype: str, topic: str, t_s: float) -> list:
    """[(time, position, orientation or yaw)] of a set-point message: one, or a trajectory's points
    each at the message's time + its time_from_start (the time a controller releases it; RotorS'
    publishers send one point per message, ours a waypoint file as one trajectory sent ahead).
    BagError for a type that holds no position set point."""
    if msgtype.endswith("/PoseStamped"):
        return [(t_s, msg.pose.position, msg.pose.orientation)]
    if msgtype.endswith("/Pose"):
        return [(t_s, msg.position, msg.orientation)]
    if msgtype.endswith("MultiDOFJointTrajectory"):
        return [
            (t_s + p.time_from_start.sec + p.time_from_start.nanosec * 1e-9, p.transforms[0].translation, p.transforms[0].rotation)
            for p in msg.points
            if p.transforms
        ]
    if hasattr(msg, "position") and hasattr(msg, "yaw"):  # mav_msgs/CommandTrajectoryPositionYaw and kin (pre-2.0)
        return [(t_s, msg.position, float(msg.yaw))]
    raise BagError(
        f"waypoint topic '{topic}' has type {msgtype}, which holds no position set point (usable: "
        f"MultiDOFJointTrajectory, PoseStamped, Pose, or a message with position and yaw fields)"
    )


def ros2_bag_directory(path: Path) -> Path | None:
    """The ROS 2 bag `path` names (its directory, or a file in it beside metadata.yaml), else None."""
    directory = path if path.is_dir() else path.parent
    return directory if (directory / "metadata.yaml").is_file() else None


class FlightBag:
    """An open bag (ROS 1, or ROS 2 in any storage rosbags reads): topic lookup with RotorS' naming
    rules and typed message iteration."""

    def __init__(self, path: Path):
        self.path = Path(path)
        ros2 = ros2_bag_directory(self.path) if self.path.exists() else None
        if not self.path.is_file() and ros2 is None:
            raise BagError(
                f"bag '{self.path}' does not exist"
                if not self.path.exists()
                else f"'{self.path}' is a directory without a ROS 2 bag's metadata.yaml"
            )
        self.ros2 = ros2 is not None
        try:
            if self.ros2:
                self.path = ros2
                self.reader = Reader2(ros2)
            else:
                self.reader = Reader(self.path)
            self.reader.open()
        except (ReaderError, ReaderError2) as e:
            fix = (
                "it may be incomplete: was the recorder stopped before it closed the bag?"
                if self.ros2
                else f"if it is unindexed or truncated, run: rosbag reindex {self.path}"
            )
            raise BagError(f"cannot read bag '{self.path}': {e} ({fix})") from e
        self.typestore = get_typestore(Stores.ROS2_JAZZY if self.ros2 else Stores.ROS1_NOETIC)
        types = {}
        for conn in self.reader.connections:
            try:
                if getattr(conn.msgdef.format, "name", "MSG") == "IDL":
                    types.update(get_types_from_idl(conn.msgdef.data))
                else:
                    types.update(get_types_from_msg(conn.msgdef.data, conn.msgtype))
            except Exception:  # noqa: BLE001 - a definition rosbags cannot parse; the store may know it
                pass
        self.typestore.register(types)
        self.topics = {c.topic.lstrip("/"): c.msgtype for c in self.reader.connections}
        if not self.topics:
            raise BagError(f"bag '{self.path}' is empty (no topics)")

    def close(self) -> None:
        self.reader.close()

    def resolve(self, mav_name: str, topic: str) -> str | None:
        """'<mav>/<topic>' as the bag plugin writes it, else the bare topic of old RotorS bags."""
        topic = topic.lstrip("/")
        for candidate in ([f"{mav_name.strip('/')}/{topic}"] if mav_name else []) + [topic]:
            if candidate in self.topics:
                return candidate
        return None

    def resolve_any(self, mav_name: str, topic: str) -> str | None:
        """resolve() of the topic, then of the names older RotorS generations used for it."""
        for candidate in (topic,) + OLD_TOPIC_NAMES.get("/" + topic.lstrip("/"), ()):
            found = self.resolve(mav_name, candidate)
            if found:
                return found
        return None

    def require(self, mav_name: str, topic: str, what: str) -> str:
        found = self.resolve(mav_name, topic)
        if found is None:
            wanted = f"{mav_name.strip('/')}/{topic.lstrip('/')}" if mav_name else topic.lstrip("/")
            raise BagError(
                f"{what} topic '{wanted}' is not in bag '{self.path.name}' (check --mav_name and the "
                f"topic options); the bag has: {', '.join(sorted(self.topics))}"
            )
        return found

    def require_ground_truth(self, mav_name: str, topic: str, what: str, usable: tuple) -> str:
        """require() of a ground-truth topic, else (or when the bag holds it unstamped) the same
        ground truth in another form the bag holds (GROUND_TRUTH_FORMS), said in one line on stderr."""
        found = self.resolve(mav_name, topic)
        if found is not None and self.topics[found] not in UNSTAMPED_TYPES:
            return found
        for form in GROUND_TRUTH_FORMS.get("/" + topic.lstrip("/"), ()):
            other = self.resolve(mav_name, form)
            if other is not None and self.topics[other] in usable and self.topics[other] not in UNSTAMPED_TYPES:
                why = (
                    f"'{found}' is unstamped ({self.topics[found]})"
                    if found is not None
                    else f"the bag has no '{mav_name.strip('/')}/{topic.lstrip('/')}'"
                )
                print(f"note: {what} from '{other}' ({self.topics[other]}): {why}", file=sys.stderr)
                return other
        return found if found is not None else self.require(mav_name, topic, what)

    def flight_end(self, mav_name: str) -> FlightEnd | None:
        """The last pause or stop that was not followed by a resume, from the bag plugin's
        simulation_status markers; None for bags without them (rosbag record, RotorS)."""
        topic = self.resolve(mav_name, STATUS_TOPIC)
        if topic is None:
            return None
        end = None
        for msg, _, t_ns in self.messages(topic):
            if msg.state == STATUS_RUNNING:
                end = None
            elif end is None:
                state = "stopped" if msg.state == 2 else "paused"
                end = FlightEnd(
                    _stamp(msg, t_ns), f"the simulation was {state}: {msg.reason}" if msg.reason else f"the simulation was {state}"
                )
        return end

    def unwaited(self, mav_name: str, until_s: float | None = None) -> Unwaited | None:
        """The count of steps lockstep did not wait for (the largest a status marker reports) and
        why the first was not; None when every step was waited for or the bag has no markers.
        until_s: only the markers stamped up to that sim time count (the bag plugin writes one at
        the first step not waited for): a sweep judges the span it evaluates, not the steps the
        simulator takes while the nodes are stopped after it, when a controller may already be gone."""
        topic = self.resolve(mav_name, STATUS_TOPIC)
        found = None
        for msg, _, t_ns in self.messages(topic) if topic else ():
            if until_s is not None and _stamp(msg, t_ns) > until_s:
                continue
            steps = int(getattr(msg, "unwaited_steps", 0))  # older bags: no such field
            if steps > 0 and (found is None or steps > found.steps):
                reason = msg.reason.split("not repeatable: ", 1)[-1]
                found = Unwaited(steps, reason)
        return found

    def messages(self, topic: str):
        conns = [c for c in self.reader.connections if c.topic.lstrip("/") == topic.lstrip("/")]
        if not conns:  # rosbags reads every connection when given none
            return
        try:
            for conn, t_ns, raw in self.reader.messages(connections=conns):
                try:
                    msg = (self.typestore.deserialize_cdr if self.ros2 else self.typestore.deserialize_ros1)(raw, conn.msgtype)
                except Exception as e:  # noqa: BLE001 - a definition that does not match the bytes
                    raise BagError(f"topic '{topic}' of type {conn.msgtype} in bag '{self.path.name}' cannot be " f"decoded: {e}") from e
                yield msg, conn.msgtype, t_ns
        except (ReaderError, ReaderError2) as e:
            fix = "the ROS 2 bag may be incomplete" if self.ros2 else f"if it is truncated, run: rosbag reindex {self.path}"
            raise BagError(f"cannot read topic '{topic}' of bag '{self.path}': {e} ({fix})") from e


def _until(data: FlightData, end: FlightEnd | None) -> FlightData:
    """Drops what was recorded after the simulation stopped for good (see FlightEnd)."""
    if end is None:
        return data
    end.dropped_s = max(float(data.position.t[-1]) - end.t, 0.0) if len(data.position.t) else 0.0
    keep = lambda series: series.window(-np.inf, end.t) if series is not None else None  # noqa: E731
    data.position, data.angular_velocity = keep(data.position), keep(data.angular_velocity)
    data.motor_speeds = keep(data.motor_speeds)
    data.waypoints = [w for w in data.waypoints if w.t <= end.t]
    data.collision_times = data.collision_times[data.collision_times <= end.t]
    data.flight_end = end
    return data


def load_flight(
    path: Path, mav_name: str, pose_topic: str, twist_topic: str, waypoint_topic: str, wrench_topic: str, motor_topic: str | None = None
) -> FlightData:
    bag = FlightBag(path)
    try:
        used = {}
        pose = used["pose"] = bag.require_ground_truth(mav_name, pose_topic, "pose", POSE_TYPES)
        if bag.topics[pose] not in POSE_TYPES:
            raise BagError(f"pose topic '{pose}' has type {bag.topics[pose]}; expected one of {', '.join(POSE_TYPES)}")
        t, p = [], []
        for msg, msgtype, t_ns in bag.messages(pose):
            t.append(_stamp(msg, t_ns))
            p.append(_position(msg, msgtype))
        if not t:
            raise BagError(f"pose topic '{pose}' has no messages in bag '{bag.path.name}'")
        twist = used["twist"] = bag.require_ground_truth(mav_name, twist_topic, "twist", TWIST_TYPES)
        if bag.topics[twist] not in TWIST_TYPES:
            raise BagError(f"twist topic '{twist}' has type {bag.topics[twist]}; expected one of {', '.join(TWIST_TYPES)}")
        tw, w = [], []
        for msg, msgtype, t_ns in bag.messages(twist):
            if msgtype.endswith("Odometry"):
                ang = msg.twist.twist.angular
            else:
                ang = msg.twist.angular if msgtype.endswith("TwistStamped") else msg.angular
            tw.append(_stamp(msg, t_ns))
            w.append([ang.x, ang.y, ang.z])
        waypoints = []
        # the waypoint topic, else the pose command (hovering_example_msf sends a PoseStamped there),
        # else the pre-2.0 command/trajectory_position_yaw
        wp_topic = bag.resolve_any(mav_name, waypoint_topic)
        if wp_topic:
            used["waypoints"] = wp_topic
            last = None
            for msg, msgtype, t_ns in bag.messages(wp_topic):
                for t_s, pos, rot in _set_points(msg, msgtype, wp_topic, _stamp(msg, t_ns)):
                    yaw = rot if isinstance(rot, float) else _yaw(rot)
                    sample = WaypointSample(t_s, np.array([pos.x, pos.y, pos.z]), yaw)
                    key = (tuple(sample.position), sample.yaw)
                    if key != last:  # consecutive duplicates are dropped, as RotorS
                        waypoints.append(sample)
                    last = key
        collisions = []
        wrench = bag.resolve_any(mav_name, wrench_topic)
        if wrench:  # every message is a contact, whatever its type (WrenchStamped; older: collisions)
            used["wrench"] = wrench
            collisions = [_stamp(msg, t_ns) for msg, _, t_ns in bag.messages(wrench)]
        motors = None
        if motor_topic:
            motor = bag.resolve_any(mav_name, motor_topic)
            sample = next(bag.messages(motor), None) if motor else None
            if sample is not None and not (hasattr(sample[0], "angular_velocities") or hasattr(sample[0], "motor_speed")):
                print(
                    f"note: motor topic '{motor}' has type {sample[1]}, which holds no rotor speeds; motor speeds " f"are left out",
                    file=sys.stderr,
                )
                motor = None
            if motor:
                used["motors"] = motor
                tm, om = [], []
                for msg, _msgtype, t_ns in bag.messages(motor):
                    # Actuators; pre-2.0 MotorSpeed and CommandMotorSpeed
                    speeds = msg.angular_velocities if hasattr(msg, "angular_velocities") else msg.motor_speed
                    tm.append(_stamp(msg, t_ns))
                    om.append(list(speeds))
                if tm and len({len(o) for o in om}) == 1:
                    motors = Series(np.array(tm), np.array(om))
        data = FlightData(
            bag.path,
            Series(np.array(t), np.array(p)),
            Series(np.array(tw), np.array(w).reshape(-1, 3)),
            waypoints,
            np.array(sorted(collisions)),
            motors,
            used,
            unwaited=bag.unwaited(mav_name),
        )
        return _until(data, bag.flight_end(mav_name))
    finally:
        bag.close()
