#!/usr/bin/env python3
"""The book's hovering example (section 3.3) on ROS 2, with mav_hovering_example.launch's arguments
in roslaunch's form (docs/ros2.md):

    source scripts/ros2_env.bash
    python rotors_gazebo_compat/rotors_ros2/mav_hovering_example.py enable_logging:=true gui:=false

It starts the simulator node (rotors_ros2_sim.py, paused as the launch starts Gazebo), with
enable_logging:=true a recorder (rosbag2_record.py: a ROS 2 bag in $ROS_HOME, default ~/.ros, named
<log_file>_<date> as the ROS 1 bag plugin names its bag), and the hovering example node: once the
simulator and the recorder listen, it sends the waypoint (x, y, z, yaw; default 0, 0, 1, 0) on
command/trajectory due 5 s of sim time after the start, then unpauses the simulation, as the ROS 1
hovering_example does. sim_seconds:=T (ours) stops everything after T s of sim time (and fails when
sim time stands still for 30 s of wall time first); without it, Ctrl-C stops. The launch file's
arguments that are xacro arguments of the vehicle (sensor_realism, mass_scale, enable_navigation_sensors,
..., xacro_args:="a:=1 b:=2") go to the simulator's spawn as spawn_mav.launch passes them. An
argument the ROS 2 front end does not serve yet is refused in one line. mav_hovering_example_with_vi_sensor.py
is the same with the VI-sensor model and that launch file's own arguments."""

from __future__ import annotations

import math
import os
import shlex
import signal
import subprocess
import sys
import time
from datetime import datetime
from pathlib import Path

HERE = Path(__file__).resolve().parent
# wall-time budgets, 165 s together for a run that fails at any point (the ROS 2 test gives the
# whole graph 240 s): the start-up (the simulator, the recorder and the services
# found) shares one; sim time that stands still while it should run, the pause at the end, and the
# children's stop each have their own. The recorder drains for up to 30 s before it closes its bag.
STARTUP_S, STALLED_S, PAUSE_S = 60.0, 30.0, 15.0
STOP_S = {"rosbag2_record.py": 40.0, "rotors_ros2_sim.py": 20.0}

# mav_hovering_example.launch's arguments that the ROS 2 front end serves, with their defaults
ARGUMENTS = {
    "mav_name": "firefly",
    "world_name": "basic",
    "enable_logging": "false",
    "enable_ground_truth": "true",
    "log_file": None,  # the mav_name
    "gui": "false",
    "paused": "true",
    "real_time_factor": "1",
    "random_seed": "0",
    "lockstep": "true",  # the controller runs in the world's step loop: always in lockstep on ROS 2
    "x": "0.0",
    "y": "0.0",
    "z": "1.0",
    "yaw": "0.0",
    "sim_seconds": "0",
}
# its arguments that spawn_mav.launch passes to the vehicle's xacro, with their defaults
XACRO_ARGUMENTS = {
    "sensor_realism": "false",
    "mass_scale": "1",
    "motor_constant_scale": "1",
    "enable_navigation_sensors": "false",
    "enable_lidar": "none",
    "enable_gimbal": "false",
    "xacro_args": "",
}
NOT_YET = {
    "gui": "no rviz on ROS 2 here (gui:=false)",
    "enable_ground_truth": "ground truth is always published on ROS 2",
    "lockstep": "the controller runs in the world's step loop on ROS 2, always in lockstep",
}


