"""Every shipped vehicle's xacro expands and parses with urdfdom (check_urdf), alone and as the
generic-odometry and generic-pose-sensor composites, each looks like itself (RotorS' body meshes
where they exist, propellers scaled by radius_rotor), and a broken xacro is one clear error."""

import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from support import package_path

VEHICLES = ["firefly", "hummingbird", "pelican", "iris", "neo11", "asymmetric_quadrotor", "ardrone", "neo9", "omav"]
ROTORS = {"firefly": 6, "neo11": 6, "neo9": 6, "omav": 12}  # 4 otherwise


@pytest.mark.parametrize("mav", VEHICLES)
@pytest.mark.parametrize("top", ["{mav}_base.xacro", "mav_generic_odometry_sensor.gazebo", "mav_generic_pose_sensor.gazebo"])
def test_vehicle_description_parses_with_urdfdom(mav: str, top: str, tmp_path):
    urdf = subprocess.run(
        [
            "xacro",
            str(package_path("rotors_description") / "urdf" / top.format(mav=mav)),
            f"mav_name:={mav}",
            f"namespace:={mav}",
            "enable_logging:=true",
        ],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    path = tmp_path / f"{mav}.urdf"
    path.write_text(urdf)
    res = subprocess.run(["check_urdf", str(path)], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    assert f"robot name is: {mav}" in res.stdout
    servos = 6 if mav == "omav" else 0  # the omav's tilt units: motorType position
    assert urdf.count("librotors_gazebo_motor_model.so") == ROTORS.get(mav, 4) + servos
    assert "librotors_gazebo_bag_plugin.so" in urdf


# radius_rotor [m] of RotorS' rotors_description/urdf/<mav>.xacro
RADIUS_ROTOR = {
    "firefly": 0.1,
    "hummingbird": 0.1,
    "pelican": 0.128,
    "iris": 0.1,
    "neo11": 0.1397,
    "asymmetric_quadrotor": 0.128,
    "ardrone": 0.1,
    "neo9": 0.1143,
    "omav": 0.1143,
}
BODY_MESH = {"firefly": "firefly.ply", "pelican": "pelican.dae"}


@pytest.mark.parametrize("mav", VEHICLES)
def test_vehicle_visuals_are_body_and_props_scaled_by_radius(mav: str):
    urdf = ET.fromstring(
        subprocess.run(
            ["xacro", str(package_path("rotors_description") / "urdf" / f"{mav}_base.xacro"), f"namespace:={mav}"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout
    )
    links = {link.get("name"): link for link in urdf.iter("link")}
    rotors = [name for name in links if name.startswith(f"{mav}/rotor_")]
    assert len(rotors) == ROTORS.get(mav, 4)
    meshes = package_path("rotors_description") / "meshes"
    for name in rotors:
        mesh = links[name].find("visual/geometry/mesh")
        direction = "cw" if "propeller_cw" in mesh.get("filename") else "ccw"
        assert mesh.get("filename") == f"package://rotors_description/meshes/propeller_{direction}.stl"
        assert [float(s) for s in mesh.get("scale").split()] == [RADIUS_ROTOR[mav]] * 3
        assert links[name].find("visual/material/color") is not None  # red front, blue back in rviz
    body = links[f"{mav}/base_link_inertia"].find("visual/geometry")
    if mav in BODY_MESH:
        assert body.find("mesh").get("filename") == f"package://rotors_description/meshes/{BODY_MESH[mav]}"
    else:
        assert body.find("box") is not None
    for mesh in urdf.iter("mesh"):
        assert (meshes / mesh.get("filename").rsplit("/", 1)[1]).is_file(), mesh.get("filename")
    # drawn arms carry no mass: the inertial links are the body and the rotors (and the asymmetric arms,
    # the omav's tilt units)
    massive = {name for name, link in links.items() if link.find("inertial") is not None}
    assert all(
        name.endswith("base_link_inertia") or "/rotor_" in name or name.endswith("_link") or "/tilt_unit_" in name for name in massive
    )


@pytest.mark.parametrize("mav_name", VEHICLES)
def test_multirotors_take_autopilot_interface_before_its_sensors(mav_name):
    for flag, filename in (
        ("enable_mavlink_interface", "librotors_gazebo_mavlink_interface.so"),
        ("enable_ardupilot_interface", "librotors_gazebo_ardupilot_interface.so"),
        ("enable_betaflight_interface", "librotors_gazebo_betaflight_interface.so"),
    ):
        res = subprocess.run(
            [
                "xacro",
                str(package_path("rotors_description") / "urdf" / f"{mav_name}_base.xacro"),
                f"mav_name:={mav_name}",
                f"namespace:={mav_name}",
                f"{flag}:=true",
            ],
            capture_output=True,
            text=True,
        )
        assert res.returncode == 0, res.stderr
        plugins = [p.get("filename") for p in ET.fromstring(res.stdout).iter("plugin")]
        assert plugins.count(filename) == 1
        # it pins the sensor topics it reads before their plugins advertise them
        assert plugins.index(filename) < plugins.index("librotors_gazebo_imu_plugin.so")
        navigation = {"librotors_gazebo_gps_plugin.so", "librotors_gazebo_magnetometer_plugin.so", "librotors_gazebo_pressure_plugin.so"}
        # PX4 and ArduPilot read GPS, magnetometer and barometer: the interface brings them
        assert navigation <= set(plugins) or flag == "enable_betaflight_interface"


def test_launch_files_with_lee_or_attitude_offer_in_process():
    """docs/rotors_compatibility.md: in_process:=true on every launch file that starts lee_position_controller_node or
    roll_pitch_yawrate_thrust_controller_node (they can run as nodelets in the simulator)."""
    nodelet_nodes = {"lee_position_controller_node", "roll_pitch_yawrate_thrust_controller_node"}
    lacking, checked = [], 0
    for path in sorted((package_path("rotors_gazebo") / "launch").glob("*.launch")):
        root = ET.parse(path).getroot()
        nodes = [n for n in root.iter("node") if n.get("type") in nodelet_nodes]
        if not nodes:
            continue
        checked += 1
        declared = any(a.get("name") == "in_process" for a in root.iter("arg"))
        passed = all("--in-simulator" in (n.get("args") or "") and "in_process" in n.get("args") for n in nodes)
        if not (declared and passed):
            lacking.append(path.name)
    print(f"{checked} launch files start a Lee or attitude controller; without in_process: {lacking or 'none'}")
    assert checked >= 10 and lacking == []


def test_px4_profile_flies_px4s_iris_body_and_unbiased_imu():
    """PX4's own iris (PX4-SITL_gazebo-classic models/iris/iris.sdf.jinja: base link 1.5 kg, inertia
    0.029125 / 0.029125 / 0.055225 kg m^2) and its IMU plugin's biases, which start at 0; the rotors
    profile keeps RotorS' iris (0.0347563 / 0.0458929 / 0.0977) and RotorS' turn-on biases."""

    def expand(profile: str) -> ET.Element:
        res = subprocess.run(
            [
                "xacro", str(package_path("rotors_description") / "urdf" / "iris_base.xacro"), "mav_name:=iris",
                "namespace:=iris", "enable_mavlink_interface:=true", f"autopilot_profile:={profile}",
            ],
            capture_output=True, text=True,
        )  # fmt: skip
        assert res.returncode == 0, res.stderr
        return ET.fromstring(res.stdout)

    def body(urdf: ET.Element) -> tuple:
        link = next(lk for lk in urdf.iter("link") if lk.get("name") == "iris/base_link_inertia")
        inertia = link.find("inertial/inertia")
        return (
            float(link.find("inertial/mass").get("value")),
            *(float(inertia.get(k)) for k in ("ixx", "iyy", "izz")),
        )

    def turn_on_biases(urdf: ET.Element) -> tuple:
        imu = next(
            p for p in urdf.iter("plugin") if p.get("filename") == "librotors_gazebo_imu_plugin.so" and p.find("imuTopic").text == "imu"
        )
        return float(imu.find("gyroscopeTurnOnBiasSigma").text), float(imu.find("accelerometerTurnOnBiasSigma").text)

    px4, rotors = expand("px4"), expand("rotors")
    assert body(px4) == (1.5, 0.029125, 0.029125, 0.055225)
    assert turn_on_biases(px4) == (0.0, 0.0)
    assert body(rotors) == (1.5, 0.0347563, 0.0458929, 0.0977)
    assert turn_on_biases(rotors) == (0.0087, 0.196)


def test_image_sensor_options_reach_the_camera_plugins(tmp_path: Path):
    """sensor_realism:=true gives the VI-sensor's stereo plugin the MT9V034's image sensor, the D435's
    colour camera takes a rolling shutter (rgb_line_delay), and an unknown image sensor is one error."""

    def expand(path: Path, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run(["xacro", str(path), "mav_name:=firefly", *args], capture_output=True, text=True)

    urdf = package_path("rotors_description") / "urdf"
    vi = ET.fromstring(expand(urdf / "mav_with_vi_sensor.gazebo", "sensor_realism:=true").stdout)
    stereo = next(p for p in vi.iter("plugin") if p.get("filename") == "libgazebo_ros_multicamera.so")
    assert stereo.find("autoExposure").text == "true" and stereo.find("photonNoise").text == "true"
    assert stereo.find("lineDelay") is None  # the MT9V034 is a global shutter
    plain = ET.fromstring(expand(urdf / "mav_with_vi_sensor.gazebo").stdout)
    assert next(p for p in plain.iter("plugin") if p.get("filename") == "libgazebo_ros_multicamera.so").find("autoExposure") is None
    rgbd = Path(__file__).parent / "descriptions" / "firefly_with_depth_sensor.gazebo"
    colour = [p for p in ET.fromstring(expand(rgbd, "rgb_line_delay:=3e-5").stdout).iter("plugin") if p.find("lineDelay") is not None]
    assert len(colour) == 1 and float(colour[0].find("lineDelay").text) == 3e-5
    wrong = tmp_path / "wrong.xacro"
    wrong.write_text(
        '<robot name="w" xmlns:xacro="http://ros.org/wiki/xacro"><xacro:include filename="'
        + str(urdf / "component_snippets.xacro")
        + '"/><xacro:image_sensor_params image_sensor="mt9v032"/></robot>'
    )
    bad = expand(wrong)
    assert bad.returncode != 0 and "image_sensor=mt9v032 is not known: use none, rolling, mt9v034 or mt9v034_rolling" in bad.stderr


def test_mass_and_motor_constant_scales_reach_every_multirotor():
    """mass_scale and motor_constant_scale (spawn_mav.launch and the vehicle launch files pass them
    on): every link mass of the airframe and the body's inertia times mass_scale, every
    motorConstant times motor_constant_scale; a scale <= 0 is one error naming both."""

    def expand(*args: str) -> subprocess.CompletedProcess:
        urdf = package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo"
        return subprocess.run(["xacro", str(urdf), *args], capture_output=True, text=True)

    for mav in ("firefly", "hummingbird", "pelican", "iris", "neo11"):
        plain = ET.fromstring(expand(f"mav_name:={mav}").stdout)
        scaled = ET.fromstring(expand(f"mav_name:={mav}", "mass_scale:=1.2", "motor_constant_scale:=0.85").stdout)

        def body(robot, mav=mav):
            link = next(link for link in robot.iter("link") if link.get("name") == f"{mav}/base_link_inertia")
            inertial = link.find("inertial")
            return float(inertial.find("mass").get("value")), float(inertial.find("inertia").get("izz"))

        def motor_constants(robot):
            return [float(p.find("motorConstant").text) for p in robot.iter("plugin") if p.find("motorConstant") is not None]

        (m0, izz0), (m1, izz1) = body(plain), body(scaled)
        assert m1 == pytest.approx(1.2 * m0, rel=1e-12) and izz1 == pytest.approx(1.2 * izz0, rel=1e-12), mav
        k0, k1 = motor_constants(plain), motor_constants(scaled)
        assert len(k0) >= 4 and k1 == pytest.approx([0.85 * k for k in k0], rel=1e-12), mav
    bad = expand("mav_name:=firefly", "motor_constant_scale:=0")
    assert bad.returncode != 0 and "mass_scale = 1, motor_constant_scale = 0: both must be > 0" in bad.stderr
