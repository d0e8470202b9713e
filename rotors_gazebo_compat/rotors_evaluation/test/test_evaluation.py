"""The evaluation scripts on synthetic bags whose RMS, settling time and collision time are known
exactly, run as plain Python scripts (no ROS needed), plus their one-line errors on bad input."""

import json
import subprocess
import sys
from pathlib import Path

import pytest
from synthetic_bags import write_flight, write_old_rotors_flight, write_ros2_flight

SCRIPTS = Path(__file__).resolve().parents[1] / "scripts"


def run(script: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPTS / script), *args, "--plot", "False"], capture_output=True, text=True, timeout=120)


def hover_bag(tmp_path: Path, **kw) -> Path:
    # set point (0, 0, 1) at t = 5 s; from 10 s on an offset of (0.04, 0, 0.03): RMS = 0.05 m;
    # angular velocity (0.08, 0, 0) throughout: RMS 0.08 rad/s
    return write_flight(
        tmp_path / kw.pop("name", "hover.bag"),
        lambda t: (0.04, 0.0, 1.03) if t > 10.0 else (0.0, 0.0, 0.1 if t < 5 else 0.5),
        lambda t: (0.08, 0.0, 0.0),
        [(5.0, (0.0, 0.0, 1.0))],
        **kw,
    )


def test_hovering_rms_is_exact_and_printed_as_rotors_does(tmp_path: Path):
    bag = hover_bag(tmp_path)
    res = run(
        "hovering_eval.py",
        "-b",
        str(bag),
        "--mav_name",
        "firefly",
        "--json",
        str(tmp_path / "r.json"),
        "--save_plots",
        "True",
        "--plot_dir",
        str(tmp_path),
    )
    assert res.returncode == 0, res.stderr
    assert "[Waypoint 0]: [0.000, 0.000, 1.000, 0.000] at time 5.000 s" in res.stdout
    assert "Position RMS error: 0.050 m" in res.stdout
    assert "Angular velocity RMS error: 0.080 rad/s" in res.stdout
    assert "No collisions occurred - good job!" in res.stdout
    summary = json.loads((tmp_path / "r.json").read_text())
    assert summary["position_rms"] == pytest.approx(0.05, abs=1e-12)
    assert summary["angular_velocity_rms"] == pytest.approx(0.08, abs=1e-12)
    assert summary["scores"] == {"position": 3.5, "angular_velocity": 2.0}  # 0.02 < 0.05 <= 0.1 m; 0.02 < 0.08 <= 0.1 rad/s
    for name in ("position", "position_error", "angular_velocities"):
        assert (tmp_path / f"{name}.png").stat().st_size > 10000


def test_collision_after_the_delay_voids_the_score(tmp_path: Path):
    bag = hover_bag(tmp_path, collisions=[2.0, 12.5])  # the 2 s one is before the evaluation starts
    res = run("hovering_eval.py", "-b", str(bag), "-n", "firefly", "--json", "-")
    assert res.returncode == 0, res.stderr
    assert "Collision at time 12.500 s!" in res.stdout
    assert "One or more collisions occurred - no points are awarded!" in res.stdout
    summary = json.loads(res.stdout[res.stdout.index("{") :])
    assert summary["collision_times"] == [12.5]


def test_waypoint_settling_time_is_exact(tmp_path: Path):
    # waypoint 1 at 20 s to (2, 0, 1): the MAV is 0.5 m away until 23.5 s, then exactly there
    def position(t):
        if t <= 20.0:
            return (0.0, 0.0, 1.0)
        return (1.5, 0.0, 1.0) if t < 23.5 else (2.0, 0.0, 1.0)

    bag = write_flight(tmp_path / "wp.bag", position, lambda t: (0.0, 0.0, 0.0), [(5.0, (0.0, 0.0, 1.0)), (20.0, (2.0, 0.0, 1.0))])
    for script in ("waypoints_eval.py", "waypoint_eval.py"):
        res = run(script, "-b", str(bag), "--mav_name", "firefly", "--json", "-")
        assert res.returncode == 0, res.stderr
        summary = json.loads(res.stdout[res.stdout.index("{") :])
        assert summary["segments"][1]["settling_time"] == pytest.approx(3.5, abs=0.011)
        assert summary["segments"][1]["position_rms"] == pytest.approx(0.0, abs=1e-12)
        assert "settling time: 3.50 s" in res.stdout


def test_compressed_bag_and_rosbag_record_topic_names(tmp_path: Path):
    for comp in ("lz4", "bz2"):
        bag = hover_bag(tmp_path, name=f"{comp}.bag", compression=comp, prefix="/firefly/")
        res = run("hovering_eval.py", "-b", str(bag), "--mav_name", "firefly")
        assert res.returncode == 0, res.stderr
        assert "Position RMS error: 0.050 m" in res.stdout


