#!/usr/bin/env python3
"""Writes a recorded VI-sensor flight in the EuRoC / ASL dataset layout, so that VIO pipelines and
Kalibr-style tools run on simulated data unchanged:

  <out>/mav0/cam0, cam1/   data.csv (#timestamp [ns],filename), data/<ns>.png, sensor.yaml
  <out>/mav0/imu0/         data.csv (gyro [rad/s], accel [m/s^2]), sensor.yaml (the IMU plugin's noise)
  <out>/mav0/state_groundtruth_estimate0/data.csv   IMU-frame pose and velocity in the world
  <out>/kalibr/camchain-imucam.yaml, imu.yaml        the calibration in Kalibr's layout (VIO configs)

The body frame B is the VI-sensor's IMU, as in EuRoC. Everything comes from the bag, for the vehicle
actually flown: the cameras' intrinsics and distortion from camera_info, each sensor.yaml's T_BS
(the sensor in B) from the robot description the bag plugin records (<ns>/robot_description: the
IMU's and cameras' links), the IMU's noise densities and random walks from its IMU plugin's
parameters there, and each camera's image sensor parameters (exposure, noise, rolling shutter;
docs/sensor_realism.md) from its camera plugin's, written under `rotors_image_sensor` beside
EuRoC's keys.

    rosrun rotors_evaluation export_euroc.py -b <bag> -o <dir> [--mav_name firefly]
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation.bag_data import BagError, FlightBag  # noqa: E402
from rotors_evaluation.robot_description import DescriptionError, RobotDescription  # noqa: E402

IMU_PLUGIN = "librotors_gazebo_imu_plugin.so"
ODOMETRY_PLUGIN = "librotors_gazebo_odometry_plugin.so"
CAMERA_PLUGIN = "libgazebo_ros_multicamera.so"
# the image sensor's plugin parameters (docs/sensor_realism.md), as the camera plugins read them
IMAGE_SENSOR_PARAMS = (
    "exposureTime",
    "blurMethod",
    "maxSubframes",
    "subframesPerPixel",
    "lineDelay",
    "autoExposure",
    "autoExposureDesiredBin",
    "autoExposureLowPass",
    "autoGainLowPass",
    "autoExposureUpdateInterval",
    "rowTime",
    "maxShutterWidth",
    "maxAnalogGain",
    "referenceExposure",
    "photonNoise",
    "fullWellCapacity",
    "readNoise",
    "photoResponseNonUniformity",
    "darkSignalNonUniformity",
    "adcBits",
    "vignetting",
    "vignettingCoefficients",
    "timeOffset",
    "stampJitter",
)


def _description(bag: FlightBag, mav: str) -> RobotDescription:
    topic = f"{mav}/robot_description"
    if topic not in bag.topics:
        raise BagError(
            f"{bag.path.name} has no {topic}: the calibration and noise figures come from the robot description "
            "the bag plugin records; record the flight again (enable_logging:=true)"
        )
    return RobotDescription.parse(next(msg for msg, _, _ in bag.messages(topic)).data)


def _imu_frame(bag: FlightBag, mav: str) -> str:
    topic = bag.require(mav, "vi_sensor/imu", "VI-sensor IMU")
    return next(msg for msg, _, _ in bag.messages(topic)).header.frame_id


def _ns(stamp) -> int:
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def _rotation(q) -> np.ndarray:
    w, x, y, z = q.w, q.x, q.y, q.z
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _quaternion(R: np.ndarray) -> list[float]:
    """(w, x, y, z) of a rotation matrix, w >= 0 (Shepperd's method)."""
    t = np.trace(R)
    if t > 0:
        s = 2.0 * np.sqrt(1.0 + t)
        q = [0.25 * s, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k])
        q = [0.0] * 4
        q[0] = (R[k, j] - R[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (R[j, i] + R[i, j]) / s
        q[1 + k] = (R[k, i] + R[i, k]) / s
    q = np.array(q)
    return list(q if q[0] >= 0 else -q)


def _matrix_yaml(T: np.ndarray) -> str:
    rows = ",\n         ".join(", ".join(f"{v:.9f}" for v in row) for row in T)
    return f"  cols: 4\n  rows: 4\n  data: [{rows}]\n"


def _write_camera(bag: FlightBag, mav: str, side: str, out: Path, from_png, urdf: RobotDescription) -> int:
    image_topic = bag.require(mav, f"vi_sensor/{side}/image_raw", f"{side} image")
    info_topic = bag.require(mav, f"vi_sensor/{side}/camera_info", f"{side} camera_info")
    info = next(msg for msg, _, _ in bag.messages(info_topic))
    name = "cam0" if side == "left" else "cam1"
    folder = out / "mav0" / name
    (folder / "data").mkdir(parents=True, exist_ok=True)
    rows, stamps = [], []
    for msg, _, _ in bag.messages(image_topic):
        if msg.encoding != "mono8":
            raise BagError(f"{image_topic}: encoding '{msg.encoding}' (EuRoC images are mono8)")
        t = _ns(msg.header.stamp)
        pixels = np.frombuffer(bytes(msg.data), dtype=np.uint8).reshape(msg.height, msg.step)[:, : msg.width]
        from_png.fromarray(pixels, mode="L").save(folder / "data" / f"{t}.png")
        rows.append(f"{t},{t}.png")
        stamps.append(t)
    if not rows:
        raise BagError(f"no images on {image_topic}")
    (folder / "data.csv").write_text("#timestamp [ns],filename\n" + "\n".join(rows) + "\n")
    T_BS = urdf.transform(_imu_frame(bag, mav), info.header.frame_id)  # the camera's optical frame in B
    camera = urdf.plugin_params(CAMERA_PLUGIN, robotNamespace=mav, cameraName="vi_sensor")
    image_sensor = {k: camera[k] for k in IMAGE_SENSOR_PARAMS if k in camera}
    image_sensor_yaml = "\n" + "".join(f"  {k}: {v}\n" for k, v in image_sensor.items()) if image_sensor else " none\n"
    rate = (len(stamps) - 1) / ((stamps[-1] - stamps[0]) * 1e-9) if len(stamps) > 1 else 0.0
    K = info.K
    D = list(info.D) + [0.0] * (5 - len(info.D))  # plumb_bob: k1 k2 p1 p2 k3
    if D[4] != 0.0:
        raise BagError(f"{info_topic}: k3 = {D[4]!r}; EuRoC's radial-tangential model has k1 k2 p1 p2 only")
    (folder / "sensor.yaml").write_text(
        f"sensor_type: camera\ncomment: VI-sensor {side} camera (simulated, {bag.path.name})\n"
        f"T_BS:\n{_matrix_yaml(T_BS)}rate_hz: {rate:.3f}\nresolution: [{info.width}, {info.height}]\n"
        f"camera_model: pinhole\nintrinsics: [{K[0]!r}, {K[4]!r}, {K[2]!r}, {K[5]!r}]\n"
        f"distortion_model: radial-tangential\ndistortion_coefficients: [{D[0]!r}, {D[1]!r}, {D[2]!r}, {D[3]!r}]\n"
        f"rotors_image_sensor:{image_sensor_yaml}"
    )
    kalibr = {
        "T_BS": T_BS,
        "intrinsics": [K[0], K[4], K[2], K[5]],
        "distortion_coeffs": D[:4],
        "resolution": [info.width, info.height],
        "rostopic": "/" + image_topic.lstrip("/"),
    }
    return len(rows), kalibr


def _write_imu(bag: FlightBag, mav: str, out: Path, urdf: RobotDescription) -> int:
    topic = bag.require(mav, "vi_sensor/imu", "VI-sensor IMU")
    folder = out / "mav0" / "imu0"
    folder.mkdir(parents=True, exist_ok=True)
    lines, stamps = [], []
    for msg, _, _ in bag.messages(topic):
        w, a = msg.angular_velocity, msg.linear_acceleration
        t = _ns(msg.header.stamp)
        lines.append(f"{t},{w.x!r},{w.y!r},{w.z!r},{a.x!r},{a.y!r},{a.z!r}")
        stamps.append(t)
    if not lines:
        raise BagError(f"no messages on {topic}")
    (folder / "data.csv").write_text(
        "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
        "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n" + "\n".join(lines) + "\n"
    )
    rate = (len(stamps) - 1) / ((stamps[-1] - stamps[0]) * 1e-9) if len(stamps) > 1 else 0.0
    # the IMU plugin's continuous-time densities (RotorS' xacro spells the gyroscope's random walk
    # gyroscopeRandomWalk, the plugin also takes gyroscopeBiasRandomWalk)
    p = urdf.plugin_params(IMU_PLUGIN, robotNamespace=f"{mav}/vi_sensor", imuTopic="imu")
    walk_g = p.get("gyroscopeRandomWalk", p.get("gyroscopeBiasRandomWalk"))
    walk_a = p.get("accelerometerRandomWalk", p.get("accelerometerBiasRandomWalk"))
    if walk_g is None or walk_a is None or "gyroscopeNoiseDensity" not in p or "accelerometerNoiseDensity" not in p:
        raise DescriptionError(f"the VI-sensor's {IMU_PLUGIN} lacks a noise density or random walk: {sorted(p)}")
    noise = (
        f"gyroscope_noise_density: {float(p['gyroscopeNoiseDensity'])!r}\ngyroscope_random_walk: {float(walk_g)!r}\n"
        f"accelerometer_noise_density: {float(p['accelerometerNoiseDensity'])!r}\naccelerometer_random_walk: {float(walk_a)!r}\n"
    )
    # the rotor vibration the IMU felt (docs/sensor_realism.md, S8), or none
    vibration_keys = (
        "balanceGrade",
        "residualUnbalance",
        "bladeCount",
        "bladePassThrustRipple",
        "internalSampleRate",
        "bartlettTaps",
        "frameModeFrequency",
        "frameModeDamping",
        "thrustNoiseDensity",
    )
    if p.get("rotorVibration", "false").strip().lower() in ("true", "1"):
        vibration = "".join(f"\n  {k}: {float(p[k])!r}" for k in vibration_keys if k in p)
    else:
        vibration = " none"
    (folder / "sensor.yaml").write_text(
        f"sensor_type: imu\ncomment: VI-sensor IMU (simulated, {bag.path.name})\nT_BS:\n{_matrix_yaml(np.eye(4))}"
        f"rate_hz: {rate:.3f}\n{noise}rotors_imu_vibration:{vibration}\n"
    )
    return len(lines), {"noise": noise, "rostopic": "/" + topic.lstrip("/"), "update_rate": rate}


def _kalibr_matrix(T: np.ndarray, indent: str = "  ") -> str:
    return "".join(f"{indent}- [{', '.join(f'{v:.9f}' for v in row)}]\n" for row in T)


def _write_kalibr(out: Path, cameras: list[dict], imu: dict, bag_name: str) -> None:
    """The calibration as Kalibr writes it (camchain-imucam and imu yaml files), the input that
    OpenVINS, VINS-Fusion and ORB-SLAM3's converters take: T_cam_imu (IMU to camera), the intrinsics
    (fu, fv, cu, cv), radtan distortion, the resolution and topic; cam1 also T_cn_cnm1 (cam0 to
    cam1); the IMU's densities and random walks and its rate."""
    folder = out / "kalibr"
    folder.mkdir(parents=True, exist_ok=True)
    text = f"# {bag_name}: the simulated VI-sensor (export_euroc.py), Kalibr's camchain-imucam layout\n"
    T_cam_imu = [np.linalg.inv(c["T_BS"]) for c in cameras]
    for i, c in enumerate(cameras):
        text += f"cam{i}:\n  T_cam_imu:\n{_kalibr_matrix(T_cam_imu[i], '  ')}"
        if i > 0:
            text += f"  T_cn_cnm1:\n{_kalibr_matrix(T_cam_imu[i] @ np.linalg.inv(T_cam_imu[i - 1]), '  ')}"
        text += (
            f"  cam_overlaps: [{', '.join(str(j) for j in range(len(cameras)) if j != i)}]\n  camera_model: pinhole\n"
            f"  distortion_coeffs: [{', '.join(repr(float(d)) for d in c['distortion_coeffs'])}]\n  distortion_model: radtan\n"
            f"  intrinsics: [{', '.join(repr(float(k)) for k in c['intrinsics'])}]\n"
            f"  resolution: [{c['resolution'][0]}, {c['resolution'][1]}]\n  rostopic: {c['rostopic']}\n  timeshift_cam_imu: 0.0\n"
        )
    (folder / "camchain-imucam.yaml").write_text(text)
    noise = "".join(f"  {line}\n" for line in imu["noise"].splitlines())
    (folder / "imu.yaml").write_text(
        f"# {bag_name}: the simulated VI-sensor's IMU plugin (export_euroc.py), Kalibr's imu layout\n"
        f"imu0:\n  T_i_b:\n{_kalibr_matrix(np.eye(4), '  ')}{noise}  rostopic: {imu['rostopic']}\n  update_rate: {imu['update_rate']:.3f}\n"
    )


def _write_ground_truth(bag: FlightBag, mav: str, out: Path, urdf: RobotDescription) -> int:
    topic = bag.require(mav, "vi_sensor/ground_truth/odometry", "VI-sensor ground truth")
    # the ground truth's link L (its odometry plugin's) and the IMU B in it
    odometry = urdf.plugin_params(ODOMETRY_PLUGIN, robotNamespace=f"{mav}/vi_sensor", odometryTopic="ground_truth/odometry")
    T_LB = urdf.transform(odometry["linkName"], _imu_frame(bag, mav))
    p_L_B, R_LB = T_LB[:3, 3], T_LB[:3, :3]
    folder = out / "mav0" / "state_groundtruth_estimate0"
    folder.mkdir(parents=True, exist_ok=True)
    lines = []
    for msg, _, _ in bag.messages(topic):
        pose, twist = msg.pose.pose, msg.twist.twist
        R_WL = _rotation(pose.orientation)
        p_WL = np.array([pose.position.x, pose.position.y, pose.position.z])
        # the IMU origin: p_WB = p_WL + R_WL p_L_B; v_WB = R_WL (v_L + w_L x p_L_B); R_WB = R_WL R_LB
        p_WB = p_WL + R_WL @ p_L_B
        v_L = np.array([twist.linear.x, twist.linear.y, twist.linear.z])
        w_L = np.array([twist.angular.x, twist.angular.y, twist.angular.z])
        v_WB = R_WL @ (v_L + np.cross(w_L, p_L_B))
        q = _quaternion(R_WL @ R_LB)
        values = [*p_WB, *q, *v_WB, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        lines.append(f"{_ns(msg.header.stamp)}," + ",".join(repr(float(v)) for v in values))
    if not lines:
        raise BagError(f"no messages on {topic}")
    (folder / "data.csv").write_text(
        "#timestamp,p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],q_RS_z [],"
        "v_RS_R_x [m s^-1],v_RS_R_y [m s^-1],v_RS_R_z [m s^-1],b_w_RS_S_x [rad s^-1],b_w_RS_S_y [rad s^-1],"
        "b_w_RS_S_z [rad s^-1],b_a_RS_S_x [m s^-2],b_a_RS_S_y [m s^-2],b_a_RS_S_z [m s^-2]\n" + "\n".join(lines) + "\n"
    )
    return len(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-b", "--bag", required=True, help="bag of a VI-sensor flight (enable_logging:=true)")
    parser.add_argument("-o", "--output", required=True, help="dataset folder to write (mav0/... inside)")
    parser.add_argument("--mav_name", default="firefly")
    args = parser.parse_args(argv)
    try:
        from PIL import Image  # matplotlib's own PNG writer

        bag = FlightBag(Path(args.bag))
        out = Path(args.output)
        try:
            urdf = _description(bag, args.mav_name)
            (n_left, left), (n_right, right) = (_write_camera(bag, args.mav_name, side, out, Image, urdf) for side in ("left", "right"))
            n_imu, imu = _write_imu(bag, args.mav_name, out, urdf)
            counts = {
                "cam0": n_left,
                "cam1": n_right,
                "imu0": n_imu,
                "state_groundtruth_estimate0": _write_ground_truth(bag, args.mav_name, out, urdf),
            }
            _write_kalibr(out, [left, right], imu, bag.path.name)
        finally:
            bag.close()
    except (BagError, DescriptionError) as e:
        print(f"export_euroc.py: {e}", file=sys.stderr)
        return 1
    (out / "mav0" / "body.yaml").write_text("comment: body frame B = the VI-sensor IMU (as in EuRoC)\n")
    for name, n in counts.items():
        print(f"{name}: {n} rows")
    print(f"wrote {out / 'mav0'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
