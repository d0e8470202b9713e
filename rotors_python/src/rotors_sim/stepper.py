"""A world stepped over a pipe: the simulator side of a front end that cannot import rotors_sim in its
own process. ROS 2's Python message packages (PyPI's Jazzy wheels) and ROS 1's (Debian's, which
xacro and rospkg load) share module names (sensor_msgs, rosgraph_msgs, ...), so the ROS 2 front end
(rotors_gazebo_compat/rotors_ros2) runs this in a child process with ROS 1's environment.

    python3 -m rotors_sim.stepper --mav firefly --world basic --seed 0 [--model mav_with_vi_sensor]
                                  [--controller lee | roll_pitch_yawrate_thrust | none] [name:=value ...]

(name:=value: further xacro arguments of the vehicle, as spawn_mav.launch passes them, e.g.
enable_navigation_sensors:=true for the GPS, magnetometer and barometer.)

One JSON object per line on stdin, one answer per line on stdout:

    {"op": "step", "n": 10}                          -> {"t": ..., "odometry": [[t, p(3), q xyzw(4), v_B(3), w_B(3)], ...],
                                                          "ground_truth": [... as odometry],
                                                          "imu": [[t, gyro(3), specific force(3)], ...],
                                                          "motor_speed": [[t, signed rotor speeds [rad/s]...], ...],
                                                          "messages": [[topic, ROS 1 type, ROS 1 bytes in base64], ...]}
    {"op": "set_point", "position": [x, y, z], "yaw": 0.0} -> {"t": ...}               (--controller lee)
    {"op": "roll_pitch_yawrate_thrust", "roll": .., "pitch": .., "yaw_rate": .., "thrust": ..} -> {"t": ...}
    {"op": "attitude_thrust", "orientation": [x, y, z, w], "thrust": ..} -> {"t": ...}
    {"op": "rate_thrust", "angular_velocity": [x, y, z], "thrust": ..} -> {"t": ...}  (--controller roll_pitch_yawrate_thrust)
    {"op": "motor_speeds", "speeds": [...]}        -> {"t": ...}   (command/motor_speed; a controller's next answer replaces it)
    {"op": "forward", "topics": [...]}               -> {"t": ...}   (the other topics to answer, from now on; none at start)
    {"op": "spawn", "xml": "<robot ...", "name": ..., "xyz": [...], "rpy": [...]}
                                                     -> {"t": ..., "name": ..., "topics": [[topic, ROS 1 type], ...]}
    {"op": "delete", "name": ...}                    -> {"t": ...}   (the vehicle itself too: its readings stop)
    {"op": "reset"} / {"op": "reset_world"}          -> {"t": ...}
    {"op": "info"}                                   -> {"t": ..., "step_s": ..., "mav": ..., "frames": {"odometry": ..., "imu": ...},
                                                          "controller": ..., "topics": [[topic, ROS 1 type], ...]}

Each reading of the vehicle's odometry sensor, its ground-truth odometry (ground_truth/odometry;
none for a vehicle spawned without ground truth) and its IMU taken during the steps is answered,
read from the vehicle bus. Every other topic the world's plugins publish (GPS, magnetometer,
barometer, the ground truth's pose and transform, lasers, cameras with their camera_info, ...) is
answered as the plugin built it, once asked for (op forward: a front end asks for the topics someone
subscribes to): each new message of the steps, ROS 1's serialised bytes (a front end converts them;
rosbags' ros1_to_cdr for ROS 2). Cameras included: their messages, kept only when named
(World.listen), are named here.

The controller (--controller: Lee's position controller, default, or the roll-pitch-yawrate-thrust
controller, each with the yaml files the ROS 1 launch files load; none: the motors take only
command/motor_speed) answers each odometry reading inside the engine's step loop
(World.attach_controller), as the ROS node does in lockstep; the vehicle's motor speeds
(motor_speed, RotorS' multirotor base plugin's mav_msgs/Actuators) are answered every step. A
request that cannot be served answers {"error": "..."} in one line and the world keeps
its state."""

from __future__ import annotations

