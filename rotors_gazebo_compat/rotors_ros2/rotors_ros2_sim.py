#!/usr/bin/env python3
"""rotors_ros2_sim: the simulator on a ROS 2 graph (rclpy, PyPI's Jazzy wheels; docs/ros2.md).

    build/ros2-venv/bin/python rotors_gazebo_compat/rotors_ros2/rotors_ros2_sim.py --mav firefly

A node named `gazebo` publishes `/clock` (rosgraph_msgs/msg/Clock), `/<mav>/odometry_sensor1/odometry`
and `/<mav>/ground_truth/odometry` (nav_msgs/msg/Odometry) and `/<mav>/imu` (sensor_msgs/msg/Imu) with
every reading of the vehicle's odometry sensor, ground truth and IMU, and `/<mav>/motor_speed`
(mav_msgs/msg/Actuators, the real signed rotor speeds, every step), stamped with sim time and framed as
the ROS 1 messages are, and serves Gazebo ROS 2's `/reset_simulation`, `/reset_world`,
`/pause_physics` and `/unpause_physics` (std_srvs/srv/Empty) and `/spawn_entity` and `/delete_entity`
(gazebo_msgs/srv/SpawnEntity, DeleteEntity: a model from URDF or SDF text; its topics published from
then on). mav_msgs, rotors_comm and gazebo_msgs are RotorS' interface packages built for ROS 2 by make
setup (rotors_gazebo_compat/rotors_ros2/interfaces).

The controller runs inside the world's step loop, so the flight is in lockstep with it whatever the
machine's load; --controller picks it, as the ROS 1 launch files pick a controller node:
- lee (default; the hovering example's yaml): set points on `/<mav>/command/trajectory`
  (trajectory_msgs/msg/MultiDOFJointTrajectory: the first point's first transform, in force from its
  stamp + time_from_start, as the ROS 1 Lee node releases it) and `/<mav>/command/pose`
  (geometry_msgs/msg/PoseStamped, from its stamp);
- roll_pitch_yawrate_thrust (roll_pitch_yawrate_thrust_controller_node's yaml): `/<mav>/command/
  roll_pitch_yawrate_thrust`, `command/attitude_thrust` and `command/rate_thrust` (mav_msgs/msg/...,
  thrust.z [N]);
- none: no controller.
`/<mav>/command/motor_speed` (mav_msgs/msg/Actuators, angular_velocities [rad/s]) reaches the motors
as RotorS' controller interface plugin passes it; with a controller running, its next answer replaces
it, as on ROS 1 when the controller node publishes the same topic.

The world itself is rotors_sim's, stepped in a child process (python3 -m rotors_sim.stepper, ROS 1's
environment): ROS 1's and ROS 2's Python message packages share module names and cannot live in one
process. --real-time-factor 1 (the default) paces sim time to wall time; 0 runs as fast as it can.
--paused starts with physics paused (the launch files' paused:=true), until /unpause_physics.
Every other topic the vehicle's plugins publish on ROS 1 is published, to its subscribers, under the
same name with the ROS 2 form of its type (the ground truth's and the odometry sensor's pose,
position and transform, the IMU bias; with enable_navigation_sensors:=true the GPS, ground speed,
magnetometer and barometer; cameras' image_raw and camera_info; lasers): the plugin's own ROS 1
message, converted to CDR by rosbags (ros1_to_cdr: the same fields, Header without seq), so field for
field and pixel for pixel what ROS 1 sees. A topic whose type has no ROS 2 package here, or whose name
ROS 2 cannot carry (motor_speed/<N>: a token starting with a digit), is named in one line at start
and not published. --model mav_with_vi_sensor (a model of rotors_description/urdf, or a path)
spawns that model instead of the generic odometry sensor's; name:=value arguments are further xacro
arguments of the vehicle, as spawn_mav.launch passes them.
A command with a NaN or a missing transform, or a motor command of the wrong length, is refused in one
line; the world runs on."""

from __future__ import annotations

import argparse
import base64
import importlib
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import rclpy
from builtin_interfaces.msg import Time
from gazebo_msgs.srv import DeleteEntity, SpawnEntity
from geometry_msgs.msg import PoseStamped
from mav_msgs.msg import Actuators, AttitudeThrust, RateThrust, RollPitchYawrateThrust
from nav_msgs.msg import Odometry
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.exceptions import InvalidTopicNameException
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty
from trajectory_msgs.msg import MultiDOFJointTrajectory

