"""Every shipped vehicle's xacro expands and parses with urdfdom (check_urdf), alone and as the
generic-odometry and generic-pose-sensor composites, and a broken xacro is one clear error."""
import subprocess

import pytest

from conftest import package_path

VEHICLES = ["firefly", "hummingbird", "pelican", "iris", "neo11", "asymmetric_quadrotor"]


@pytest.mark.parametrize("mav", VEHICLES)
@pytest.mark.parametrize("top", ["{mav}_base.xacro", "mav_generic_odometry_sensor.gazebo", "mav_generic_pose_sensor.gazebo"])
def test_vehicle_description_parses_with_urdfdom(mav: str, top: str, tmp_path):
    urdf = subprocess.run(["xacro", str(package_path("rotors_description") / "urdf" / top.format(mav=mav)),
                           f"mav_name:={mav}", f"namespace:={mav}", "enable_logging:=true"],
                          capture_output=True, text=True, check=True).stdout
    path = tmp_path / f"{mav}.urdf"
    path.write_text(urdf)
    res = subprocess.run(["check_urdf", str(path)], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    assert f"robot name is: {mav}" in res.stdout
    rotors = 6 if mav in ("firefly", "neo11") else 4
    assert urdf.count("librotors_gazebo_motor_model.so") == rotors
    assert "librotors_gazebo_bag_plugin.so" in urdf


def test_mavlink_interface_is_refused_clearly():
    res = subprocess.run(["xacro", str(package_path("rotors_description") / "urdf" / "firefly_base.xacro"),
                          "enable_mavlink_interface:=true"], capture_output=True, text=True)
    assert res.returncode != 0
    assert "ERROR_enable_mavlink_interface_is_not_supported_by_this_simulator" in res.stderr
