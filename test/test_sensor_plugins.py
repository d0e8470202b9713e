"""Sensor plugins in the running simulator: the odometry outage map (package:// URL) suppresses
measurements over black pixels; the IMU at rest reads +g."""
from pathlib import Path

import pytest

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


def test_wind_force_accelerates_a_free_body_as_f_over_m(ros: RosGraph, tmp_path: Path):
    """Force-on-link mode: 2 N along +y on a 1 kg box in free fall: y(t) = 1/2 (F/m) t^2."""
    start_server(ros, "-u", "--rtf", "1")
    urdf = tmp_path / "kite.urdf"
    urdf.write_text(f"""<robot name="kite"><link name="kite/base_link"><inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <gazebo><plugin name="wind_plugin" filename="librotors_gazebo_wind_plugin.so">
        <robotNamespace>kite</robotNamespace><linkName>kite/base_link</linkName><xyzOffset>0 0 0</xyzOffset>
        <windDirection>0 1 0</windDirection><windForceMean>2.0</windForceMean><windSpeedMean>3.0</windSpeedMean>
      </plugin></gazebo></robot>""")
    ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(urdf), "-model", "kite", "-z", "100"])
    result = ros.rospy("""
        from gazebo_msgs.msg import ModelStates
        from rotors_comm.msg import WindSpeed
        from std_srvs.srv import Empty
        from rosgraph_msgs.msg import Clock
        rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
        speed = rospy.wait_for_message('/kite/wind_speed', WindSpeed, timeout=10)
        result['wind_y'] = speed.velocity.y
        while rospy.wait_for_message('/clock', Clock).clock.to_sec() < 1.0:
            pass
        rospy.ServiceProxy('/gazebo/pause_physics', Empty)()
        t = rospy.wait_for_message('/clock', Clock).clock.to_sec()
        m = rospy.wait_for_message('/gazebo/model_states', ModelStates)
        result['t'] = t
        result['y'] = m.pose[m.name.index('kite')].position.y
    """)
    assert result["wind_y"] == 3.0
    t = result["t"]
    # semi-implicit Euler: y_N = a dt^2 N (N+1) / 2 with a = 2 m/s^2
    n = round(t / 0.01)
    assert result["y"] == pytest.approx(2.0 * 0.01 ** 2 * n * (n + 1) / 2, rel=1e-6)
