"""Flights a VIO can be scored on (docs/sensor_realism.md, "VIO flights"): the shipped trajectories
have the mean speed and mean angular rate of EuRoC's Vicon-room sequences; trajectory files that are
not one are refused in one line; and (long tier) mav_vio_flight.launch flies one with every sensor
effect on, records a bag, and the EuRoC export of it, read by evo, shows the flight that was asked for."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from rotors_evaluation.bag_data import FlightBag
from rotors_evaluation.robot_description import RobotDescription
from rotors_gazebo.flight_paths import EUROC_SHAPES, VIO_PLACES, mean_speed, mean_yaw_rate_deg_s, read_trajectory_file, vio_flight
from support import REPO, RosGraph, launch, package_path, stop_launch, wait_sim_time

FLIGHTS = package_path("rotors_gazebo") / "resource" / "vio_flights"
DELAY_S = 5.0  # trajectory_publisher_file's default: the flight is due 5 s after the first IMU message


@pytest.mark.parametrize("place", sorted(VIO_PLACES))
@pytest.mark.parametrize("difficulty", sorted(EUROC_SHAPES))
def test_shipped_flights_have_euroc_speeds_and_rates(place: str, difficulty: str):
    sequence, shape = EUROC_SHAPES[difficulty]
    flight = read_trajectory_file(FLIGHTS / f"{place}_{difficulty}.csv")
    print(
        f"{place} {difficulty}: {flight.duration_s:.1f} s, {flight.length_m():.1f} m, mean speed {mean_speed(flight):.3f} m/s "
        f"(EuRoC {sequence} {shape.mean_speed_m_s}), "
        f"mean yaw rate {mean_yaw_rate_deg_s(flight):.2f} deg/s ({shape.mean_angular_rate_deg_s})"
    )
    assert mean_speed(flight) == pytest.approx(shape.mean_speed_m_s, rel=0.01)
    assert mean_yaw_rate_deg_s(flight) == pytest.approx(shape.mean_angular_rate_deg_s, rel=0.01)
    # the file is what the generator makes now (6 decimals)
    again = vio_flight(place, difficulty)
    assert np.allclose(flight.p_W, again.p_W, atol=1e-6) and np.allclose(flight.yaw, again.yaw, atol=1e-6)
    # feed-forward consistent with the positions: v = dp/dt, yaw_rate = dyaw/dt (central differences)
    dt = np.diff(flight.t_s)[0]
    assert np.abs(np.gradient(flight.p_W, dt, axis=0) - flight.v_W).max() < 0.05
    assert np.abs(np.gradient(flight.yaw, dt) - flight.yaw_rate).max() < 0.05


def test_a_broken_trajectory_file_is_one_line(tmp_path: Path):
    bad = tmp_path / "bad.csv"
    bad.write_text("0,1,2,3\n1,1,2,3\n")
    with pytest.raises(ValueError, match="4 columns in 2 rows; expected 12 columns"):
        read_trajectory_file(bad)
    rows = np.loadtxt(FLIGHTS / "warehouse_easy.csv", delimiter=",", comments="#")[:5]
    rows[3, 0] = rows[1, 0]
    np.savetxt(bad, rows, delimiter=",")
    with pytest.raises(ValueError, match=r"the times must increase \(row 4\)"):
        read_trajectory_file(bad)
    node = package_path("rotors_gazebo") / "scripts" / "trajectory_publisher_file"
    result = subprocess.run([sys.executable, str(node), str(tmp_path / "missing.csv")], capture_output=True, text=True, timeout=60)
    assert result.returncode == 255 and "missing.csv" in result.stderr


@pytest.mark.long  # the long tier: make test-all / make test-long
@pytest.mark.parametrize(("place", "difficulty"), [("warehouse", "medium"), ("powerplant", "difficult")])
def test_vio_flight_launch_records_a_flight_shaped_like_euroc(ros: RosGraph, tmp_path: Path, place: str, difficulty: str):
    sequence, shape = EUROC_SHAPES[difficulty]
    flight = read_trajectory_file(FLIGHTS / f"{place}_{difficulty}.csv")
    proc = launch(ros, "rotors_gazebo", "mav_vio_flight.launch", f"world_name:={place}", f"difficulty:={difficulty}", "gui:=false")
    try:
        wait_sim_time(ros, DELAY_S + flight.duration_s + 2.0, timeout_s=1500)
    finally:
        stop_launch(proc)
    bags = sorted(Path(ros.env["ROS_HOME"]).glob(f"firefly_vio_{place}_{difficulty}_*.bag"))
    assert bags, Path(proc.log_path).read_text()[-3000:]
    recorded = FlightBag(bags[-1])
    description = RobotDescription.parse(next(msg for msg, _, _ in recorded.messages("firefly/robot_description")).data)
    out = tmp_path / "euroc"
    export = REPO / "rotors_gazebo_compat/rotors_evaluation/scripts/export_euroc.py"
    result = subprocess.run([sys.executable, str(export), "-b", str(bags[-1]), "-o", str(out)], capture_output=True, text=True, timeout=900)
    assert result.returncode == 0, result.stderr
    bags[-1].unlink()
    mav0 = out / "mav0"
    # every effect on, as recorded: the cameras' image sensor and the IMU's rotor vibration
    assert yaml.safe_load((mav0 / "cam0" / "sensor.yaml").read_text())["rotors_image_sensor"]["autoExposure"] is True
    assert yaml.safe_load((mav0 / "imu0" / "sensor.yaml").read_text())["rotors_imu_vibration"]["balanceGrade"] == 6.3
    # the flight as evo reads it, over the trajectory's time (from the first IMU sample + DELAY_S)
    from evo.tools import file_interface

    truth = file_interface.read_euroc_csv_trajectory(str(mav0 / "state_groundtruth_estimate0" / "data.csv"))
    imu_t0 = np.loadtxt(mav0 / "imu0" / "data.csv", delimiter=",", comments="#", max_rows=1)[0] * 1e-9

    # the ground truth is the IMU's (EuRoC's body frame); the trajectory is the base link's: p_B = p_I - R_WI p_IB
    from scipy.spatial.transform import Rotation

    p_IB = description.transform("firefly/vi_sensor/imu_link", "firefly/base_link")[:3, 3]
    R_WI = Rotation.from_quat(truth.orientations_quat_wxyz[:, [1, 2, 3, 0]])
    p_WB = truth.positions_xyz + R_WI.apply(p_IB)

    def tracking_rms(t0: float) -> float:
        inside = (truth.timestamps >= t0) & (truth.timestamps <= t0 + flight.duration_s)
        desired = np.array([np.interp(truth.timestamps[inside] - t0, flight.t_s, flight.p_W[:, i]) for i in range(3)]).T
        return float(np.sqrt(np.mean(np.linalg.norm(p_WB[inside] - desired, axis=1) ** 2)))

    # the trajectory is due DELAY_S after the first IMU message the publisher got, which the bag may
    # not hold: the start is found within 2 s of that, where the flight follows the file best
    t0 = min(imu_t0 + DELAY_S + np.arange(-2.0, 2.0, 0.01), key=tracking_rms)
    inside = (truth.timestamps >= t0) & (truth.timestamps <= t0 + flight.duration_s)
    t, p = truth.timestamps[inside], truth.positions_xyz[inside]
    # speeds and rotation rates over 50 ms, as EuRoC's shapes are computed
    k = max(1, int(round(0.05 / np.median(np.diff(t)))))

    q = truth.orientations_quat_wxyz[inside][::k]
    rotations = Rotation.from_quat(q[:, [1, 2, 3, 0]])
    dts = np.diff(t[::k])
    speed = np.linalg.norm(np.diff(p[::k], axis=0), axis=1) / dts
    rate = np.degrees((rotations[1:] * rotations[:-1].inv()).magnitude() / dts)
    print(
        f"flown {t[-1] - t[0]:.1f} s: mean speed {speed.mean():.3f} m/s (EuRoC {sequence} {shape.mean_speed_m_s}), "
        f"mean angular rate {rate.mean():.1f} deg/s ({shape.mean_angular_rate_deg_s}), "
        f"tracking RMS {tracking_rms(t0):.3f} m (start {t0 - imu_t0 - DELAY_S:+.2f} s), "
        f"{len(list((mav0 / 'cam0' / 'data').iterdir()))} stereo frames"
    )
    assert speed.mean() == pytest.approx(shape.mean_speed_m_s, rel=0.1)
    assert rate.mean() == pytest.approx(shape.mean_angular_rate_deg_s, rel=0.25)
    assert tracking_rms(t0) < 0.3  # the Lee controller at 0.9 m/s with the yaw swinging 30 deg