def test_original_rotors_bag_without_mav_prefix(tmp_path: Path):
    bag = hover_bag(tmp_path, name="old.bag", prefix="/", old_motor_topic=True)
    res = run("hovering_eval.py", "-b", str(bag), "--mav_name", "firefly", "-m", "/motors", "--json", "-")
    assert res.returncode == 0, res.stderr
    assert "Position RMS error: 0.050 m" in res.stdout
    assert json.loads(res.stdout[res.stdout.index("{") :])["topics"]["motors"] == "motors"
    # the MotorSpeed messages are read: 4,000 samples of six rotors at 543 rad/s
    from rotors_evaluation.bag_data import load_flight

    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench", "/motors")
    assert data.motor_speeds is not None and data.motor_speeds.values.shape == (4000, 6)
    assert (data.motor_speeds.values == 543.0).all()


def test_compare_tabulates_several_bags(tmp_path: Path):
    a = hover_bag(tmp_path, name="a.bag")
    b = write_flight(tmp_path / "b.bag", lambda t: (0.0, 0.0, 1.0), lambda t: (0, 0, 0), [(5.0, (0.0, 0.0, 1.0))])
    res = subprocess.run(
        [sys.executable, str(SCRIPTS / "compare_eval.py"), "-b", str(a), str(b), "-n", "firefly"], capture_output=True, text=True
    )
    assert res.returncode == 0, res.stderr
    lines = res.stdout.splitlines()
    assert lines[0].split()[:3] == ["bag", "position", "RMS"]
    assert lines[2].split()[:3] == ["a.bag", "0.050", "0.080"]
    assert lines[3].split()[:3] == ["b.bag", "0.000", "0.000"]


def test_wrong_mav_name_names_missing_topic_and_lists_bag(tmp_path: Path):
    bag = hover_bag(tmp_path)
    res = run("hovering_eval.py", "-b", str(bag), "--mav_name", "pelican")
    assert res.returncode == 1
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert "pose topic 'pelican/ground_truth/pose' is not in bag 'hover.bag'" in lines[0]
    assert "firefly/ground_truth/pose" in lines[0]


