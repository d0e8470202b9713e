"""The simulator's ROS face: /clock, pause/unpause/reset services, spawn/delete, model states
(topic and get_model_state),
and one-line errors for bad input."""

from pathlib import Path

import pytest

import clients.sim_server
from support import RosGraph, package_path
from support.sim_server import start_server

BOX_URDF = """<robot name="box"><link name="box/base_link"><inertial><mass value="1"/>
<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>"""


def test_pause_unpause_reset_and_spawn(ros: RosGraph, tmp_path: Path):
    start_server(ros, "-u", "--rtf", "0")
    urdf = tmp_path / "box.urdf"
    urdf.write_text(BOX_URDF)
    ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(urdf), "-model", "box", "-z", "5"])
    result = ros.run_client(clients.sim_server.pause_unpause_reset)
    assert result["paused_t0"] == result["paused_t1"] == 0.0  # started paused (-u)
    # gazebo_msgs/GetModelState: world pose, pose relative to a model, unknown names
    assert result["state_z"] == [True, 5.0, "world"]
    assert result["state_self"] == [True, 0.0, 1.0]
    assert result["state_nope"] == [False, "GetModelState: model 'nope' does not exist"]
    assert not result["state_rel_nope"][0] and "relative entity 'nope'" in result["state_rel_nope"][1]
    assert result["running_t"] > 1.0  # --rtf 0 runs faster than real time
    assert result["pause_t0"] == result["pause_t1"]  # paused again
    assert result["z_fallen"] < 0.2  # fell onto the ground
    assert abs(result["z_reset"] - 5.0) < 1e-9  # back at its spawn pose
    assert result["t_after_reset_world"] == result["pause_t1"]  # reset_world keeps time
    assert result["t_after_reset_sim"] == 0.0  # reset_simulation rewinds it


def test_runtime_spawn_delete_and_tf(ros: RosGraph, tmp_path: Path):
    start_server(ros, "--rtf", "1")
    urdf = tmp_path / "box.urdf"
    urdf.write_text(BOX_URDF)
    ros.run(["rosparam", "set", "/box_description", BOX_URDF])
    res = ros.run(
        ["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-param", "/box_description", "-model", "box", "-x", "1", "-y", "2", "-z", "0.1"]
    )
    assert "Successfully spawned entity 'box'" in res.stdout
    result = ros.run_client(clients.sim_server.box_tf_and_delete)
    assert abs(result["x"] - 1.0) < 2e-3 and abs(result["y"] - 2.0) < 2e-3  # resting on the ground
    assert result["deleted"] and not result["deleted_again"]
    assert "no model named 'box'" in result["msg"]


PROBE_SDF = """<?xml version="1.0"?>
<!-- an SDF vehicle with RotorS plugins: <robotNamespace> is in every plugin block -->
<sdf version="1.6"><model name="probe"><static>true</static><link name="probe/base_link">
  <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
  <sensor name="rangefinder" type="ray"><pose>0 0 -0.15 0 1.5707963267948966 0</pose><update_rate>20</update_rate>
    <ray><scan><horizontal><samples>1</samples><min_angle>0</min_angle><max_angle>0</max_angle></horizontal></scan>
      <range><min>0.06</min><max>25</max></range></ray>
    <plugin name="lidar" filename="librotors_gazebo_lidar_plugin.so"><robotNamespace>probe</robotNamespace></plugin>
  </sensor>
</link>
<plugin name="baro" filename="librotors_gazebo_pressure_plugin.so">
  <robotNamespace>probe</robotNamespace><linkName>probe/base_link</linkName>
</plugin></model></sdf>"""


def test_sdf_vehicle_with_rotors_plugins_spawns_via_spawn_sdf(ros: RosGraph, tmp_path: Path):
    # the format is the root element's: an SDF model whose plugins carry <robotNamespace> is no URDF
    start_server(ros, "--rtf", "1")
    sdf = tmp_path / "probe.sdf"
    sdf.write_text(PROBE_SDF)
    res = ros.run(["rosrun", "gazebo_ros", "spawn_model", "-sdf", "-file", str(sdf), "-model", "probe", "-z", "2"])
    assert "Successfully spawned entity 'probe'" in res.stdout, res.stdout + res.stderr
    result = ros.run_client(clients.sim_server.probe_readings)
    # 2 m over the ground of basic.world (elevation 500 m), the beam starts 0.15 m below the link
    assert abs(result["range"] - 1.85) < 1e-4
    assert 90000 < result["pressure"] < 96000


