"""Fuzzing: every topic and service the simulator and the nodes of the book's hovering example (plus
the estimator, the attitude controller and the joystick mapping, running beside it) subscribe to or
serve receives, for a bounded time each, random invalid and extreme messages, built
from the message definition itself:

- invalid (1 s at 100 Hz per topic): every float NaN or +-inf, arrays empty, of one element or
  1,000 long, zero quaternions; integers at their type's extremes;
- extreme (1 s at 100 Hz per topic): finite but absurd: +-1e30, 1e-300, stamps at 0 and in 2038,
  wrong and 10,000-character frame ids, time_from_start and durations at the int32 limits.

Nothing may crash, the physics state stays finite throughout, the MAV keeps hovering while the
inputs are invalid (extreme ones may be valid commands: a 1e30 m set point is flown towards at the
tilt limit, so afterwards the set point is sent again and the MAV must come back), and rejections
are rate-limited (a handful of log lines per second, not one per message; Debian's
robot_state_publisher, not ours, logs each invalid JointState). The test prints a table.

Left out, with the reason: /clock (the simulator's own output: a second publisher is a set-up error,
not an input), /rosout (ROS' log aggregation), the Empty services pause/unpause/reset (no payload;
their effects are tested in test_faults.py) and roscpp's get_loggers/set_logger_level."""

from pathlib import Path

import pytest

import clients.fuzz
from support import RosGraph, stop_launch, wait_sim_time

WATCHED = [
    "/gazebo",
    "/firefly/lee_position_controller_node",
    "/firefly/robot_state_publisher",
    "/bystanders/msf",
    "/bystanders/roll_pitch_yawrate_thrust_controller_node",
    "/bystanders/rotors_joy_interface",
    "/bystanders/planner",
    "/bystanders/mapping",
    "/bystanders/omav_pose_controller_node",
    "/bystanders/fixed_wing_joy_interface",
]

# The hovering example with the camera gimbal (its command topics in the simulator), plus the
# project's other input-taking nodes outside its control loop ("bystanders": the estimator, the
# attitude controller, the joystick mapping for multirotors and for the fixed wing, the planner, the
# mapping node and the omav's pose controller), so that their inputs are fuzzed too without steering
# the MAV.
FUZZ_LAUNCH = """<launch>
  <include file="$(find rotors_gazebo)/launch/mav_hovering_example.launch">
    <arg name="real_time_factor" value="1"/>
    <arg name="gui" value="false"/>
    <arg name="enable_gimbal" value="true"/>
  </include>
  <group ns="bystanders">
    <node name="msf" pkg="msf_updates" type="pose_sensor" clear_params="true" output="screen">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/msf_simulator.yaml"/>
    </node>
    <node name="roll_pitch_yawrate_thrust_controller_node" pkg="rotors_control"
          type="roll_pitch_yawrate_thrust_controller_node" output="screen">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/roll_pitch_yawrate_thrust_controller_firefly.yaml"/>
      <rosparam command="load" file="$(find rotors_gazebo)/resource/firefly.yaml"/>
    </node>
    <node name="rotors_joy_interface" pkg="rotors_joy_interface" type="rotors_joy_interface" output="screen"/>
    <node name="fixed_wing_joy_interface" pkg="rotors_joy_interface" type="rotors_joy_interface" output="screen">
      <param name="is_fixed_wing" value="true"/>
      <remap from="joy" to="fixed_wing_joy"/>
    </node>
    <node name="planner" pkg="rotors_planning" type="rotors_planner_node" output="screen">
      <param name="map_source" value="topic"/>
      <param name="robot_radius" value="0.3"/>
    </node>
    <node name="mapping" pkg="rotors_planning" type="rotors_mapping_node" output="screen">
      <param name="frame_id" value="world"/>
    </node>
    <node name="omav_pose_controller_node" pkg="rotors_control" type="omav_pose_controller_node" output="screen">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/omav_pose_controller.yaml"/>
      <rosparam command="load" file="$(find rotors_gazebo)/resource/omav.yaml"/>
    </node>
  </group>
</launch>
"""
# Debian's robot_state_publisher (not ours) logs one line per invalid JointState, and tf2's
# BufferCore (in every node with a tf2 listener, here the mapping node) one per invalid transform;
# neither may crash.
NOT_RATE_LIMITED_UPSTREAM = {"/firefly/joint_states", "/tf", "/tf_static"}


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_fuzzing_every_input_of_the_hovering_example(ros: RosGraph, tmp_path: Path):
    launch_file = tmp_path / "fuzz.launch"
    launch_file.write_text(FUZZ_LAUNCH)
    proc = ros.start(["roslaunch", "-p", str(ros.port), str(launch_file)], "launch")
    try:
        wait_sim_time(ros, 10.0)
        res = ros.run_client(clients.fuzz.fuzz_every_input, timeout=900, log_path=str(Path(proc.log_path)), watched=WATCHED)
    finally:
        stop_launch(proc)
    rows = res["rows"]
    header = (
        f"{'topic / service':44} {'type':36} {'invalid':>7} {'extreme':>7} {'crashes':>7} {'non-finite':>10} "
        f"{'offset (inv.)':>13} {'log lines/s':>11} {'back':>5}"
    )
    print("\n" + header + "\n" + "-" * len(header))
    for r in rows:
        lines_per_s = max(r["invalid_log_lines"], r["extreme_log_lines"])
        print(
            f"{r['name']:44} {r['type']:36} {r['invalid']:7d} {r['extreme']:7d} {len(r['crashed']):7d} "
            f"{0 if r['finite'] else 1:10d} {r['invalid_offset'] * 1000:10.1f} mm {lines_per_s:11d} "
            f"{'yes' if r['recovered'] else 'reset':>5}"
        )
    print(f"{len(rows)} inputs, {sum(r['invalid'] + r['extreme'] for r in rows)} messages and calls, " f"{res['samples']} states sampled")
    names = {r["name"] for r in rows}
    for expected in (
        "/firefly/command/motor_speed",
        "/firefly/gazebo/command/motor_speed",
        "/firefly/command/trajectory",
        "/firefly/command/pose",
        "/firefly/odometry_sensor1/odometry",
        "/firefly/motor_failure",
        "/gazebo/spawn_urdf_model",
        "/gazebo/delete_model",
        "/firefly/set_motor_failure",
        "/bystanders/msf_core/imu_state_input",
        "/bystanders/msf_updates/pose_with_covariance_input",
        "/bystanders/command/roll_pitch_yawrate_thrust",
        "/bystanders/joy",
        "/bystanders/msf/pose_sensor/initialize_msf_scale",
        "/bystanders/fixed_wing_joy",
        "/bystanders/goal",
        "/bystanders/octomap_binary",
        "/bystanders/cloud_in",
        "/firefly/gimbal_pitch_cmd",
    ):
        assert expected in names, f"{expected} was not fuzzed: {sorted(names)}"
    for r in rows:
        assert r["crashed"] == [], f"{r['name']}: {r['crashed']} crashed"
        assert r["finite"], f"{r['name']}: the physics state became non-finite"
        assert r["invalid_offset"] < 0.05, f"{r['name']}: invalid input moved the MAV {r['invalid_offset']:.3f} m"
        assert r["name"] in NOT_RATE_LIMITED_UPSTREAM or (
            r["invalid_log_lines"] <= 12 and r["extreme_log_lines"] <= 12
        ), f"{r['name']}: {r['invalid_log_lines']} / {r['extreme_log_lines']} log lines in 1 s: not rate-limited"
        assert r["recovered"], f"{r['name']}: the MAV did not come back to its set point after the extreme inputs"