def test_empty_and_truncated_bags_get_one_clear_line(tmp_path: Path):
    from rosbags.rosbag1 import Writer

    empty = tmp_path / "empty.bag"
    with Writer(empty):
        pass
    res = run("hovering_eval.py", "-b", str(empty), "-n", "firefly")
    assert res.returncode == 1 and "is empty (no topics)" in res.stderr and "Traceback" not in res.stderr
    good = hover_bag(tmp_path)
    truncated = tmp_path / "truncated.bag"
    truncated.write_bytes(good.read_bytes()[: good.stat().st_size // 2])
    res = run("hovering_eval.py", "-b", str(truncated), "-n", "firefly")
    assert res.returncode == 1 and "Traceback" not in res.stderr
    assert f"rosbag reindex {truncated}" in res.stderr
    res = run("hovering_eval.py", "-b", str(tmp_path / "missing.bag"))
    assert res.returncode == 1 and "does not exist" in res.stderr


def test_pre_2_0_rotors_bag_is_evaluated_by_every_script(tmp_path: Path):
    """RotorS' own test bag layout (reference 1.6): old names without prefix, MotorSpeed on /motors,
    /<mav>/collisions, CommandTrajectoryPositionYaw set points, CommandMotorSpeed commands."""

    def position(t):  # as hover_bag, then waypoint 1 at 20 s to (2, 0, 1) reached at 23.5 s
        if t <= 10.0:
            return (0.0, 0.0, 0.1 if t < 5 else 0.5)
        if t <= 20.0:
            return (0.04, 0.0, 1.03)
        return (1.5, 0.0, 1.0) if t < 23.5 else (2.0, 0.0, 1.0)

    bag = write_old_rotors_flight(
        tmp_path / "waypoint_example.bag", position, [(5.0, (0.0, 0.0, 1.0)), (20.0, (2.0, 0.0, 1.0))], collisions=[35.0]
    )
    res = run("hovering_eval.py", "-b", str(bag), "--mav_name", "asymmetric_quadrotor", "-m", "/motors", "--json", "-")
    assert res.returncode == 0, res.stderr
    assert "[Waypoint 0]: [0.000, 0.000, 1.000, 0.000] at time 5.000 s" in res.stdout
    assert "Collision at time 35.000 s!" in res.stdout  # and, as RotorS, no points
    summary = json.loads(res.stdout[res.stdout.index("{") :])
    assert summary["position_rms"] == pytest.approx(0.05, abs=1e-12)
    assert summary["topics"]["waypoints"] == "asymmetric_quadrotor/command/trajectory_position_yaw"
    assert summary["topics"]["motors"] == "motors" and summary["topics"]["wrench"] == "asymmetric_quadrotor/collisions"
    res = run("waypoints_eval.py", "-b", str(bag), "--mav_name", "asymmetric_quadrotor", "--json", "-")
    assert res.returncode == 0, res.stderr
    summary = json.loads(res.stdout[res.stdout.index("{") :])
    assert summary["segments"][1]["settling_time"] == pytest.approx(3.5, abs=0.011)
    print(res.stdout)


def test_a_topic_of_a_type_the_evaluation_cannot_use_is_one_line(tmp_path: Path):
    bag = write_old_rotors_flight(
        tmp_path / "velocity.bag", lambda t: (0.0, 0.0, 1.0), [(5.0, (1.0, 0.0, 0.0))], set_point_type="CommandTrajectoryVelocityYawrate"
    )
    res = run("hovering_eval.py", "-b", str(bag), "--mav_name", "asymmetric_quadrotor")
    assert res.returncode == 1 and "Traceback" not in res.stderr, res.stderr
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert (
        "waypoint topic 'asymmetric_quadrotor/command/trajectory_position_yaw' has type "
        "mav_msgs/msg/CommandTrajectoryVelocityYawrate, which holds no position set point"
    ) in lines[0]
    res = run("hovering_eval.py", "-b", str(bag), "--mav_name", "asymmetric_quadrotor", "-t", "/motors")
    assert res.returncode == 1 and len(res.stderr.strip().splitlines()) == 1, res.stderr
    assert "twist topic 'motors' has type mav_msgs/msg/MotorSpeed" in res.stderr


def test_mapping_eval_scores_map_vs_itself_names_bad_files(tmp_path: Path):
    plant = Path(__file__).resolve().parents[2] / "rotors_gazebo" / "resource" / "power_plant.bt"
    res = run("mapping_eval.py", "-m", str(plant), "-t", str(plant), "--save_plots", "True", "--plot_dir", str(tmp_path))
    print(res.stdout, res.stderr)
    assert res.returncode == 0
    assert "Precision: 1.000 of the occupied leaves on or next to a truth leaf (1.000 on one)" in res.stdout
    assert "Recall of the seen leaves: 1.000 found exactly" in res.stdout
    assert (tmp_path / "mapping.png").is_file()
    res = run("mapping_eval.py", "-m", str(tmp_path / "none.bt"), "-t", str(plant))
    assert res.returncode == 1 and res.stdout.strip() == f"mapping_eval: the map file '{tmp_path / 'none.bt'}' does not exist"
    not_a_map = tmp_path / "not_a_map.bt"
    not_a_map.write_text("hello\n")
    res = run("mapping_eval.py", "-m", str(not_a_map), "-t", str(plant))
    assert res.returncode == 1 and res.stdout.strip().count("\n") == 0 and "cannot read" in res.stdout


@pytest.mark.parametrize("storage", ["mcap", "sqlite3"])
def test_a_ros2_bag_is_evaluated_as_a_ros1_bag(tmp_path: Path, storage: str):
    """The ROS 2 hovering example's bag (ground truth as nav_msgs/msg/Odometry, CDR): the same exact
    figures as hover_bag's, given as the bag's directory, its metadata.yaml or its storage file; a
    directory that is not a ROS 2 bag, and a bag whose storage file is gone, are one line each."""
    bag = write_ros2_flight(
        tmp_path / "ros2_hover",
        lambda t: (0.04, 0.0, 1.03) if t > 10.0 else (0.0, 0.0, 0.1 if t < 5 else 0.5),
        lambda t: (0.08, 0.0, 0.0),
        [(5.0, (0.0, 0.0, 1.0))],
        storage=storage,
    )
    storage_file = next(p for p in bag.iterdir() if p.name != "metadata.yaml")
    for given in (bag, bag / "metadata.yaml", storage_file):
        res = run("hovering_eval.py", "-b", str(given), "--mav_name", "firefly")
        assert res.returncode == 0, res.stderr
        assert "[Waypoint 0]: [0.000, 0.000, 1.000, 0.000] at time 5.000 s" in res.stdout
        assert "Position RMS error: 0.050 m" in res.stdout and "Angular velocity RMS error: 0.080 rad/s" in res.stdout
        assert "pose from 'firefly/ground_truth/odometry' (nav_msgs/msg/Odometry)" in res.stderr
    plain = tmp_path / "plain"
    plain.mkdir()
    res = run("hovering_eval.py", "-b", str(plain), "-n", "firefly")
    assert res.returncode == 1 and "is a directory without a ROS 2 bag's metadata.yaml" in res.stderr and "Traceback" not in res.stderr
    storage_file.unlink()
    res = run("hovering_eval.py", "-b", str(bag), "-n", "firefly")
    assert res.returncode == 1 and "Traceback" not in res.stderr and f"cannot read bag '{bag}'" in res.stderr, res.stderr
