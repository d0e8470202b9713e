"""Sensor plugins in the running simulator: the odometry outage map (package:// URL) suppresses
measurements over black pixels; the IMU at rest reads +g."""
from pathlib import Path

from conftest import RosGraph
from test_sim_server import start_server


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
        ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(f), "-model", name, "-x", str(x),
                 "-y", str(y), "-z", "0.1"])
    result = ros.rospy("""
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import Imu
        counts = {'white': 0, 'black': 0}
        subs = [rospy.Subscriber(f'/{n}/odometry', Odometry, lambda m, n=n: counts.__setitem__(n, counts[n] + 1))
                for n in counts]
        imu = []
        sub_imu = rospy.Subscriber('/white/imu', Imu, lambda m: imu.append(m.linear_acceleration.z))
        time.sleep(2.0)
        result.update(counts)
        result['imu_z'] = sum(imu[-50:]) / max(len(imu[-50:]), 1)
    """)
    assert result["white"] > 50  # 100 Hz where the map is white
    assert result["black"] == 0  # nothing over the black blob
    assert abs(result["imu_z"] - 9.8) < 0.05  # at rest: +g (gyro/accel noise left at ADIS defaults is small)
