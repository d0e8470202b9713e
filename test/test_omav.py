"""The omav tilt-rotor (omav.xacro, tilt servos as RotorS' motorType position) flown by our pose
controller (omav_pose_controller_node: 6-DoF PD + tilt-rotor allocation): its yaml agrees with the
URDF, it hovers, and being overactuated it holds its position while rolled 20 degrees."""

import math

import numpy as np
import pytest
import yaml

import clients.omav
from rotors_gazebo.vehicle_params import rigid_body_from_urdf, run_xacro
from support import RosGraph, launch, package_path, stop_launch, wait_sim_time

ROTOR_OFFSET = 0.06  # [m] upper and lower rotor above and below the tilt axis (omav.xacro)


def test_omav_yaml_agrees_with_the_urdf():
    desc = package_path("rotors_description")
    urdf = run_xacro(desc / "scripts" / "rotors_xacro", desc / "urdf" / "mav_generic_odometry_sensor.gazebo", "omav")
    body = rigid_body_from_urdf(urdf, "omav/base_link")
    omav = yaml.safe_load((package_path("rotors_gazebo") / "resource" / "omav.yaml").read_text())
    assert omav["mass"] == pytest.approx(body.mass_kg, abs=1e-5)
    inertia = omav["inertia"]
    J = np.array(
        [
            [inertia["xx"], inertia["xy"], inertia["xz"]],
            [inertia["xy"], inertia["yy"], inertia["yz"]],
            [inertia["xz"], inertia["yz"], inertia["zz"]],
        ]
    )
    assert np.allclose(J, body.inertia_kg_m2, rtol=1e-5, atol=1e-9), body.inertia_kg_m2
    assert len(body.rotors) == 12  # the six servos are not rotors
    arms = omav["tilt_rotor_configuration"]
    for i in range(6):
        arm = arms[str(i)]
        axis = np.array([arm["x"], arm["y"], arm["z"]])
        for rotor, z, direction, k_M in (
            (body.rotors[i], ROTOR_OFFSET, arm["upper_direction"], arm["upper_moment_constant"]),
            (body.rotors[i + 6], -ROTOR_OFFSET, -arm["upper_direction"], arm["lower_moment_constant"]),
        ):
            assert np.allclose(rotor.position_B, axis + [0, 0, z], atol=1e-4), (i, rotor)
            assert (rotor.direction, rotor.force_constant, rotor.moment_constant, rotor.max_rot_velocity) == (
                direction,
                arm["rotor_force_constant"],
                k_M,
                arm["max_rot_velocity"],
            ), (i, rotor)
        # the arm's yaw points from the body centre to its tilt unit
        assert math.atan2(arm["y"], arm["x"]) % (2 * math.pi) == pytest.approx(arm["yaw"] % (2 * math.pi), abs=1e-4)


def test_omav_hovers_then_holds_position_while_rolled_20_degrees(ros: RosGraph):
    proc = launch(ros, "rotors_gazebo", "omav_hovering_example.launch", "lockstep:=true", "real_time_factor:=10")
    try:
        wait_sim_time(ros, 12.0)  # hovering_example's (0, 0, 1) is due at 8.6 s
        got = ros.run_client(clients.omav.hover_then_roll_20_degrees, timeout=240)
    finally:
        stop_launch(proc)
    hover, tilted = np.array(got["hover"]), np.array(got["tilted"])
    err_hover = np.max(np.linalg.norm(hover[:, :3] - [0, 0, 1], axis=1))
    err_tilted = np.max(np.linalg.norm(tilted[:, :3] - [0, 0, 1], axis=1))
    arms = ", ".join(f"{math.degrees(a):.1f}" for a in got["arms"])
    print(
        f"omav: level hover: largest distance from (0, 0, 1) {err_hover * 1000:.1f} mm over 2 s; rolled: roll "
        f"{tilted[:, 3].min():.2f}..{tilted[:, 3].max():.2f} deg, pitch {np.abs(tilted[:, 4]).max():.2f} deg, "
        f"largest distance {err_tilted * 1000:.1f} mm over 5 s; arm tilts [deg]: {arms}"
    )
    assert err_hover < 0.02 and np.abs(hover[:, 3:]).max() < 0.5
    assert np.abs(tilted[:, 3] - 20.0).max() < 0.5 and np.abs(tilted[:, 4]).max() < 0.5
    assert err_tilted < 0.02  # a multirotor with fixed rotors would accelerate sideways at g tan 20 deg
    assert max(abs(a) for a in got["arms"]) > math.radians(5)  # the arms tilted to hold it


def test_omav_controller_without_its_yaml_is_one_line(ros: RosGraph):
    res = ros.run(["rosrun", "rotors_control", "omav_pose_controller_node", "__ns:=omav"], check=False, timeout=30)
    lines = [line for line in (res.stdout + res.stderr).splitlines() if "omav_pose_controller]" in line]
    assert res.returncode == 1 and len(lines) == 1, res.stdout + res.stderr
    assert "missing parameter /omav/omav_pose_controller_node/mass" in lines[0], lines
