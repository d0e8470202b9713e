"""The simulator server (rotors_sim_server) started against a test's ROS graph."""

from pathlib import Path

from support import RosGraph, package_path


def start_server(ros: RosGraph, *args: str):
    world = package_path("rotors_gazebo") / "worlds" / "basic.world"
    proc = ros.start(["rosrun", "rotors_core", "rotors_sim_server", str(world), *args], "server")
    ok = ros.wait_for(lambda: "/gazebo/unpause_physics" in ros.run(["rosservice", "list"], check=False).stdout, 30)
    assert ok, Path(proc.log_path).read_text()
    return proc