def parse(argv: list[str], xacro_arguments: dict | None = None) -> dict:
    """The arguments with their defaults; those for the vehicle's xacro that were given, as name:=value
    strings, under "xacro"."""
    xacro_arguments = XACRO_ARGUMENTS if xacro_arguments is None else xacro_arguments
    known = {**ARGUMENTS, **xacro_arguments}
    args, xacro = dict(ARGUMENTS), []
    for item in argv:
        name, sep, value = item.partition(":=")
        if not sep:
            raise SystemExit(f"mav_hovering_example: '{item}' is not name:=value")
        if name not in known:
            raise SystemExit(
                f"mav_hovering_example: argument '{name}' is not served on ROS 2 yet (docs/ros2.md); "
                f"the ROS 2 hovering example takes: {', '.join(known)}"
            )
        if name == "xacro_args":
            bad = [a for a in shlex.split(value) if ":=" not in a]
            if bad:
                raise SystemExit(f"mav_hovering_example: xacro_args: {' '.join(bad)} is not name:=value")
            xacro += shlex.split(value)
        elif name in xacro_arguments:
            xacro.append(f"{name}:={value}")
        else:
            args[name] = value
    args["xacro"] = xacro
    for name, wanted in (("gui", "false"), ("enable_ground_truth", "true"), ("lockstep", "true")):
        if args[name].lower() != wanted:
            raise SystemExit(f"mav_hovering_example: {name}:={args[name]} is not served: {NOT_YET[name]}")
    for name in ("enable_logging", "paused"):
        if args[name].lower() not in ("true", "false"):
            raise SystemExit(f"mav_hovering_example: {name}:={args[name]} must be true or false")
    for name in ("real_time_factor", "x", "y", "z", "yaw", "sim_seconds"):
        try:
            float(args[name])
        except ValueError:
            raise SystemExit(f"mav_hovering_example: {name}:={args[name]} is not a number") from None
    args["log_file"] = args["log_file"] or args["mav_name"]
    return args


