"""One source of truth: every shipped vehicle's controller parameters (resource/<mav>.yaml) agree with
the URDF the simulator flies (rotor positions, directions, constants, speed limits, mass, inertia,
gravity), except the differences resource/urdf_overrides.yaml names with a reason (the book's
deliberate mass and gravity mismatch among them)."""

import subprocess
from pathlib import Path

import pytest
import yaml

from rotors_gazebo.vehicle_params import compare_with_urdf, rigid_body_from_urdf, run_xacro
from support import package_path

VEHICLES = ["firefly", "hummingbird", "pelican", "iris", "neo11", "asymmetric_quadrotor", "ardrone", "neo9"]
WORLD_GRAVITY = 9.8  # every shipped world


def resource() -> Path:
    return package_path("rotors_gazebo") / "resource"


def body_of(mav: str):
    desc = package_path("rotors_description")
    urdf = run_xacro(desc / "scripts" / "rotors_xacro", desc / "urdf" / "mav_generic_odometry_sensor.gazebo", mav)
    return rigid_body_from_urdf(urdf, f"{mav}/base_link")


def overrides(mav: str):
    return yaml.safe_load((resource() / "urdf_overrides.yaml").read_text()).get(mav, {})


@pytest.mark.parametrize("mav", VEHICLES)
def test_vehicle_yaml_agrees_with_the_urdf(mav: str):
    vehicle = yaml.safe_load((resource() / f"{mav}.yaml").read_text())
    assert compare_with_urdf(mav, vehicle, body_of(mav), WORLD_GRAVITY, overrides(mav)) == []


def test_the_books_mass_and_gravity_mismatch_is_a_named_override():
    named = overrides("firefly")
    assert set(named) == {"mass", "inertia", "gravity"}
    firefly = yaml.safe_load((resource() / "firefly.yaml").read_text())
    body = body_of("firefly")
    assert firefly["mass"] == 1.56779 and round(body.mass_kg, 5) == 1.54503  # book section 3.6
    # without the overrides both are reported, naming vehicle and parameter
    lines = compare_with_urdf("firefly", firefly, body, WORLD_GRAVITY, {})
    assert "firefly: mass: 1.56779 in firefly.yaml, 1.54503 in the URDF (not a named override)" in lines
    assert "firefly: gravity: 9.81 in firefly.yaml, 9.8 in the URDF (not a named override)" in lines


def test_a_yaml_that_disagrees_with_its_xacro_is_named(tmp_path: Path):
    firefly = yaml.safe_load((resource() / "firefly.yaml").read_text())
    firefly["rotor_configuration"]["2"]["rotor_force_constant"] = 9e-06
    firefly["rotor_configuration"]["4"]["direction"] = -1
    firefly["rotor_configuration"]["5"]["angle"] = -0.6
    lines = compare_with_urdf("firefly", firefly, body_of("firefly"), WORLD_GRAVITY, overrides("firefly"))
    assert lines == [
        "firefly: rotor_configuration/2/rotor_force_constant: 9e-06 in firefly.yaml, 8.54858e-06 in the URDF " "(not a named override)",
        "firefly: rotor_configuration/4/direction: -1 in firefly.yaml, 1 in the URDF (not a named override)",
        "firefly: rotor_configuration/5/position: angle -0.6000 rad, arm 0.2150 m in firefly.yaml, -0.5236 rad, "
        "0.2150 m in the URDF (16.4 mm apart) (not a named override)",
    ]
    # the command-line check says the same and fails
    bad = tmp_path / "firefly.yaml"  # named as the shipped one, so the lines are the same
    bad.write_text(yaml.safe_dump(firefly))
    res = subprocess.run(
        ["rosrun", "rotors_gazebo", "vehicle_params", "--mav_name", "firefly", "--check", "--yaml", str(bad)],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 1 and res.stdout.splitlines() == lines
    res = subprocess.run(["rosrun", "rotors_gazebo", "vehicle_params", "--mav_name", "iris", "--check"], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "iris: iris.yaml agrees with the URDF (named overrides: mass, inertia, gravity)" in res.stdout


def test_a_named_override_that_is_not_needed_is_reported():
    pelican = yaml.safe_load((resource() / "pelican.yaml").read_text())
    named = dict(overrides("pelican"), **{"rotor_configuration/0/direction": "stale"})
    lines = compare_with_urdf("pelican", pelican, body_of("pelican"), WORLD_GRAVITY, named)
    assert lines == [
        "pelican: rotor_configuration/0/direction: named override, but both give "
        f"{pelican['rotor_configuration']['0']['direction']}: remove it"
    ]
