"""An rclpy client of the ROS 2 front end's mav_msgs topics (run with build/ros2-venv's python in
scripts/ros2_env.bash's environment; the simulator started with --controller none or
roll_pitch_yawrate_thrust). It finds motor_speed and the command topics in the graph with their
mav_msgs types, then flies:
- none: command/motor_speed at 600 rad/s (above the firefly's hover speed): the rotors spin up to it
  (motor_speed, signed as the rotors turn) and the firefly climbs; a NaN and a short command change
  nothing; 0 rad/s stops the rotors;
- roll_pitch_yawrate_thrust: command/roll_pitch_yawrate_thrust with roll 0.1 rad and 1.1 m g of
  thrust: the firefly lifts off and holds the roll.
Prints RESULT=<json>. Every wait is bounded, and all together by the budget in argv[2] [s of wall time]."""

import math
import sys

import rclpy
from budget import Budget, report
from mav_msgs.msg import Actuators, RollPitchYawrateThrust
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock

ODOMETRY, MOTOR_SPEED = "/firefly/odometry_sensor1/odometry", "/firefly/motor_speed"
FIREFLY_MASS_KG, G = 1.56779, 9.81  # resource/firefly.yaml's mass (body, rotors, sensors), as Lee's yaml


def seconds(stamp) -> float:
    return stamp.sec + stamp.nanosec * 1e-9


def roll_of(q) -> float:
    return math.atan2(2.0 * (q.w * q.x + q.y * q.z), 1.0 - 2.0 * (q.x * q.x + q.y * q.y))


def main() -> None:
    mode = sys.argv[1]
    rclpy.init()
    node = rclpy.create_node("command_client")
    state = {"clock": -1.0, "odometry": [], "motor_speed": []}
    node.create_subscription(Clock, "/clock", lambda m: state.update(clock=seconds(m.clock)), 10)
    node.create_subscription(
        Odometry,
        ODOMETRY,
        lambda m: state["odometry"].append((seconds(m.header.stamp), m.pose.pose.position.z, roll_of(m.pose.pose.orientation))),
        100,
    )
    node.create_subscription(
        Actuators,
        MOTOR_SPEED,
        lambda m: state["motor_speed"].append((seconds(m.header.stamp), m.header.frame_id, list(m.angular_velocities))),
        100,
    )

    budget = Budget(node, float(sys.argv[2]), "command_client")

    def sim_seconds(duration_s: float, what: str) -> None:
        t = state["clock"]
        budget.until(lambda: state["clock"] >= t + duration_s, what, 60)

    command = "/firefly/command/motor_speed" if mode == "none" else "/firefly/command/roll_pitch_yawrate_thrust"
    budget.until(lambda: MOTOR_SPEED in dict(node.get_topic_names_and_types()) and state["motor_speed"], "motor_speed in the graph", 60)
    pub = node.create_publisher(Actuators if mode == "none" else RollPitchYawrateThrust, command, 10)
    budget.until(lambda: pub.get_subscription_count() > 0, f"the simulator subscribed to {command}", 30)
    topics = dict(node.get_topic_names_and_types())
    result: dict = {"types": {t: topics[t] for t in (MOTOR_SPEED, command)}}
    result["motor_speed_frame"] = state["motor_speed"][-1][1]
    sim_seconds(0.5, "0.5 s of sim time")
    result["z_start"] = state["odometry"][-1][1]
    if mode == "none":

        def hold(speeds: list[float], duration_s: float, what: str) -> None:
            """Sends the command every 0.1 s of sim time, as a controller does (the controller interface
            stops the motors after commandTimeout without a command)."""
            t_end = state["clock"] + duration_s
            while state["clock"] < t_end:
                pub.publish(Actuators(angular_velocities=speeds))
                next_s = min(state["clock"] + 0.1, t_end)
                budget.until(lambda next_s=next_s: state["clock"] >= next_s, what, 30)

        hold([600.0] * 6, 2.0, "2 s of sim time at 600 rad/s")
        result["speeds_at_600"] = state["motor_speed"][-1][2]
        result["z_at_600"] = state["odometry"][-1][1]
        pub.publish(Actuators(angular_velocities=[math.nan] * 6))  # refused in one line: 600 stays
        pub.publish(Actuators(angular_velocities=[100.0] * 3))  # too short: refused, 600 stays
        sim_seconds(0.5, "0.5 s of sim time after two bad commands")
        result["speeds_after_bad"] = state["motor_speed"][-1][2]
        hold([0.0] * 6, 1.0, "1 s of sim time at 0 rad/s")
        result["speeds_at_0"] = state["motor_speed"][-1][2]
    else:
        msg = RollPitchYawrateThrust(roll=0.1)
        msg.thrust.z = 1.1 * FIREFLY_MASS_KG * G
        pub.publish(msg)
        t_sent = state["clock"]
        sim_seconds(1.5, "1.5 s of sim time after the command")
        late = [o for o in state["odometry"] if o[0] > t_sent + 1.0]
        result["roll_after_1_s"] = sum(o[2] for o in late) / len(late)
        result["z_after_1_5_s"] = state["odometry"][-1][1]
    report(node, result)


if __name__ == "__main__":
    main()
