"""export_euroc.py takes the calibration and noise figures of the vehicle actually flown from the
bag: a bag shaped as the bag plugin writes it (camera_info, images, IMU, ground truth and the robot
description that xacro made of mav_with_vi_sensor.gazebo with sensor_realism:=true) exports T_BS
from the description's links, the IMU plugin's densities and rotor vibration and the camera plugin's image sensor;
evo's EuRoC reader reads the ground truth back with the bag's stamps; a bag without the description is one line
naming the fix."""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml
from PIL import Image
from rosbags.rosbag1 import Writer
from synthetic_bags import TS, T, header, vec

EVAL = Path(__file__).resolve().parents[1]
REPO = EVAL.parents[1]
EXPORT = EVAL / "scripts" / "export_euroc.py"
F_PX = 752 / (2 * math.tan(1.3962634 / 2))


def vi_sensor_description(**args: str) -> str:
    xacro = REPO / "rotors_description" / "scripts" / "rotors_xacro"
    model = REPO / "rotors_description" / "urdf" / "mav_with_vi_sensor.gazebo"
    cmd = [str(xacro), str(model), "mav_name:=firefly", *[f"{k}:={v}" for k, v in args.items()]]
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def camera_info(t: float, side: str):
    K = [F_PX, 0, 375.5, 0, F_PX, 239.5, 0, 0, 1]
    P = [F_PX, 0, 375.5, -F_PX * 0.11 if side == "right" else 0.0, 0, F_PX, 239.5, 0, 0, 0, 1, 0]
    roi = T["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0, width=0, do_rectify=False)
    return T["sensor_msgs/msg/CameraInfo"](
        header=header(t, f"firefly/vi_sensor/camera_{side}_optical_link"), height=480, width=752,
        distortion_model="plumb_bob", D=np.zeros(5), K=np.array(K, dtype=float),
        R=np.eye(3).ravel(), P=np.array(P, dtype=float), binning_x=0, binning_y=0, roi=roi,
    )  # fmt: skip


def image(t: float, side: str, value: int):
    return T["sensor_msgs/msg/Image"](
        header=header(t, f"firefly/vi_sensor/camera_{side}_optical_link"), height=480, width=752,
        encoding="mono8", is_bigendian=0, step=752, data=np.full(752 * 480, value, dtype=np.uint8),
    )  # fmt: skip


def imu(t: float):
    q = T["geometry_msgs/msg/Quaternion"](x=0, y=0, z=0, w=1)
    return T["sensor_msgs/msg/Imu"](
        header=header(t, "firefly/vi_sensor/imu_link"), orientation=q, orientation_covariance=np.full(9, -1.0),
        angular_velocity=vec(0.01, 0.0, 0.0), angular_velocity_covariance=np.zeros(9),
        linear_acceleration=vec(0.0, 0.0, 9.8), linear_acceleration_covariance=np.zeros(9),
    )  # fmt: skip


def odometry(t: float, child: str):
    pose = T["geometry_msgs/msg/Pose"](
        position=T["geometry_msgs/msg/Point"](x=1.0, y=2.0, z=3.0), orientation=T["geometry_msgs/msg/Quaternion"](x=0, y=0, z=0, w=1)
    )
    twist = T["geometry_msgs/msg/Twist"](linear=vec(0, 0, 0), angular=vec(0, 0, 0))
    return T["nav_msgs/msg/Odometry"](
        header=header(t), child_frame_id=child,
        pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.zeros(36)),
        twist=T["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=np.zeros(36)),
    )  # fmt: skip


def write_bag(path: Path, description: str | None) -> Path:
    with Writer(path) as w:
        conns = {}

        def conn(topic, msgtype):
            if topic not in conns:
                conns[topic] = w.add_connection(topic, msgtype, typestore=TS)
            return conns[topic]

        def put(topic, msgtype, t, msg):
            w.write(conn(topic, msgtype), int(t * 1e9), TS.serialize_ros1(msg, msgtype))

        if description is not None:
            put("firefly/robot_description", "std_msgs/msg/String", 0.001, T["std_msgs/msg/String"](data=description))
        for k in range(3):
            t = 1.0 + k / 30
            for side in ("left", "right"):
                put(f"firefly/vi_sensor/{side}/camera_info", "sensor_msgs/msg/CameraInfo", t, camera_info(t, side))
                put(f"firefly/vi_sensor/{side}/image_raw", "sensor_msgs/msg/Image", t, image(t, side, 40 + 10 * k))
        for k in range(100):
            t = 1.0 + k * 0.001
            put("firefly/vi_sensor/imu", "sensor_msgs/msg/Imu", t, imu(t))
            put("firefly/vi_sensor/ground_truth/odometry", "nav_msgs/msg/Odometry", t, odometry(t, "firefly/vi_sensor/base_link"))
    return path


def export(bag: Path, out: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(EXPORT), "-b", str(bag), "-o", str(out)], capture_output=True, text=True, timeout=120)


