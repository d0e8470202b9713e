"""Sensor plugins in the running simulator: the odometry outage map (package:// URL) suppresses
measurements over black pixels; the IMU at rest reads +g; exact and noisy depth cameras."""

from pathlib import Path

import pytest

import clients.sensor_plugins
from support import RosGraph
from support.sim_server import start_server


def sensor_box(name: str) -> str:
    """A box carrying an odometry sensor with the shipped outage map and an IMU."""
    return f"""<robot name="{name}" xmlns:xacro="http://ros.org/wiki/xacro">
  <link name="{name}/base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="{name}/odometry_sensor_link"><inertial><mass value="0.00001"/>
    <inertia ixx="0.00001" ixy="0" ixz="0" iyy="0.00001" iyz="0" izz="0.00001"/></inertial></link>
  <joint name="{name}/odometry_sensor_joint" type="revolute"><parent link="{name}/base_link"/>
    <child link="{name}/odometry_sensor_link"/><limit upper="0" lower="0" effort="0" velocity="0"/></joint>
  <gazebo><plugin name="odometry" filename="librotors_gazebo_odometry_plugin.so">
    <robotNamespace>{name}</robotNamespace><linkName>{name}/odometry_sensor_link</linkName>
    <childFrameId>{name}/odometry_sensor</childFrameId>
    <covarianceImage>package://rotors_gazebo/resource/example_odometry_plugin_map1.bmp</covarianceImage>
    <covarianceImageScale>0.1</covarianceImageScale>
  </plugin></gazebo>
  <gazebo><plugin name="imu" filename="librotors_gazebo_imu_plugin.so">
    <robotNamespace>{name}</robotNamespace><linkName>{name}/base_link</linkName>
    <accelerometerTurnOnBiasSigma>0.0</accelerometerTurnOnBiasSigma>
    <accelerometerNoiseDensity>0.0</accelerometerNoiseDensity><accelerometerRandomWalk>0.0</accelerometerRandomWalk>
  </plugin></gazebo>
</robot>"""


def test_outage_map_suppresses_odometry_over_black_pixels(ros: RosGraph, tmp_path: Path):
    start_server(ros, "--rtf", "1")
    for name, x, y in (("white", 0.05, 0.05), ("black", 16.05, -4.95)):
        f = tmp_path / f"{name}.urdf"
        f.write_text(sensor_box(name))
        ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(f), "-model", name, "-x", str(x), "-y", str(y), "-z", "0.1"])
    result = ros.run_client(clients.sensor_plugins.odometry_counts_and_imu)
    assert result["white"] > 50  # 100 Hz where the map is white
    assert result["black"] == 0  # nothing over the black blob
    assert abs(result["imu_z"] - 9.8) < 0.05  # at rest: +g (gyro/accel noise left at ADIS defaults is small)


def test_wind_force_accelerates_a_free_body_as_f_over_m(ros: RosGraph, tmp_path: Path):
    """Force-on-link mode: 2 N along +y on a 1 kg box in free fall: y(t) = 1/2 (F/m) t^2."""
    start_server(ros, "-u", "--rtf", "1")
    urdf = tmp_path / "kite.urdf"
    urdf.write_text("""<robot name="kite"><link name="kite/base_link"><inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <gazebo><plugin name="wind_plugin" filename="librotors_gazebo_wind_plugin.so">
        <robotNamespace>kite</robotNamespace><linkName>kite/base_link</linkName><xyzOffset>0 0 0</xyzOffset>
        <windDirection>0 1 0</windDirection><windForceMean>2.0</windForceMean><windSpeedMean>3.0</windSpeedMean>
      </plugin></gazebo></robot>""")
    ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(urdf), "-model", "kite", "-z", "100"])
    result = ros.run_client(clients.sensor_plugins.wind_on_a_falling_kite)
    assert result["wind_y"] == 3.0
    t = result["t"]
    # semi-implicit Euler: y_N = a dt^2 N (N+1) / 2 with a = 2 m/s^2
    n = round(t / 0.01)
    assert result["y"] == pytest.approx(2.0 * 0.01**2 * n * (n + 1) / 2, rel=1e-6)


def depth_rig(name: str) -> str:
    """A static rig 2 m above the ground with two depth cameras looking straight down: exact
    (libgazebo_ros_openni_kinect) and Kinect-noisy (librotors_gazebo_noisydepth_plugin)."""

    def depth_sensor(sensor: str, plugin: str, extra: str) -> str:
        return f"""<sensor type="depth" name="{sensor}"><pose>0 0 0 0 1.5707963 0</pose><update_rate>10</update_rate>
      <camera><horizontal_fov>1.0</horizontal_fov><image><width>160</width><height>120</height><format>L8</format></image>
        <clip><near>0.05</near><far>10</far></clip></camera>
      <plugin name="{sensor}_plugin" filename="{plugin}"><robotNamespace>{name}</robotNamespace>
        <cameraName>{sensor}</cameraName><frameName>{name}/optical</frameName>{extra}</plugin></sensor>"""

    return f"""<robot name="{name}">
  <link name="{name}/base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <gazebo><static>true</static></gazebo>
  <gazebo reference="{name}/base_link">
    {depth_sensor("exact", "libgazebo_ros_openni_kinect.so", "<pointCloudCutoff>0.1</pointCloudCutoff>")}
    {depth_sensor("kinect", "librotors_gazebo_noisydepth_plugin.so",
                  "<depthNoiseModelName>Kinect</depthNoiseModelName><randomEngineSeed>5</randomEngineSeed>")}
  </gazebo>
</robot>"""


def test_depth_cameras_exact_and_kinect_noisy(ros: RosGraph, tmp_path: Path):
    """The ground 2 m below: the exact camera reads 2 m to a millimetre, the
    noisy one scatters with Kinect's sigma(2 m) = 0.0012 + 0.0019 (2 - 0.4)^2 = 6.06 mm."""
    start_server(ros, "--rtf", "0")
    f = tmp_path / "rig.urdf"
    f.write_text(depth_rig("rig"))
    ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(f), "-model", "rig", "-z", "2.0"])
    result = ros.run_client(clients.sensor_plugins.depth_cameras)
    print(result)
    assert result["encoding"] == "32FC1" and result["frame"] == "rig/optical"
    # depth is the distance along the optical axis: 2 m at every pixel of a camera facing the plane
    assert abs(result["exact_min"] - 2.0) < 0.001 and abs(result["exact_max"] - 2.0) < 0.001
    sigma = 0.0012 + 0.0019 * (2.0 - 0.4) ** 2
    assert abs(result["noisy_mean"] - 2.0) < 0.005
    assert abs(result["noisy_std"] - sigma) < 0.15 * sigma
    assert result["cloud"] == [160, 120]
