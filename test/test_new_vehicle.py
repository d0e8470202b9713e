"""docs/vehicles.md "Adding a vehicle", done step by step as a user would: an X quadrotor of 1.0 kg body mass,
its vehicle yaml and gains from `rosrun rotors_gazebo vehicle_params`, flown by the hovering
example. It must hover within 0.01 m of its set point first time (the simulated vehicle weighs
more than its body: rotors and sensors; the computed yaml knows it)."""

import math
from pathlib import Path

import pytest
import yaml

from rotors_evaluation.bag_data import load_flight
from rotors_evaluation.metrics import rms_error
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time

NAME = "readme_xquad"
URDF = REPO / "rotors_description" / "urdf"
RESOURCE = REPO / "rotors_gazebo_compat" / "rotors_gazebo" / "resource"
CREATED = [URDF / f"{NAME}.xacro", URDF / f"{NAME}_base.xacro", RESOURCE / f"{NAME}.yaml", RESOURCE / f"lee_controller_{NAME}.yaml"]


def write_vehicle_as_readme_says() -> None:
    # step 1: copy pelican.xacro, set the properties, place the rotors (X configuration)
    text = (URDF / "pelican.xacro").read_text()
    head, _, _ = text.partition('  <xacro:placed_rotor motor_number="0"')
    d = 0.21 / math.sqrt(2.0)
    rotors = "".join(
        f'  <xacro:placed_rotor motor_number="{i}" suffix="{s}" direction="{dr}" color="{c}" x="{x:.6f}" y="{y:.6f}" '
        f'z="${{rotor_offset_top}}" />\n'
        for i, (s, dr, c, x, y) in enumerate(
            [
                ("front_left", "cw", "Red", d, d),
                ("back_left", "ccw", "Blue", -d, d),
                ("back_right", "cw", "Blue", -d, -d),
                ("front_right", "ccw", "Red", d, -d),
            ]
        )
    )
    (URDF / f"{NAME}.xacro").write_text(head + rotors + "</robot>\n")
    # step 2: copy pelican_base.xacro, replace the name
    (URDF / f"{NAME}_base.xacro").write_text((URDF / "pelican_base.xacro").read_text().replace("pelican", NAME))


# its files sit in the source tree while it runs: not beside the test that lists the known vehicles
@pytest.mark.xdist_group("source_tree_vehicles")
def test_a_quadrotor_added_by_the_readme_steps_hovers_first_time(ros: RosGraph):
    assert not any(p.exists() for p in CREATED), "left over from an earlier run"
    try:
        write_vehicle_as_readme_says()
        # step 3: the vehicle yaml and the gains
        res = ros.run(["rosrun", "rotors_gazebo", "vehicle_params", "--mav_name", NAME])
        print(res.stdout)
        vehicle = yaml.safe_load((RESOURCE / f"{NAME}.yaml").read_text())
        # body 1.0 kg + 4 rotors of 0.01 kg + ADIS16448 IMU 0.015 kg + 3 sensor links of 1e-5 kg
        assert math.isclose(vehicle["mass"], 1.0 + 4 * 0.01 + 0.015 + 3 * 1e-5, abs_tol=1e-9)
        assert vehicle["gravity"] == 9.8 and len(vehicle["rotor_configuration"]) == 4
        assert math.isclose(vehicle["rotor_configuration"]["0"]["angle"], math.pi / 4, abs_tol=1e-6)
        assert "scaled to" in res.stdout
        # step 4: fly it
        proc = launch(
            ros,
            "rotors_gazebo",
            "mav_hovering_example.launch",
            f"mav_name:={NAME}",
            "enable_logging:=true",
            "lockstep:=true",
            "real_time_factor:=0",
        )
        try:
            wait_sim_time(ros, 21.0)
        finally:
            stop_launch(proc)
        bag = next(Path(ros.env["ROS_HOME"]).glob(f"{NAME}_*.bag"))
        data = load_flight(bag, NAME, "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench")
        wp = data.waypoints[0]
        offset = rms_error(data.position.window(wp.t + 5, wp.t + 15), wp.position)
        print(f"{NAME}: hover RMS about the set point {offset:.4f} m")
        assert offset < 0.01
    finally:
        for p in CREATED:
            p.unlink(missing_ok=True)