REPO = Path(__file__).resolve().parents[2]
# the sensors' QoS: reliable, keeping the last 10,000 readings (100 s at 100 Hz, about 7 MB a topic)
# for a reliable subscriber that falls behind (a recorder while the world runs faster than real
# time) to catch up; keep-all would let a subscriber that stops reading stall the world (and rcl
# fails the publish once the writer's resources run out)
SENSOR_QOS = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10_000, reliability=ReliabilityPolicy.RELIABLE)
# physics steps per exchange with the world when running as fast as possible (10: 0.1 s of basic.world):
# subscriptions and services are served between exchanges
STEPS_PER_EXCHANGE = 10
# the cameras' and point clouds' QoS: reliable, the last 100 (36 MB of the VI-sensor's 752 x 480 images)
IMAGE_QOS = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=100, reliability=ReliabilityPolicy.RELIABLE)
LARGE_TYPES = ("sensor_msgs/msg/Image", "sensor_msgs/msg/PointCloud2")
INTERFACES = REPO / "rotors_gazebo_compat" / "rotors_ros2" / "interfaces"


def to_time(t_s: float) -> Time:
    ns = int(round(t_s * 1e9))
    return Time(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


class Ros1Bridge:
    """The ROS 2 publishers of the world's other topics: a ROS 1 type pkg/Name becomes pkg/msg/Name, its
    messages are converted from ROS 1's bytes to CDR (rosbags' ROS 1 to CDR conversion, with the project's
    ROS 2 interface packages registered) and published as they are. The world sends the messages of the
    topics someone subscribes to (`listened`, kept by the publishers' matched events): converting and
    publishing every topic of a vehicle every step would cost more than the step."""

    def __init__(self, node: Node, topics: list):
        self.node = node
        self.typestore = get_typestore(Stores.ROS2_JAZZY)
        for msg in sorted(INTERFACES.glob("*/msg/*.msg")):
            self.typestore.register(get_types_from_msg(msg.read_text(), f"{msg.parent.parent.name}/msg/{msg.stem}"))
        self.publishers, self.ros2_types = {}, {}
        self.listened: set[str] = set()
        self.changed = False
        self.add(topics)

    def add(self, topics: list) -> None:
        """Publishers for [topic, ROS 1 type] pairs (at start, and a spawned model's)."""
        skipped = []
        for topic, ros1_type in topics:
            package, name = ros1_type.split("/")
            ros2_type = f"{package}/msg/{name}"
            try:
                cls = getattr(importlib.import_module(f"{package}.msg"), name)
            except (ImportError, AttributeError):
                skipped.append(f"{topic} ({ros1_type}: no ROS 2 package here)")
                continue
            if ros2_type not in self.typestore.fielddefs:
                skipped.append(f"{topic} ({ros1_type}: rosbags cannot convert it)")
                continue
            try:
                self.publishers[topic] = self.node.create_publisher(
                    cls,
                    topic,
                    IMAGE_QOS if ros2_type in LARGE_TYPES else SENSOR_QOS,
                    event_callbacks=PublisherEventCallbacks(matched=lambda status, topic=topic: self.matched(topic, status.current_count)),
                )
            except InvalidTopicNameException:  # e.g. motor_speed/0: a ROS 2 name token cannot start with a digit
                skipped.append(f"{topic} (not a ROS 2 topic name)")
                continue
            self.ros2_types[topic] = ros2_type
        if skipped:
            self.node.get_logger().info(f"not on ROS 2: {', '.join(skipped)}")

    def matched(self, topic: str, subscribers: int) -> None:
        before = set(self.listened)
        (self.listened.add if subscribers > 0 else self.listened.discard)(topic)
        self.changed = self.changed or self.listened != before

    def publish(self, topic: str, data_b64: str) -> None:
        if topic in self.publishers:
            raw = base64.b64decode(data_b64)
            self.publishers[topic].publish(bytes(self.typestore.ros1_to_cdr(raw, self.ros2_types[topic])))


def yaw_of(x: float, y: float, z: float, w: float) -> float:
    """The yaw of a quaternion (ZYX Euler angles, as mav_msgs::yawFromQuaternion)."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class StepperLink:
    """The world's process (rotors_sim.stepper): one JSON request per line, one answer per line."""

    def __init__(self, mav: str, world: str, seed: int, model: str | None = None, controller: str = "lee", xacro_args=()):
        # ROS 1's environment for the world's process (ros2_env.sh saves it before it enters ROS 2's)
        env = dict(os.environ)
        for name in ("PYTHONPATH", "LD_LIBRARY_PATH"):
            if f"ROTORS_ROS1_{name}" in env:
                env[name] = env[f"ROTORS_ROS1_{name}"]
        python = env.get("ROTORS_ROS1_PYTHON", str(REPO / "build" / "venv" / "bin" / "python"))
        cmd = [python, "-m", "rotors_sim.stepper", "--mav", mav, "--world", world, "--seed", str(seed)]
        cmd += ["--model", model] if model else []
        cmd += ["--controller", controller, *xacro_args]
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
        ready = self._read()
        if "error" in ready:
            raise SystemExit(f"rotors_ros2_sim: the world did not start: {ready['error']}")

    def _read(self) -> dict:
        line = self.proc.stdout.readline()
        if not line:
            raise SystemExit(f"rotors_ros2_sim: the world's process ended (exit code {self.proc.wait()})")
        return json.loads(line)

    def request(self, **req) -> dict:
        self.proc.stdin.write(json.dumps(req) + "\n")
        self.proc.stdin.flush()
        return self._read()

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.stdin.close()
            self.proc.wait(timeout=10)


class RotorsSim(Node):
    def __init__(self, link: StepperLink, mav: str, real_time_factor: float, paused: bool = False):
        super().__init__("gazebo")
        self.link, self.mav, self.real_time_factor = link, mav, real_time_factor
        info = link.request(op="info")
        self.step_s = info["step_s"]
        self.frames = info["frames"]
        self.clock_pub = self.create_publisher(Clock, "/clock", 10)
        self.odometry_pubs = {"odometry": self.create_publisher(Odometry, f"/{mav}/odometry_sensor1/odometry", SENSOR_QOS)}
        if "ground_truth" in self.frames:
            self.odometry_pubs["ground_truth"] = self.create_publisher(Odometry, f"/{mav}/ground_truth/odometry", SENSOR_QOS)
        self.imu_pub = self.create_publisher(Imu, f"/{mav}/imu", SENSOR_QOS)
        self.motor_speed_pub = self.create_publisher(Actuators, f"/{mav}/motor_speed", SENSOR_QOS)
        self.bridge = Ros1Bridge(self, info["topics"])
        self.messages = {key: Odometry() for key in self.odometry_pubs}
        for key, m in self.messages.items():
            m.header.frame_id, m.child_frame_id = self.frames[key], self.frames[f"{key}_child"]
        self.messages["imu"] = Imu()
        self.messages["imu"].header.frame_id = self.frames["imu"]
        self.messages["imu"].orientation_covariance[0] = -1.0  # no orientation measurement (REP 145), as the ROS 1 IMU says
        self.messages["motor_speed"] = Actuators()
        self.messages["motor_speed"].header.frame_id = self.frames["motor_speed"]
        if info["controller"] == "lee":
            self.create_subscription(MultiDOFJointTrajectory, f"/{mav}/command/trajectory", self.on_trajectory, 10)
            self.create_subscription(PoseStamped, f"/{mav}/command/pose", self.on_pose, 10)
        elif info["controller"] == "roll_pitch_yawrate_thrust":
            self.create_subscription(RollPitchYawrateThrust, f"/{mav}/command/roll_pitch_yawrate_thrust", self.on_rpyt, 10)
            self.create_subscription(AttitudeThrust, f"/{mav}/command/attitude_thrust", self.on_attitude_thrust, 10)
            self.create_subscription(RateThrust, f"/{mav}/command/rate_thrust", self.on_rate_thrust, 10)
        self.create_subscription(Actuators, f"/{mav}/command/motor_speed", self.on_motor_speed, 10)
        self.requests: list[dict] = []  # served between steps, in the order they came
        self.due: list[tuple[float, dict]] = []  # set points stamped for later: (sim time, request)
        self.paused = paused
        for name, op in (("/reset_simulation", "reset"), ("/reset_world", "reset_world")):
            self.create_service(Empty, name, lambda req, res, op=op: self.queue(res, op=op))
        self.create_service(SpawnEntity, "/spawn_entity", self.spawn_entity)
        self.create_service(DeleteEntity, "/delete_entity", self.delete_entity)
        self.create_service(Empty, "/pause_physics", lambda req, res: self.pause(res, True))
        self.create_service(Empty, "/unpause_physics", lambda req, res: self.pause(res, False))

    def queue(self, response, **request):
        self.requests.append(request)
        return response

    def spawn_entity(self, request, response):
        """Gazebo ROS 2's /spawn_entity: the model from its URDF or SDF text at initial_pose (the world's
        frame). The plugins take their namespaces from the description, as the ROS 1 spawn does, so a
        robot_namespace is reported as not applied. Its topics are published from then on."""
        notes = []
        if request.reference_frame not in ("", "world", "map"):
            response.success, response.status_message = (
                False,
                f"reference_frame '{request.reference_frame}': only the world's frame is served",
            )
            return response
        if request.robot_namespace and request.robot_namespace.strip("/") != request.name:
            notes.append(f"robot_namespace '{request.robot_namespace}' not applied: the plugins take theirs from the description")
        p, q = request.initial_pose.position, request.initial_pose.orientation
        rpy = [
            math.atan2(2.0 * (q.w * q.x + q.y * q.z), 1.0 - 2.0 * (q.x * q.x + q.y * q.y)),
            math.asin(max(-1.0, min(1.0, 2.0 * (q.w * q.y - q.z * q.x)))),
            yaw_of(q.x, q.y, q.z, q.w),
        ]
        answer = self.link.request(op="spawn", xml=request.xml, name=request.name, xyz=[p.x, p.y, p.z], rpy=rpy)
        if "error" in answer:
            self.get_logger().error(answer["error"])
            response.success, response.status_message = False, answer["error"]
            return response
        self.bridge.add(answer["topics"])
        response.success = True
        response.status_message = "; ".join([f"spawned '{answer['name']}' with {len(answer['topics'])} topics", *notes])
        return response

    def delete_entity(self, request, response):
        """Gazebo ROS 2's /delete_entity. Deleting the vehicle this front end serves (--mav) stops its
        readings; the world runs on."""
        answer = self.link.request(op="delete", name=request.name)
        response.success = "error" not in answer
        response.status_message = answer.get("error", f"deleted '{request.name}'")
        if not response.success:
            self.get_logger().error(answer["error"])
        return response

    def pause(self, response, paused: bool):
        self.paused = paused
        return response

    def set_point(self, p, yaw: float, source: str, due_s: float = 0.0) -> None:
        """A set point now, or from sim time due_s on (a message stamped ahead, as the ROS 1
        hovering example sends its waypoint and the Lee node releases it at its stamp)."""
        values = [p.x, p.y, p.z, yaw]
        if not all(math.isfinite(v) for v in values):
            self.get_logger().error(f"{source}: set point {values} is not finite: ignored, the last one stays in force")
            return
        self.due.append((due_s, {"op": "set_point", "position": values[:3], "yaw": yaw}))
        self.due.sort(key=lambda d: d[0])

    def on_trajectory(self, msg: MultiDOFJointTrajectory) -> None:
        if not msg.points or not msg.points[0].transforms:
            self.get_logger().error("command/trajectory without a point or a transform: ignored")
            return
        tf = msg.points[0].transforms[0]
        q = tf.rotation
        offset = msg.points[0].time_from_start
        due_s = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9 + offset.sec + offset.nanosec * 1e-9
        self.set_point(tf.translation, yaw_of(q.x, q.y, q.z, q.w), "command/trajectory", due_s)

    def on_pose(self, msg: PoseStamped) -> None:
        q = msg.pose.orientation
        self.set_point(
            msg.pose.position, yaw_of(q.x, q.y, q.z, q.w), "command/pose", msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        )

    def on_rpyt(self, msg: RollPitchYawrateThrust) -> None:
        self.requests.append(
            {"op": "roll_pitch_yawrate_thrust", "roll": msg.roll, "pitch": msg.pitch, "yaw_rate": msg.yaw_rate, "thrust": msg.thrust.z}
        )

    def on_attitude_thrust(self, msg: AttitudeThrust) -> None:
        q = msg.attitude
        self.requests.append({"op": "attitude_thrust", "orientation": [q.x, q.y, q.z, q.w], "thrust": msg.thrust.z})

    def on_rate_thrust(self, msg: RateThrust) -> None:
        w = msg.angular_rates
        self.requests.append({"op": "rate_thrust", "angular_velocity": [w.x, w.y, w.z], "thrust": msg.thrust.z})

    def on_motor_speed(self, msg: Actuators) -> None:
        self.requests.append({"op": "motor_speeds", "speeds": list(msg.angular_velocities)})

    def publish(self, answer: dict) -> None:
        """Every reading of the answer, then the clock at its end. One message object per topic is
        filled and published again (rclpy serialises it at publish; building a message costs more
        than publishing it)."""
        for key, pub in self.odometry_pubs.items():
            m = self.messages[key]
            p, q, v, w = m.pose.pose.position, m.pose.pose.orientation, m.twist.twist.linear, m.twist.twist.angular
            for row in answer[key]:
                m.header.stamp = to_time(row[0])
                p.x, p.y, p.z = row[1:4]
                q.x, q.y, q.z, q.w = row[4:8]
                v.x, v.y, v.z = row[8:11]  # body frame, as RotorS' odometry plugin
                w.x, w.y, w.z = row[11:14]
                pub.publish(m)
        m = self.messages["imu"]
        for row in answer["imu"]:
            m.header.stamp = to_time(row[0])
            m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z = row[1:4]
            m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = row[4:7]
            self.imu_pub.publish(m)
        m = self.messages["motor_speed"]
        for row in answer["motor_speed"]:
            m.header.stamp = to_time(row[0])
            m.angular_velocities = row[1:]
            self.motor_speed_pub.publish(m)
        for topic, _, data in answer["messages"]:
            self.bridge.publish(topic, data)
        self.clock_pub.publish(Clock(clock=to_time(answer["t"])))

    def steps_to_take(self, now_s: float) -> int:
        """Paced: one step per exchange with the world. As fast as possible: up to STEPS_PER_EXCHANGE,
        never past the next set point's due time (it takes effect at its step, as when paced)."""
        if self.real_time_factor > 0.0:
            return 1
        n = STEPS_PER_EXCHANGE
        if self.due:
            n = min(n, max(1, math.ceil((self.due[0][0] - now_s) / self.step_s - 1e-9)))
        return n

    def run(self) -> None:
        wall_start, sim_start, now_s = time.monotonic(), None, 0.0
        while rclpy.ok():
            rclpy.spin_once(self, timeout_sec=0.0)
            if self.bridge.changed:
                self.bridge.changed = False
                self.requests.append({"op": "forward", "topics": sorted(self.bridge.listened)})
            while self.due and self.due[0][0] <= now_s + 1e-9:
                self.requests.append(self.due.pop(0)[1])
            while self.requests:
                request = self.requests.pop(0)
                answer = self.link.request(**request)
                if "error" in answer:
                    self.get_logger().error(answer["error"])
                if request["op"] == "reset":
                    sim_start = None  # sim time went back to 0: pace from here
                    now_s = answer["t"]
            if self.paused:
                rclpy.spin_once(self, timeout_sec=0.01)
                sim_start = None
                continue
            answer = self.link.request(op="step", n=self.steps_to_take(now_s))
            now_s = answer["t"]
            self.publish(answer)
            if self.real_time_factor > 0.0:
                if sim_start is None:
                    wall_start, sim_start = time.monotonic(), answer["t"]
                ahead_s = (answer["t"] - sim_start) / self.real_time_factor - (time.monotonic() - wall_start)
                if ahead_s > 0.0:
                    rclpy.spin_once(self, timeout_sec=ahead_s)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mav", default="firefly")
    parser.add_argument("--world", default="basic")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--real-time-factor", type=float, default=1.0)
    parser.add_argument("--paused", action="store_true", help="start with physics paused, until /unpause_physics")
    parser.add_argument("--model", default=None, help="rotors_description/urdf/<model>.gazebo (e.g. mav_with_vi_sensor), or a path")
    parser.add_argument(
        "--controller", default="lee", choices=("lee", "roll_pitch_yawrate_thrust", "none"), help="the controller in the world's loop"
    )
    parser.add_argument("xacro_args", nargs="*", metavar="name:=value", help="further xacro arguments of the vehicle")
    args = parser.parse_args(argv)
    link = StepperLink(args.mav, args.world, args.seed, args.model, args.controller, args.xacro_args)
    rclpy.init(args=[a for a in (sys.argv if argv is None else argv) if a not in args.xacro_args])  # xacro's, not remaps
    node = RotorsSim(link, args.mav, args.real_time_factor, args.paused)
    try:
        node.run()
    except (KeyboardInterrupt, ExternalShutdownException):  # SIGINT: rclpy's handler shuts the context down
        pass
    finally:
        link.close()
        node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
