"""A MAV deleted and re-spawned under the same namespace starts clean: the in-memory vehicle bus
(motor command, rotor count, faults) belongs to the vehicle's plugins and goes with them. Checked
where a bus left over from the old vehicle would show: a 6-rotor firefly spins up its six rotors
on a 6-speed command; a 4-rotor hummingbird re-spawned in its place must spin up its four on a
4-speed command, which the firefly's rotor count would reject, and the simulator's log must hold
no rejected motor command."""

from pathlib import Path

import clients.respawn
from support import REPO, RosGraph
from support.sim_server import start_server


def spawn(ros: RosGraph, tmp_path: Path, vehicle: str) -> None:
    urdf = ros.run(
        [
            str(REPO / "rotors_description/scripts/rotors_xacro"),
            str(REPO / f"rotors_description/urdf/{vehicle}_base.xacro"),
            f"mav_name:={vehicle}",
            "namespace:=mav",
        ]
    ).stdout
    (tmp_path / f"{vehicle}.urdf").write_text(urdf)
    res = ros.run(
        ["rosrun", "gazebo_ros", "spawn_model", "-urdf", "-file", str(tmp_path / f"{vehicle}.urdf"), "-model", "mav", "-z", "0.1"]
    )
    assert "Successfully spawned entity 'mav'" in res.stdout, res.stdout + res.stderr


def test_respawn_with_another_rotor_count_starts_on_a_fresh_bus(ros: RosGraph, tmp_path: Path):
    server = start_server(ros, "--rtf", "1")
    spawn(ros, tmp_path, "firefly")
    six = ros.run_client(clients.respawn.spin_motors, n=6)["speeds"]
    assert len(six) == 6 and min(six) > 299.0, six
    deleted = ros.run(["rosservice", "call", "/gazebo/delete_model", "mav"]).stdout
    assert "success: True" in deleted, deleted
    spawn(ros, tmp_path, "hummingbird")
    four = ros.run_client(clients.respawn.spin_motors, n=4)["speeds"]
    log = Path(server.log_path).read_text()
    assert "rejected motor command" not in log, log[-2000:]
    assert len(four) == 4 and min(four) > 299.0, four
