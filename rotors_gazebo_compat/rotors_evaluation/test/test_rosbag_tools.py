"""RotorS evaluation's rosbag_tools module (analyze_bag, helpers) as user scripts import it: a
script written against it (rosbag_tools_user.py) on synthetic bags whose settling times, RMS errors
and collisions are known exactly, and the module's series API itself.

RotorS' own hovering_eval.py imports this module too; it is not shipped (never copied code). With
ROTORS_UPSTREAM_EVALUATION pointing at a RotorS checkout's rotors_evaluation/src, the last test runs
it on the same bag."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from synthetic_bags import write_flight

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / "src"


def run(script: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    """The script as a user runs it, in `cwd` (where RotorS' module saves its plots)."""
    env = dict(os.environ, PYTHONPATH=f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
    return subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True, timeout=120, env=env, cwd=cwd)


def two_waypoint_bag(tmp_path: Path, **kw) -> Path:
    # waypoint 0 (0, 0, 1) at 5 s: 0.5 m short until 7 s, then 0.05 m off in x; waypoint 1 (2, 0, 1)
    # at 20 s: 0.5 m short until 23.5 s, then exact; angular velocity (0, 0.03, 0) throughout
    def position(t):
        if t < 20.0:
            return (0.0, 0.0, 0.5) if t < 7.0 else (0.05, 0.0, 1.0)
        return (1.5, 0.0, 1.0) if t < 23.5 else (2.0, 0.0, 1.0)

    return write_flight(tmp_path / "two.bag", position, lambda t: (0.0, 0.03, 0.0), [(5.0, (0.0, 0.0, 1.0)), (20.0, (2.0, 0.0, 1.0))], **kw)


def test_a_user_script_on_rosbag_tools_gets_the_exact_figures(tmp_path: Path):
    bag = two_waypoint_bag(tmp_path, collisions=[30.0])
    res = run(HERE / "rosbag_tools_user.py", "-b", str(bag), "-n", "firefly", "--save_plots", "True", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    out = res.stdout
    # periods count from the bag's first message (0.01 s), as RotorS' helpers do
    assert "[Waypoint 0]: [0.000, 0.000, 1.000] from 4.990 s to 19.990 s" in out
    assert "[Waypoint 0]: Settling time: 2.000 s" in out  # inside 0.1 m from 7 s (first sample after 7.0)
    assert "[Waypoint 0]: Position RMS error: 0.050 m" in out
    assert "[Waypoint 1]: Settling time: 3.500 s" in out
    assert "[Waypoint 1]: Position RMS error: 0.000 m" in out
    assert "[Waypoint 1]: Angular velocity RMS error: 0.030 rad/s" in out
    assert "Collision at time 30.000!" in out and "no points are awarded" in out
    for name in ("pos_0", "pos_error_0", "angular_velocity_1"):
        assert (tmp_path / f"{name}.png").stat().st_size > 10000


def test_series_slice_resample_and_work_follow_rotors_rules(tmp_path: Path):
    sys.path.insert(0, str(SRC))
    from rosbag_tools import analyze_bag

    ab = analyze_bag.AnalyzeBag(str(two_waypoint_bag(tmp_path)), save_plots=False)
    ab.add_pose_topic("firefly/ground_truth/pose")
    ab.add_twist_topic("/firefly/ground_truth/twist")
    ab.add_waypoint_topic("firefly/command/trajectory")
    ab.add_imu_topic("firefly/imu")  # not in the bag: stays empty
    ab.extract_messages()
    pos = ab.pos[0]
    assert len(pos.x) == 4000 and ab.bag_time_start.to_sec() == pytest.approx(0.01)
    assert list(ab.waypoint[0].x) == [0.0, 2.0] and ab.waypoint[0].bag_time[1].to_sec() == pytest.approx(20.0)
    window = pos.slice(10.0, 12.0)  # samples after 10.0 up to and including 12.0
    assert len(window.x) == 200 and window.time[0] == pytest.approx(10.01) and window.time[-1] == pytest.approx(12.0)
    assert ab.rpy[0].roll.max() == 0.0 and len(ab.acc[0].x) == 0
    pos.resample(np.array([22.0, 24.0]))
    assert list(pos.x) == [pytest.approx(1.5), pytest.approx(2.0)]
    speeds = analyze_bag.ArrayWithTime()
    for t in (0.0, 0.5, 1.0):
        speeds.append_array([100.0, -100.0])
        speeds.append_times(t, analyze_bag.BagTime(t))
    assert analyze_bag.work(speeds, 1e-6) == pytest.approx(2 * 100.0**3 * 1e-6 * 1.0)
    assert analyze_bag.create_topic_list("a,b") == ["a", "b"] and analyze_bag.create_topic_list("") == []


UPSTREAM = os.environ.get("ROTORS_UPSTREAM_EVALUATION")
if UPSTREAM:  # only defined when RotorS' sources are given (see the module docstring)

    def test_rotors_own_hovering_eval_runs_on_this_module(tmp_path: Path):
        res = run(
            Path(UPSTREAM) / "hovering_eval.py", "-b", str(two_waypoint_bag(tmp_path)), "-n", "firefly", "--plot", "False", cwd=tmp_path
        )
        assert res.returncode == 0, res.stderr
        print(res.stdout)
        assert "Average position RMS error: 0.050 m" in res.stdout
        assert "Average angular velocity RMS error: 0.030 rad/s" in res.stdout