def test_export_takes_the_flown_vehicles_calibration_from_the_bag(tmp_path: Path):
    description = vi_sensor_description(sensor_realism="true")
    result = export(write_bag(tmp_path / "flight.bag", description), tmp_path / "euroc")
    assert result.returncode == 0, result.stderr
    mav0 = tmp_path / "euroc" / "mav0"
    cams = {c: yaml.safe_load((mav0 / c / "sensor.yaml").read_text()) for c in ("cam0", "cam1")}
    T0, T1 = (np.array(cams[c]["T_BS"]["data"]).reshape(4, 4) for c in ("cam0", "cam1"))
    # the description's geometry: the cameras 0.11 m apart along the IMU's y, looking along its x
    # (optical z), 15 mm ahead of the VI-sensor link and 4.8 mm below the IMU
    print("T_BS cam0:", np.round(T0, 4).tolist())
    assert np.allclose(T0[:3, 3] - T1[:3, 3], [0, 0.11, 0], atol=1e-9)
    assert np.allclose(T0[:3, 2], [1, 0, 0], atol=1e-9) and np.allclose(T0[:3, 0], [0, -1, 0], atol=1e-9)
    assert cams["cam0"]["intrinsics"] == pytest.approx([F_PX, F_PX, 375.5, 239.5])
    # the camera plugin's image sensor, as sensor_realism:=true set it
    sensor = cams["cam0"]["rotors_image_sensor"]
    assert sensor["autoExposure"] is True and sensor["photonNoise"] is True and sensor["adcBits"] == 10
    # the IMU plugin's noise, read from the description (the ADIS16448 of vi_sensor_macro)
    imu0 = yaml.safe_load((mav0 / "imu0" / "sensor.yaml").read_text())
    assert imu0["gyroscope_noise_density"] == 0.0003394 and imu0["accelerometer_random_walk"] == 0.006
    assert imu0["rotors_imu_vibration"]["balanceGrade"] == 6.3 and imu0["rotors_imu_vibration"]["bartlettTaps"] == 16
    # the same calibration in Kalibr's camchain-imucam and imu layouts (what VIO configurations take):
    # T_cam_imu the inverse of T_BS, cam1's T_cn_cnm1 the baseline, the IMU's densities and topic
    chain = yaml.safe_load((tmp_path / "euroc" / "kalibr" / "camchain-imucam.yaml").read_text())
    assert np.allclose(np.array(chain["cam0"]["T_cam_imu"]) @ T0, np.eye(4), atol=1e-9)
    assert np.allclose(np.array(chain["cam1"]["T_cam_imu"]) @ T1, np.eye(4), atol=1e-9)
    assert np.allclose(np.array(chain["cam1"]["T_cn_cnm1"])[:3, 3], [-0.11, 0, 0], atol=1e-9)
    assert chain["cam1"]["intrinsics"] == pytest.approx([F_PX, F_PX, 375.5, 239.5]) and chain["cam0"]["distortion_model"] == "radtan"
    kalibr_imu = yaml.safe_load((tmp_path / "euroc" / "kalibr" / "imu.yaml").read_text())["imu0"]
    assert kalibr_imu["gyroscope_noise_density"] == 0.0003394 and kalibr_imu["accelerometer_random_walk"] == 0.006
    assert kalibr_imu["rostopic"].endswith("firefly/vi_sensor/imu") and kalibr_imu["update_rate"] == pytest.approx(1000.0, rel=1e-6)
    # images read back as they were written
    rows = (mav0 / "cam1" / "data.csv").read_text().splitlines()[1:]
    assert len(rows) == 3 and np.asarray(Image.open(mav0 / "cam1" / "data" / rows[2].split(",")[1])).mean() == 60
    # the ground truth of the odometry plugin's link L at (1, 2, 3), level: the IMU at p_WL + p_LB
    gt = np.loadtxt(mav0 / "state_groundtruth_estimate0" / "data.csv", delimiter=",", comments="#")
    print("ground truth of B:", gt[0, 1:8].tolist())
    assert np.allclose(gt[0, 4:8], [1, 0, 0, 0]) and np.linalg.norm(gt[0, 1:4] - [1.0, 2.0, 3.0]) < 0.05

    # read back by evo's own EuRoC reader (a reader written elsewhere): the stamps are the bag's
    # odometry stamps to the nanosecond, the poses those of the file
    from evo.tools import file_interface

    trajectory = file_interface.read_euroc_csv_trajectory(str(mav0 / "state_groundtruth_estimate0" / "data.csv"))
    bag_stamps_ns = [int(round((1.0 + k * 0.001) * 1e9)) for k in range(100)]
    assert np.array_equal(np.round(trajectory.timestamps * 1e9).astype(np.int64), bag_stamps_ns)
    assert np.allclose(trajectory.positions_xyz, gt[:, 1:4]) and np.allclose(trajectory.orientations_quat_wxyz, gt[:, 4:8])
    print(f"evo read {trajectory.num_poses} poses over {trajectory.path_length:.3f} m")
    # the image and IMU stamps are the bag's header stamps
    image_stamps = [int(r.split(",")[0]) for r in rows]
    assert image_stamps == [int(round((1.0 + k / 30) * 1e9)) for k in range(3)]
    imu_stamps = np.loadtxt(mav0 / "imu0" / "data.csv", delimiter=",", comments="#", dtype=np.int64, usecols=0)
    assert imu_stamps.tolist() == bag_stamps_ns

    # without sensor_realism the image sensor is none
    plain = export(write_bag(tmp_path / "plain.bag", vi_sensor_description()), tmp_path / "plain")
    assert plain.returncode == 0, plain.stderr
    assert yaml.safe_load((tmp_path / "plain" / "mav0" / "cam0" / "sensor.yaml").read_text())["rotors_image_sensor"] == "none"
    assert yaml.safe_load((tmp_path / "plain" / "mav0" / "imu0" / "sensor.yaml").read_text())["rotors_imu_vibration"] == "none"


def test_a_bag_without_the_robot_description_is_one_line(tmp_path: Path):
    result = export(write_bag(tmp_path / "old.bag", None), tmp_path / "out")
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "has no firefly/robot_description" in lines[0] and "record the flight again" in lines[0], result.stderr