def test_bad_model_is_one_line_error_and_server_keeps_running(ros: RosGraph, tmp_path: Path):
    server = start_server(ros, "--rtf", "0")
    bad = tmp_path / "bad.urdf"
    bad.write_text("""<robot name="bad"><link name="bad/base_link"><inertial><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
      <link name="bad/arm"/><joint name="bad/arm_joint" type="continuous"><parent link="bad/base_link"/>
      <child link="bad/arm"/></joint>
      <gazebo><plugin name="p" filename="librotors_gazebo_motor_model.so"/></gazebo></robot>""")
    res = ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(bad), "-model", "bad"], check=False)
    assert res.returncode == 1
    lines = [line for line in res.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, res.stderr
    assert "link 'bad/arm' has no <inertial>" in lines[0]
    plugin = tmp_path / "plugin.urdf"
    plugin.write_text(
        BOX_URDF.replace("</robot>", '<gazebo><plugin name="ghost" filename="librotors_gazebo_ghost.so">' "</plugin></gazebo></robot>")
    )
    res = ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(plugin), "-model", "ghost"], check=False)
    assert res.returncode == 1
    assert "plugin 'ghost' (librotors_gazebo_ghost.so)" in res.stderr and "not found" in res.stderr
    # a firefly whose first motor lost its <motorConstant> is refused (no silent default)
    firefly = ros.run(
        [
            str(package_path("rotors_description") / "scripts" / "rotors_xacro"),
            str(package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo"),
            "mav_name:=firefly",
            "namespace:=firefly",
        ]
    ).stdout
    first_constant = firefly.index("<motorConstant>")
    broken = tmp_path / "no_motor_constant.urdf"
    broken.write_text(firefly[:first_constant] + firefly[firefly.index("</motorConstant>") + len("</motorConstant>") :])
    res = ros.run(["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(broken), "-model", "firefly"], check=False)
    lines = [line for line in res.stderr.splitlines() if line.strip()]
    assert res.returncode == 1 and len(lines) == 1, res.stderr
    assert "missing required parameter <motorConstant>" in lines[0], lines[0]
    assert server.poll() is None  # the simulator carries on
    clock = ros.run(["rostopic", "echo", "-n", "1", "/clock"]).stdout
    assert "secs" in clock
    models = ros.run(["rostopic", "echo", "-n", "1", "/gazebo/model_states/name"]).stdout
    assert "ground_plane" in models and "bad" not in models and "ghost" not in models


def test_unparsable_world_exits_with_one_line(ros: RosGraph, tmp_path: Path):
    world = tmp_path / "broken.world"
    world.write_text("<sdf version='1.6'><world name='w'><physics type='ode'><max_step_size>x</max_step_size>")
    res = ros.run(["rosrun", "rotors_core", "rotors_sim_server", str(world)], check=False, timeout=30)
    assert res.returncode == 1
    errors = [line for line in (res.stdout + res.stderr).splitlines() if "error" in line.lower()]
    assert len(errors) == 1 and "broken.world" in errors[0], res.stdout + res.stderr
    res = ros.run(["rosrun", "rotors_core", "rotors_sim_server", str(tmp_path / "missing.world")], check=False)
    assert res.returncode == 1 and "missing.world" in res.stderr


def test_spawn_normalises_the_quaternion_as_set_model_state_does(ros: RosGraph, tmp_path: Path):
    """A hand-typed quaternion (0, 0, 0.7, 0.7) is not a unit one: the model is spawned turned by
    90 deg about z with a unit orientation, not scaled; all zeros (rosservice's default) is the identity."""
    start_server(ros, "--rtf", "0")
    urdf = tmp_path / "box.urdf"
    urdf.write_text(BOX_URDF)
    result = ros.run_client(clients.sim_server.spawn_turned_and_plain, urdf_path=str(urdf))
    print(result)
    assert result["ok"] == [True, True]
    assert sum(c * c for c in result["turned"]) == pytest.approx(1.0, abs=1e-9)
    assert result["turned"][2] == pytest.approx(2**-0.5, abs=1e-6) and result["turned"][3] == pytest.approx(2**-0.5, abs=1e-6)
    assert result["plain"] == pytest.approx([0, 0, 0, 1], abs=1e-9)