def main(argv: list[str], model: str | None = None, xacro_arguments: dict | None = None, recorded_extra: tuple = ()) -> int:
    """The example; `model`, `xacro_arguments` and the further topics its bag records (relative to the
    vehicle's namespace) for a launch file that spawns another model."""
    args = parse(argv, xacro_arguments)
    import rclpy  # after the arguments: a wrong one costs no start-up
    from geometry_msgs.msg import Transform
    from rclpy.parameter import Parameter
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import Empty
    from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

    mav = args["mav_name"]
    children: list[subprocess.Popen] = []
    sim_cmd = [sys.executable, str(HERE / "rotors_ros2_sim.py"), "--mav", mav, "--world", args["world_name"]]
    sim_cmd += ["--seed", args["random_seed"], "--real-time-factor", args["real_time_factor"]]
    sim_cmd += ["--paused"] if args["paused"] == "true" else []
    sim_cmd += ["--model", model] if model else []
    sim_cmd += args["xacro"]
    children.append(subprocess.Popen(sim_cmd))
    recorded = [f"/{mav}/ground_truth/odometry", f"/{mav}/odometry_sensor1/odometry", f"/{mav}/imu", f"/{mav}/command/trajectory"]
    recorded += [f"/{mav}/{topic}" for topic in recorded_extra]
    if args["enable_logging"] == "true":
        ros_home = Path(os.environ.get("ROS_HOME", Path.home() / ".ros"))
        ros_home.mkdir(parents=True, exist_ok=True)
        bag = ros_home / f"{args['log_file']}_{datetime.now().strftime('%Y-%m-%d-%H-%M-%S')}"
        children.append(subprocess.Popen([sys.executable, str(HERE / "rosbag2_record.py"), "-o", str(bag), *recorded]))
        print(f"[mav_hovering_example] recording {bag}", flush=True)

    rclpy.init(args=[sys.argv[0]])  # the name:=value arguments are ours, not ROS remaps
    node = rclpy.create_node("hovering_example", namespace=mav, parameter_overrides=[Parameter("use_sim_time", value=True)])
    clock = {"t": 0.0}
    node.create_subscription(Clock, "/clock", lambda m: clock.update(t=m.clock.sec + m.clock.nanosec * 1e-9), 10)
    pub = node.create_publisher(MultiDOFJointTrajectory, "command/trajectory", 10)

    def ended() -> str | None:
        for child in children:
            if child.poll() is not None:
                return f"{Path(child.args[1]).name} ended (exit code {child.returncode})"
        return None

    def wait(condition, what: str, deadline: float) -> None:
        """Spins until condition(); SystemExit naming `what` when a child ends or the deadline passes."""
        while not condition():
            why = ended()
            if why or time.monotonic() > deadline:
                raise SystemExit(f"mav_hovering_example: {what}: {why or 'not within its time'}")
            rclpy.spin_once(node, timeout_sec=0.05)

    stopping = {"now": False}
    signal.signal(signal.SIGTERM, lambda *_: stopping.update(now=True))
    code = 0
    try:
        # the simulator listens for set points, and the recorder (if any) to every recorded topic
        startup = time.monotonic() + STARTUP_S
        listeners = 1 + (args["enable_logging"] == "true")
        wait(
            lambda: pub.get_subscription_count() >= listeners,
            f"the simulator and the recorder did not subscribe in {STARTUP_S:.0f} s",
            startup,
        )
        if args["enable_logging"] == "true":
            wait(lambda: all(node.count_subscribers(t) >= 1 for t in recorded), "the recorder did not subscribe to every topic", startup)
        unpause = node.create_client(Empty, "/unpause_physics")
        wait(lambda: unpause.service_is_ready(), "the simulator's /unpause_physics did not appear", startup)
        point = MultiDOFJointTrajectoryPoint(transforms=[Transform()])
        t = point.transforms[0]
        t.translation.x, t.translation.y, t.translation.z = (float(args[k]) for k in ("x", "y", "z"))
        yaw = float(args["yaw"])
        t.rotation.z, t.rotation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
        msg = MultiDOFJointTrajectory(points=[point])
        due_ns = int(round((clock["t"] + 5.0) * 1e9))  # due 5 s of sim time from now
        msg.header.stamp.sec, msg.header.stamp.nanosec = due_ns // 1_000_000_000, due_ns % 1_000_000_000
        pub.publish(msg)
        waypoint = f"[{t.translation.x}, {t.translation.y}, {t.translation.z}, {yaw}]"
        node.get_logger().info(f"Publishing waypoint on namespace /{mav}: {waypoint}, due at t = {due_ns * 1e-9:.1f} s.")
        future = unpause.call_async(Empty.Request())
        wait(lambda: future.done(), "/unpause_physics did not answer", startup)
        node.get_logger().info("Unpaused the simulation.")
        sim_seconds = float(args["sim_seconds"])
        last_t, moved = clock["t"], time.monotonic()
        while not stopping["now"] and (sim_seconds <= 0.0 or clock["t"] < sim_seconds):
            why = ended()
            if clock["t"] != last_t:
                last_t, moved = clock["t"], time.monotonic()
            elif sim_seconds > 0.0 and time.monotonic() - moved > STALLED_S:  # a bounded run only: a user may pause
                why = f"sim time stood still at {last_t:.2f} s for {STALLED_S:.0f} s"
            if why:
                print(f"mav_hovering_example: {why}", file=sys.stderr)
                code = 1
                break
            rclpy.spin_once(node, timeout_sec=0.1)
        print(f"[mav_hovering_example] simulated {clock['t']:.1f} s", flush=True)
        if args["enable_logging"] == "true" and ended() is None:  # the recorder gets what is on its way
            pause = node.create_client(Empty, "/pause_physics")
            paused = pause.call_async(Empty.Request())
            wait(lambda: paused.done(), "/pause_physics did not answer", time.monotonic() + PAUSE_S)
    except KeyboardInterrupt:
        pass
    except SystemExit as e:
        print(e, file=sys.stderr)
        code = 1
    finally:
        for child in reversed(children):  # the recorder first: it closes its bag
            if child.poll() is None:
                child.send_signal(signal.SIGINT)
            try:
                child.wait(timeout=STOP_S[Path(child.args[1]).name])
            except subprocess.TimeoutExpired:
                child.kill()
        node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
