"""One parameter policy for the controller nodes: a missing required parameter stops the node with one
line naming it; an absent optional one is announced with the value used; a key the node never reads
(a typo) is reported by name."""

import os
import signal
import subprocess
import time
from pathlib import Path

from support import RosGraph, package_path

NODE = ["rosrun", "rotors_control", "lee_position_controller_node", "__ns:=/firefly", "__name:=lee_position_controller_node"]
PARAMS = "/firefly/lee_position_controller_node"


def load(ros: RosGraph, *files: Path) -> None:
    for f in files:
        ros.run(["rosparam", "load", str(f), PARAMS])


def test_a_missing_gain_stops_the_node_with_one_line(ros: RosGraph, tmp_path: Path):
    resource = package_path("rotors_gazebo") / "resource"
    load(ros, resource / "lee_controller_firefly.yaml", resource / "firefly.yaml")
    ros.run(["rosparam", "delete", f"{PARAMS}/velocity_gain"])
    res = subprocess.run(NODE, env=ros.env, capture_output=True, text=True, timeout=60)
    fatal = [line for line in (res.stdout + res.stderr).splitlines() if "FATAL" in line]
    assert res.returncode != 0 and len(fatal) == 1, res.stdout + res.stderr
    assert (f"missing parameter {PARAMS}/velocity_gain (load the controller yaml, e.g. " "resource/lee_controller_<mav>.yaml)") in fatal[0]


def test_unknown_keys_are_named_and_defaults_announced(ros: RosGraph, tmp_path: Path):
    resource = package_path("rotors_gazebo") / "resource"
    load(ros, resource / "lee_controller_firefly.yaml", resource / "firefly.yaml")
    ros.run(["rosparam", "set", f"{PARAMS}/positon_gain", "{x: 1, y: 1, z: 1}"])  # a typo
    node = ros.start(NODE, "lee")
    try:
        assert ros.wait_for(lambda: "unknown parameter" in Path(node.log_path).read_text(), 30)
        time.sleep(0.5)
    finally:
        os.killpg(node.pid, signal.SIGINT)  # a clean exit flushes stdout (the INFO lines)
        node.wait(timeout=20)
    log = Path(node.log_path).read_text()
    assert (
        f"unknown parameter(s), not used: {PARAMS}/positon_gain/x, {PARAMS}/positon_gain/y, " f"{PARAMS}/positon_gain/z (a typo?)"
    ) in log, log
    assert f"{PARAMS}/gravity not given: 9.81 (RotorS' value; the world's may differ" in log, log