import argparse
import base64
import json
import math
import os
import sys
from pathlib import Path

from rotors_sim._engine import SimError
from rotors_sim.controllers import AttitudeLevelController, LeePositionController
from rotors_sim.paths import package_path
from rotors_sim.world import World

CONTROLLERS = {"lee": LeePositionController, "roll_pitch_yawrate_thrust": AttitudeLevelController, "none": None}


def model_path(model: str | None) -> Path | None:
    """--model: a path, or the name of a model in rotors_description/urdf (SimError naming it when it
    is neither)."""
    if model is None:
        return None
    if Path(model).is_file():
        return Path(model)
    path = package_path("rotors_description") / "urdf" / f"{model}.gazebo"
    if not path.is_file():
        raise SimError(f"--model {model}: not a file, and rotors_description/urdf has no {model}.gazebo")
    return path


def finite_numbers(request: dict, op: str, key: str, n: int, default=None, then: str = "") -> list[float]:
    """request[key] as n finite numbers (one may come bare), or SimError naming op, key and the value."""
    v = request.get(key, default)
    v = [v] if n == 1 and not isinstance(v, list) else v
    if not (isinstance(v, list) and len(v) == n and all(isinstance(x, (int, float)) and math.isfinite(x) for x in v)):
        raise SimError(f"{op}: {key} {request.get(key, default)!r} must be {n} finite number{'s' if n > 1 else ''}{then}")
    return [float(x) for x in v]


