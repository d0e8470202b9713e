"""An rclpy client of the ROS 2 front end (run with build/ros2-venv's python in scripts/ros2_env.bash's
environment): it finds the simulator through ROS 2's graph queries, measures the odometry and IMU
rates over 2 s of sim time, sends the hovering example's set point (0, 0, 1) on command/trajectory,
watches the firefly reach it, and calls /reset_simulation. Prints RESULT=<json>. Every wait is
bounded, and all of them together by the budget given as the first argument [s of wall time]."""

import sys

import rclpy
from budget import Budget, report
from geometry_msgs.msg import Transform
from nav_msgs.msg import Odometry
from rclpy.parameter import Parameter
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

ODOMETRY, IMU = "/firefly/odometry_sensor1/odometry", "/firefly/imu"
SERVICES = {"/reset_simulation", "/reset_world", "/pause_physics", "/unpause_physics", "/spawn_entity", "/delete_entity"}


def seconds(stamp) -> float:
    return stamp.sec + stamp.nanosec * 1e-9


def main() -> None:
    rclpy.init()
    node = rclpy.create_node("hover_client", parameter_overrides=[Parameter("use_sim_time", Parameter.Type.BOOL, True)])
    result: dict = {}
    state = {"clock": -1.0, "odometry": [], "imu": []}
    node.create_subscription(Clock, "/clock", lambda m: state.update(clock=seconds(m.clock)), 10)
    node.create_subscription(
        Odometry,
        ODOMETRY,
        lambda m: state["odometry"].append((seconds(m.header.stamp), m.header.frame_id, m.child_frame_id, m.pose.pose.position.z)),
        100,
    )
    node.create_subscription(
        Imu, IMU, lambda m: state["imu"].append((seconds(m.header.stamp), m.header.frame_id, m.linear_acceleration.z)), 100
    )

    budget = Budget(node, float(sys.argv[1]), "hover_client")

    def graph_ready() -> bool:
        topics = dict(node.get_topic_names_and_types())
        services = {name for name, _ in node.get_service_names_and_types()}
        return "gazebo" in node.get_node_names() and {ODOMETRY, IMU, "/clock"} <= set(topics) and SERVICES <= services

    # topics and services are discovered one by one: wait for all of them
    budget.until(graph_ready, "the simulator's node, topics and services in the graph", 60)
    result["nodes"] = node.get_node_names()
    result["topics"] = {k: v for k, v in node.get_topic_names_and_types() if k.startswith(("/firefly", "/clock"))}
    result["services"] = [name for name, _ in node.get_service_names_and_types() if name in SERVICES]

    # the rates over 2 s of sim time
    budget.until(lambda: state["clock"] > 0.5, "sim time past 0.5 s", 60)
    t0 = state["clock"]
    budget.until(lambda: state["clock"] >= t0 + 2.0, "2 s more of sim time", 60)
    for name in ("odometry", "imu"):  # messages per second of their own stamps
        stamps = [m[0] for m in state[name] if t0 <= m[0] <= t0 + 2.0]
        result[f"{name}_hz"] = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        result[f"{name}_gaps"] = sum(b - a > 0.015 for a, b in zip(stamps, stamps[1:]))  # a lost message
    result["odometry_frames"] = [state["odometry"][-1][1], state["odometry"][-1][2]]
    result["imu_frame"] = state["imu"][-1][1]
    result["imu_z_at_rest"] = state["imu"][-1][2]
    result["sim_time_now_minus_clock"] = node.get_clock().now().nanoseconds * 1e-9 - state["clock"]
    result["z_before"] = state["odometry"][-1][3]

    # the hovering example's set point
    pub = node.create_publisher(MultiDOFJointTrajectory, "/firefly/command/trajectory", 10)
    budget.until(lambda: pub.get_subscription_count() > 0, "the simulator subscribed to command/trajectory", 30)
    msg = MultiDOFJointTrajectory(points=[MultiDOFJointTrajectoryPoint(transforms=[Transform()])])
    msg.points[0].transforms[0].translation.z = 1.0
    msg.points[0].transforms[0].rotation.w = 1.0
    pub.publish(msg)
    t_sent = state["clock"]
    budget.until(lambda: state["clock"] >= t_sent + 10.0, "10 s of sim time after the set point", 120)
    last_2_s = [m[3] for m in state["odometry"] if m[0] > t_sent + 8.0]
    result["z_after_10_s"] = state["odometry"][-1][3]
    result["z_offset_last_2_s"] = sum(last_2_s) / len(last_2_s) - 1.0

    # reset_simulation: time and vehicle back to the start
    client = node.create_client(Empty, "/reset_simulation")
    budget.until(client.service_is_ready, "/reset_simulation available", 30)
    future = client.call_async(Empty.Request())
    budget.until(future.done, "/reset_simulation answered", 30)
    state["odometry"].clear()
    budget.until(lambda: state["odometry"] and state["odometry"][-1][0] < 1.0, "odometry from before 1 s of sim time after the reset", 30)
    result["clock_after_reset"] = state["odometry"][-1][0]
    result["z_after_reset"] = state["odometry"][-1][3]
    report(node, result)


if __name__ == "__main__":
    main()
