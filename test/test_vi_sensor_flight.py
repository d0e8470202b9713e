"""End to end: the hovering example with the VI-sensor (RotorS' mav_hovering_example_with_vi_sensor
.launch) records stereo images, the VI-sensor's IMU and ground truth with enable_logging:=true, and
export_euroc.py turns that bag into an EuRoC dataset that is read back here."""

import csv
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml
from PIL import Image

from rotors_evaluation.bag_data import FlightBag
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time

F_PX = 752 / (2 * math.tan(1.3962634 / 2))  # f = W / (2 tan(hfov / 2))
VI_TOPICS = [
    f"/firefly/vi_sensor/{t}"
    for t in ("left/image_raw", "left/camera_info", "right/image_raw", "right/camera_info", "imu", "ground_truth/odometry")
]


def stamps(bag: FlightBag, topic: str):
    return [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for m, _, _ in bag.messages(topic)]


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_vi_sensor_flight_records_synced_stereo_exports_euroc(ros: RosGraph, tmp_path: Path):
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_hovering_example_with_vi_sensor.launch",
        "enable_logging:=true",
        "lockstep:=true",
        "real_time_factor:=0",
        "gui:=false",
    )
    try:
        wait_sim_time(ros, 8.0)
        topics = ros.run(["rostopic", "list"]).stdout.split()
    finally:
        stop_launch(proc)
    missing = [t for t in VI_TOPICS if t not in topics]
    assert not missing, f"topics missing: {missing}"
    bags = sorted(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    assert bags, Path(proc.log_path).read_text()[-3000:]

    bag = FlightBag(bags[-1])
    left = stamps(bag, "firefly/vi_sensor/left/image_raw")
    right = stamps(bag, "firefly/vi_sensor/right/image_raw")
    # one stamp per stereo pair, 30 frames per second of sim time (the recording may stop between
    # the two images of the last pair)
    n = min(len(left), len(right))
    assert n > 100 and abs(len(left) - len(right)) <= 1 and left[:n] == right[:n], (len(left), len(right))
    left = left[:n]
    rate = (len(left) - 1) / ((left[-1] - left[0]) * 1e-9)
    print(f"{len(left)} stereo pairs, {rate:.3f} Hz in sim time")
    assert abs(rate - 30.0) < 0.3
    image = next(m for m, _, _ in bag.messages("firefly/vi_sensor/left/image_raw"))
    assert (image.width, image.height, image.encoding) == (752, 480, "mono8")
    assert image.header.frame_id == "firefly/vi_sensor/camera_left_optical_link"
    info_l = next(m for m, _, _ in bag.messages("firefly/vi_sensor/left/camera_info"))
    info_r = next(m for m, _, _ in bag.messages("firefly/vi_sensor/right/camera_info"))
    assert np.allclose(info_l.K, [F_PX, 0, 375.5, 0, F_PX, 239.5, 0, 0, 1])
    assert math.isclose(info_r.P[3], -F_PX * 0.11, rel_tol=1e-9) and info_l.P[3] == 0.0
    imu = stamps(bag, "firefly/vi_sensor/imu")
    # IMU and images on one clock: every image lies within the IMU's span and on an IMU stamp
    assert imu[0] <= left[0] and left[-1] <= imu[-1] and set(left) <= set(imu)
    bag.close()

    out = tmp_path / "euroc"
    result = subprocess.run(
        [sys.executable, str(REPO / "rotors_gazebo_compat/rotors_evaluation/scripts/export_euroc.py"), "-b", str(bags[-1]), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr
    print(result.stdout)

    mav0 = out / "mav0"
    rows = {}
    for cam in ("cam0", "cam1"):
        with open(mav0 / cam / "data.csv") as f:
            rows[cam] = [r for r in csv.reader(f) if not r[0].startswith("#")]
        assert [int(r[0]) for r in rows[cam]][:n] == left
        png = Image.open(mav0 / cam / "data" / rows[cam][len(left) // 2][1])
        assert png.size == (752, 480) and png.mode == "L"
        sensor = yaml.safe_load((mav0 / cam / "sensor.yaml").read_text())
        assert np.allclose(sensor["intrinsics"], [F_PX, F_PX, 375.5, 239.5])
        assert sensor["resolution"] == [752, 480] and abs(sensor["rate_hz"] - 30.0) < 0.3
        T_BS = np.array(sensor["T_BS"]["data"]).reshape(4, 4)
        assert np.allclose(T_BS[:3, :3] @ T_BS[:3, :3].T, np.eye(3))
    # the two cameras 0.11 m apart along the IMU's y axis, looking along its x axis
    T0 = np.array(yaml.safe_load((mav0 / "cam0/sensor.yaml").read_text())["T_BS"]["data"]).reshape(4, 4)
    T1 = np.array(yaml.safe_load((mav0 / "cam1/sensor.yaml").read_text())["T_BS"]["data"]).reshape(4, 4)
    assert np.allclose(T0[:3, 3] - T1[:3, 3], [0, 0.11, 0]) and np.allclose(T0[:3, 2], [1, 0, 0])
    imu_rows = np.loadtxt(mav0 / "imu0/data.csv", delimiter=",", comments="#")
    assert len(imu_rows) == len(imu)
    # hovering: the accelerometer reads about +g along the IMU's z
    assert abs(np.median(imu_rows[-100:, 6]) - 9.8) < 0.5
    gt = np.loadtxt(mav0 / "state_groundtruth_estimate0/data.csv", delimiter=",", comments="#")
    assert gt.shape[1] == 17 and len(gt) > 100
    # on the ground at first (the VI-sensor hangs 3 cm below the base link), climbing to 1 m after 5 s
    assert gt[0, 3] < 0.15 and gt[-1, 3] > 0.5, (gt[0, 1:4], gt[-1, 1:4])
    assert np.allclose(np.linalg.norm(gt[:, 4:8], axis=1), 1.0)