class Stepper:
    """The world, its vehicle and its controller, and the requests they serve."""

    def __init__(
        self,
        mav: str,
        world: str,
        seed: int,
        xyz=(0.0, 0.0, 0.1),
        model: str | None = None,
        controller: str = "lee",
        xacro_args: dict | None = None,
    ):
        if controller not in CONTROLLERS:
            raise SimError(f"--controller {controller!r}: use one of {', '.join(CONTROLLERS)}")
        self.mav, self.controller_name = mav, controller
        self.world = World(world)
        self.mav_model = self.world.spawn_mav(mav, xyz=xyz, random_seed=seed, model=model_path(model), **(xacro_args or {}))
        self.mav_present = True  # until /delete_entity removes it
        self.controller = CONTROLLERS[controller].for_mav(mav) if CONTROLLERS[controller] else None
        if self.controller is not None:
            self.world.attach_controller(mav, self.controller)
        self.seen = {"odometry": 0, "ground_truth": 0, "imu": 0}
        # taken outside a step request, answered with the next
        self.carried: dict = {"odometry": [], "ground_truth": [], "imu": [], "motor_speed": [], "messages": []}
        self.odometry_topics = {"odometry": "odometry_sensor1/odometry"}
        topics = self.world.topics()
        if any(t == f"/{mav}/ground_truth/odometry" for t, _, _ in topics):
            self.odometry_topics["ground_truth"] = "ground_truth/odometry"
        # answered from the vehicle bus instead (above)
        self.native = {f"/{mav}/{t}" for t in (*self.odometry_topics.values(), "imu", "motor_speed")}
        # every other topic, by its plugin's ROS 1 type
        self.types = {t: kind for t, kind, _ in topics if t not in self.native}
        # those asked for (op forward), with the count of their messages answered so far
        self.forwarded: dict[str, int] = {}
        # every message is kept, the cameras' too (they are kept only when named)
        self.world.listen([t for t, _, _ in topics])

    def step(self, n: int) -> dict:
        if not (isinstance(n, int) and 0 <= n <= 100_000):
            raise SimError(f"step: n = {n!r} must be a whole number of physics steps in 0..100000")
        rows: dict[str, list] = {"odometry": [], "ground_truth": [], "imu": [], "motor_speed": []}
        messages: list[list] = self.carried["messages"]
        for _ in range(n):
            self.world.step(1)
            messages.extend(self.new_messages())
            if not self.mav_present:
                continue
            for key, topic in self.odometry_topics.items():
                o = self.world.odometry(self.mav, topic)
                if o is not None and o.count != self.seen[key]:
                    self.seen[key] = o.count
                    rows[key].append([o.time_s, *o.position_W, *o.orientation, *o.velocity_B, *o.angular_velocity_B])
            r = self.world.imu(self.mav)
            if r is not None and r.count != self.seen["imu"]:
                self.seen["imu"] = r.count
                rows["imu"].append([r.time_s, *r.angular_velocity, *r.linear_acceleration])
            # the multirotor base plugin publishes every step: the real, signed rotor speeds
            rows["motor_speed"].append([self.world.time, *self.world.rotor_speeds(self.mav)])
        answer = {key: [[float(v) for v in row] for row in self.carried[key] + rows[key]] for key in rows}
        self.carried = {key: [] for key in self.carried}
        answer["messages"] = messages
        return answer

    def new_messages(self) -> list[list]:
        """[topic, ROS 1 type, base64 bytes] of each forwarded topic's message published since the last call."""
        out = []
        if not self.forwarded:
            return out
        for topic, _, count in self.world.topics():
            if self.forwarded.get(topic, count) == count:
                continue
            self.forwarded[topic] = count
            got = self.world.engine.message(topic)  # (datatype, count, ROS 1 bytes)
            if got is not None:
                out.append([topic, got[0], base64.b64encode(got[2]).decode("ascii")])
        return out

    def frames(self) -> dict:
        """The frames the ROS 1 messages carry (their plugins' frame ids), from the first messages."""
        if self.world.message(f"/{self.mav}/imu") is None:
            self.carried = self.step(1)  # the first readings go out with the next step's answer
        frames = {}
        for key, topic in self.odometry_topics.items():
            odometry, _ = self.world.message(f"/{self.mav}/{topic}")
            frames[key], frames[f"{key}_child"] = odometry.header.frame_id, odometry.child_frame_id
        imu, _ = self.world.message(f"/{self.mav}/imu")
        frames["imu"] = imu.header.frame_id
        motors = self.world.message(f"/{self.mav}/motor_speed")
        frames["motor_speed"] = motors[0].header.frame_id if motors else f"{self.mav}/base_link"
        return frames

    def spawn(self, request: dict) -> dict:
        """A model from URDF or SDF text at a pose, as Gazebo's spawn services; its topics join the
        world's other topics (op forward sends them)."""
        xml, name = request.get("xml"), request.get("name")
        if not (isinstance(xml, str) and xml.lstrip().startswith("<")):
            raise SimError("spawn: xml must be URDF or SDF text (it starts with '<')")
        if not (isinstance(name, str) and name):
            raise SimError(f"spawn: name {name!r} must be the new model's name")
        if name in self.world.models():
            raise SimError(f"spawn: a model named '{name}' exists already")
        xyz, rpy = (finite_numbers(request, "spawn", key, 3, default=[0.0, 0.0, 0.0]) for key in ("xyz", "rpy"))
        spawned = self.world.spawn(xml, name, xyz, rpy)
        every = self.world.topics()
        self.world.listen([t for t, _, _ in every])  # its cameras' messages too
        topics = [[t, kind] for t, kind, _ in every if t not in self.types and t not in self.native]
        self.types.update(dict(topics))
        return {"name": spawned, "topics": topics}

    def command(self, op: str, request: dict) -> None:
        """A controller's command (set_point for Lee; the three attitude-level commands)."""
        wanted = "lee" if op == "set_point" else "roll_pitch_yawrate_thrust"
        if self.controller_name != wanted:
            raise SimError(f"{op}: the world runs --controller {self.controller_name}; {op} is for --controller {wanted}")

        def numbers(key: str, n: int) -> list[float]:
            return finite_numbers(request, op, key, n, then="; ignored, the last command stays in force")

        if op == "set_point":
            self.controller.set_point(numbers("position", 3), yaw=numbers("yaw", 1)[0])
        elif op == "roll_pitch_yawrate_thrust":
            args = [numbers(k, 1)[0] for k in ("roll", "pitch", "yaw_rate", "thrust")]
            self.controller.set_roll_pitch_yawrate_thrust(*args)
        elif op == "attitude_thrust":
            self.controller.set_attitude_thrust(numbers("orientation", 4), numbers("thrust", 1)[0])
        else:
            self.controller.set_rate_thrust(numbers("angular_velocity", 3), numbers("thrust", 1)[0])

    def serve(self, request: dict) -> dict:
        op = request.get("op")
        if op == "step":
            answer = self.step(request.get("n", 1))
        elif op in ("set_point", "roll_pitch_yawrate_thrust", "attitude_thrust", "rate_thrust"):
            self.command(op, request)
            answer = {}
        elif op == "motor_speeds":
            speeds = request.get("speeds")
            if not isinstance(speeds, list):
                raise SimError(f"motor_speeds: speeds {speeds!r} must be a list of rotor speeds [rad/s]")
            self.world.set_motor_speeds(self.mav, speeds)
            answer = {}
        elif op == "reset":
            self.world.reset()
            answer = {}
        elif op == "reset_world":
            self.world.reset_world()
            answer = {}
        elif op == "info":
            answer = {"step_s": self.world.step_size, "mav": self.mav, "frames": self.frames(), "controller": self.controller_name}
            answer["topics"] = [[t, kind] for t, kind in self.types.items()]
        elif op == "spawn":
            answer = self.spawn(request)
        elif op == "delete":
            name = request.get("name")
            if not (isinstance(name, str) and name):
                raise SimError(f"delete: name {name!r} must be a model's name")
            if not self.world.remove(name):
                raise SimError(f"delete: no model named '{name}' (the world has {', '.join(self.world.models()) or 'none'})")
            if name == self.mav_model:
                self.world.detach_controllers()
                self.mav_present = False
            answer = {}
        elif op == "forward":
            topics = request.get("topics")
            unknown = [t for t in topics or [] if t not in self.types] if isinstance(topics, list) else None
            if unknown is None or unknown:
                raise SimError(f"forward: {unknown or topics!r}: not among the world's other topics (op info lists them)")
            counts = {t: n for t, _, n in self.world.topics()}
            # a topic asked for anew starts with its next message
            self.forwarded = {t: self.forwarded.get(t, counts[t]) for t in topics}
            answer = {}
        else:
            raise SimError(
                f"unknown op {op!r}; use step, set_point, roll_pitch_yawrate_thrust, attitude_thrust, rate_thrust, "
                "motor_speeds, forward, spawn, delete, reset, reset_world or info"
            )
        answer["t"] = self.world.time
        return answer


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mav", default="firefly")
    parser.add_argument("--world", default="basic")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--model", default=None, help="rotors_description/urdf/<model>.gazebo, or a path (default: the generic odometry sensor's)"
    )
    parser.add_argument("--controller", default="lee", help=f"one of {', '.join(CONTROLLERS)} (default lee)")
    parser.add_argument("xacro_args", nargs="*", metavar="name:=value", help="further xacro arguments of the vehicle")
    args = parser.parse_args(argv)
    bad = [a for a in args.xacro_args if ":=" not in a]
    xacro_args = dict(a.split(":=", 1) for a in args.xacro_args if ":=" in a)
    # the answers keep stdout's pipe; everything else the process prints (the plugins' log lines)
    # goes to stderr, so that no line of theirs lands among the answers
    answers = os.fdopen(os.dup(sys.stdout.fileno()), "w")
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())

    def answer(obj: dict) -> None:
        answers.write(json.dumps(obj) + "\n")
        answers.flush()

    try:
        if bad:
            raise SimError(f"{' '.join(bad)}: a xacro argument is name:=value")
        stepper = Stepper(args.mav, args.world, args.seed, model=args.model, controller=args.controller, xacro_args=xacro_args)
    except SimError as e:
        answer({"error": str(e)})
        return 1
    answer({"ready": True, "t": stepper.world.time})
    for line in sys.stdin:
        try:
            answer(stepper.serve(json.loads(line)))
        except (SimError, ValueError, TypeError) as e:
            answer({"error": str(e)})
    return 0


if __name__ == "__main__":
    sys.exit(main())
