"""Wind, end to end: RotorS' wind-gust example (broken upstream) flown and evaluated, RotorS'
custom static wind field on the flying MAV (the published wind speed is the field's value at the
MAV's position), and the wind speed driven from a topic."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import clients.wind
from rotors_evaluation.bag_data import load_flight
from support import REPO, RosGraph, stop_launch, wait_sim_time

EVAL = REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "scripts" / "disturbance_eval.py"


def fly(ros: RosGraph, tmp_path: Path, launch_file: str, **args: str):
    """roslaunch through an include (its command line refuses values holding ':=')."""
    lines = "".join(f'<arg name="{k}" value="{v}"/>' for k, v in args.items())
    flight = tmp_path / "flight.launch"
    flight.write_text(
        f'<launch><include file="$(find rotors_gazebo)/launch/{launch_file}">'
        f'<arg name="gui" value="false"/><arg name="lockstep" value="true"/>{lines}</include></launch>'
    )
    return ros.start(["roslaunch", "-p", str(ros.port), str(flight)], "launch")


def test_wind_gust_example_flies_and_disturbance_eval_scores_it(ros: RosGraph, tmp_path: Path):
    proc = fly(ros, tmp_path, "mav_with_wind_gust.launch", enable_logging="true", real_time_factor="20", log_file="gust")
    try:
        wait_sim_time(ros, 52.0)
    finally:
        stop_launch(proc)
    bag = next(Path(ros.env["ROS_HOME"]).glob("gust_*.bag"))
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench")
    offset = data.position.window(40.0, 44.0).values - data.position.window(39.0, 40.0).values.mean(axis=0)
    peak = offset[np.argmax(np.linalg.norm(offset[:, :2], axis=1))]
    angle = np.degrees(np.arctan2(peak[1], peak[0]))
    print(f"gust 5 N along (1, 1, 0) for 2 s: peak horizontal offset {np.linalg.norm(peak[:2]):.3f} m at {angle:.1f} deg")
    assert np.linalg.norm(peak[:2]) > 0.1 and abs(angle - 45.0) < 5.0
    res = subprocess.run(
        [sys.executable, str(EVAL), "-b", str(bag), "-n", "firefly", "--plot", "False", "--json", "-"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert res.returncode == 0, res.stderr
    print(res.stdout[: res.stdout.index("{")])
    summary = json.loads(res.stdout[res.stdout.index("{") :])
    assert summary["segments"][0]["settling_time"] is not None and summary["settling_time"] < 10.0


def test_custom_static_wind_field_and_wind_from_a_topic(ros: RosGraph, tmp_path: Path):
    field = REPO / "rotors_gazebo_compat/rotors_gazebo/resource/wind_fields/shear_layer.txt"
    proc = fly(
        ros,
        tmp_path,
        "mav_hovering_example.launch",
        real_time_factor="5",
        xacro_args=f"enable_wind:=true use_custom_static_wind_field:=true custom_wind_field_path:={field}",
    )
    try:
        wait_sim_time(ros, 12.0)
        got = ros.run_client(clients.wind.speed_pairs, count=20)["pairs"]
    finally:
        stop_launch(proc)
    # the shear layer: u(z) = 5 (z / 60)^0.2 at levels 0, 3, 12, 30, 60 m, linear in between
    levels, u_levels = [0, 3, 12, 30, 60], [5.0 * (z / 60.0) ** 0.2 for z in [0, 3, 12, 30, 60]]
    for u, v, w, z in got:
        assert abs(u - np.interp(z, levels, u_levels)) < 0.01 and v == 0.0 and w == 0.0, (u, z)
    print(
        f"custom wind field at z = {got[-1][3]:.3f} m: u = {got[-1][0]:.4f} m/s "
        f"(expected {np.interp(got[-1][3], levels, u_levels):.4f})"
    )


def test_wind_speed_from_a_topic(ros: RosGraph, tmp_path: Path):
    proc = fly(
        ros, tmp_path, "mav_hovering_example.launch", real_time_factor="5", xacro_args="enable_wind:=true wind_speed_sub_topic:=wind_input"
    )
    try:
        wait_sim_time(ros, 8.0)
        got = ros.run_client(clients.wind.wind_from_a_topic)["w"]
    finally:
        stop_launch(proc)
    assert got == [3.0, -1.0, 3.0, -1.0]  # NaN input ignored: the last valid wind stays
    assert "ignoring a wind speed with NaN or inf" in Path(proc.log_path).read_text()


def test_airspeed_sensor_reads_plugin_wind_minus_velocity(ros: RosGraph, tmp_path: Path):
    """The book's wind sensor (section 4, eq. 19): with the wind plugin blowing 3 m/s along x on a
    hovering MAV, air_speed is R_WB^T (v_wind - v) of the plugin's published wind and the ground truth."""
    proc = fly(
        ros,
        tmp_path,
        "mav_hovering_example.launch",
        real_time_factor="0",
        xacro_args="enable_wind:=true wind_speed_mean:=3 enable_airspeed:=true random_seed:=1",
    )
    try:
        wait_sim_time(ros, 6.0)
        result = ros.run_client(clients.wind.airspeed_against_wind_and_velocity)
    finally:
        stop_launch(proc)
    print(
        f"air_speed against R^T (v_wind - v) of the wind plugin and ground truth: {result['n']} stamps, largest "
        f"difference {result['worst']:.2e} m/s; last reading {result['last']}"
    )
    assert result["n"] > 100
    assert result["worst"] < 1e-6
    assert abs(result["last"][0] - 3.0) < 0.3  # hovering in a 3 m/s wind along x
