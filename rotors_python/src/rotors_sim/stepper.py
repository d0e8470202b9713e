"""A world stepped over a pipe: the simulator side of a front end that cannot import rotors_sim in its
own process. ROS 2's Python message packages (PyPI's Jazzy wheels) and ROS 1's (Debian's, which
xacro and rospkg load) share module names (sensor_msgs, rosgraph_msgs, ...), so the ROS 2 front end
(rotors_gazebo_compat/rotors_ros2) runs this in a child process with ROS 1's environment.

    python3 -m rotors_sim.stepper --mav firefly --world basic --seed 0

One JSON object per line on stdin, one answer per line on stdout:

    {"op": "step", "n": 10}                          -> {"t": ..., "odometry": [[t, p(3), q xyzw(4), v_B(3), w_B(3)], ...],
                                                          "ground_truth": [... as odometry],
                                                          "imu": [[t, gyro(3), specific force(3)], ...]}
    {"op": "set_point", "position": [x, y, z], "yaw": 0.0} -> {"t": ...}
    {"op": "reset"} / {"op": "reset_world"}          -> {"t": ...}
    {"op": "info"}                                   -> {"t": ..., "step_s": ..., "mav": ..., "frames": {"odometry": ..., "imu": ...}}

Each reading of the vehicle's odometry sensor, its ground-truth odometry (ground_truth/odometry;
none for a vehicle spawned without ground truth) and its IMU taken during the steps is answered,
read from the vehicle bus. Lee's position controller (the hovering example's yaml files) answers each
odometry reading inside the engine's step loop (World.attach_controller), as the ROS node does in
lockstep. A request that cannot be served answers {"error": "..."} in one line and the world keeps
its state."""

from __future__ import annotations

import argparse
import json
import os
import sys

from rotors_sim._engine import SimError
from rotors_sim.controllers import LeePositionController
from rotors_sim.world import World


class Stepper:
    """The world, its vehicle and its controller, and the requests they serve."""

    def __init__(self, mav: str, world: str, seed: int, xyz=(0.0, 0.0, 0.1)):
        self.mav = mav
        self.world = World(world)
        self.world.spawn_mav(mav, xyz=xyz, random_seed=seed)
        self.lee = LeePositionController.for_mav(mav)
        self.world.attach_controller(mav, self.lee)
        self.seen = {"odometry": 0, "ground_truth": 0, "imu": 0}
        self.carried: dict = {"odometry": [], "ground_truth": [], "imu": []}  # readings taken outside a step request
        self.odometry_topics = {"odometry": "odometry_sensor1/odometry"}
        if any(t == f"/{mav}/ground_truth/odometry" for t, _, _ in self.world.topics()):
            self.odometry_topics["ground_truth"] = "ground_truth/odometry"

    def step(self, n: int) -> dict:
        if not (isinstance(n, int) and 0 <= n <= 100_000):
            raise SimError(f"step: n = {n!r} must be a whole number of physics steps in 0..100000")
        rows: dict[str, list] = {key: [] for key in self.carried}
        for _ in range(n):
            self.world.step(1)
            for key, topic in self.odometry_topics.items():
                o = self.world.odometry(self.mav, topic)
                if o is not None and o.count != self.seen[key]:
                    self.seen[key] = o.count
                    rows[key].append([o.time_s, *o.position_W, *o.orientation, *o.velocity_B, *o.angular_velocity_B])
            r = self.world.imu(self.mav)
            if r is not None and r.count != self.seen["imu"]:
                self.seen["imu"] = r.count
                rows["imu"].append([r.time_s, *r.angular_velocity, *r.linear_acceleration])
        answer = {key: [[float(v) for v in row] for row in self.carried[key] + rows[key]] for key in rows}
        self.carried = {key: [] for key in self.carried}
        return answer

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
        return frames

    def serve(self, request: dict) -> dict:
        op = request.get("op")
        if op == "step":
            answer = self.step(request.get("n", 1))
        elif op == "set_point":
            position = request.get("position")
            if not (isinstance(position, list) and len(position) == 3):
                raise SimError(f"set_point: position {position!r} must be 3 numbers [m]")
            self.lee.set_point([float(v) for v in position], yaw=float(request.get("yaw", 0.0)))
            answer = {}
        elif op == "reset":
            self.world.reset()
            answer = {}
        elif op == "reset_world":
            self.world.reset_world()
            answer = {}
        elif op == "info":
            answer = {"step_s": self.world.step_size, "mav": self.mav, "frames": self.frames()}
        else:
            raise SimError(f"unknown op {op!r}; use step, set_point, reset, reset_world or info")
        answer["t"] = self.world.time
        return answer


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mav", default="firefly")
    parser.add_argument("--world", default="basic")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    # the answers keep stdout's pipe; everything else the process prints (the plugins' log lines)
    # goes to stderr, so that no line of theirs lands among the answers
    answers = os.fdopen(os.dup(sys.stdout.fileno()), "w")
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())

    def answer(obj: dict) -> None:
        answers.write(json.dumps(obj) + "\n")
        answers.flush()

    try:
        stepper = Stepper(args.mav, args.world, args.seed)
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
