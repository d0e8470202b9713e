#!/usr/bin/env python3
"""Writes a recorded VI-sensor flight in the EuRoC / ASL dataset layout, so that VIO pipelines and
Kalibr-style tools run on simulated data unchanged:

  <out>/mav0/cam0, cam1/   data.csv (#timestamp [ns],filename), data/<ns>.png, sensor.yaml
  <out>/mav0/imu0/         data.csv (gyro [rad/s], accel [m/s^2]), sensor.yaml (ADIS16448 noise)
  <out>/mav0/state_groundtruth_estimate0/data.csv   IMU-frame pose and velocity in the world

The body frame B is the VI-sensor's IMU, as in EuRoC; each sensor.yaml holds T_BS (the sensor in B)
for the VI-sensor geometry that rotors_description's vi_sensor_macro builds.

    rosrun rotors_evaluation export_euroc.py -b <bag> -o <dir> [--mav_name firefly]
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation.bag_data import BagError, FlightBag  # noqa: E402

# vi_sensor_macro geometry in the VI-sensor link frame L (x forward, z up)
P_L_IMU = np.array([0.015, 0.0, 0.0113])
P_L_CAM = {"left": np.array([0.015, 0.055, 0.0065]), "right": np.array([0.015, -0.055, 0.0065])}
# optical frame (x right, y down, z forward) in the camera link frame: rpy (-pi/2, 0, -pi/2)
R_L_OPTICAL = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])
# the ADIS16448 model of default_imu / vi_sensor_macro (continuous-time densities)
ADIS16448 = {
    "gyroscope_noise_density": 0.0003394,
    "gyroscope_random_walk": 0.000038785,
    "accelerometer_noise_density": 0.004,
    "accelerometer_random_walk": 0.006,
}


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


def _matrix_yaml(T: np.ndarray) -> str:
    rows = ",\n         ".join(", ".join(f"{v:.9f}" for v in row) for row in T)
    return f"  cols: 4\n  rows: 4\n  data: [{rows}]\n"


def _write_camera(bag: FlightBag, mav: str, side: str, out: Path, from_png) -> int:
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
    T_BS = np.eye(4)  # camera (optical) in the IMU frame; both rigid in L
    T_BS[:3, :3] = R_L_OPTICAL
    T_BS[:3, 3] = P_L_CAM[side] - P_L_IMU
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
    )
    return len(rows)


def _write_imu(bag: FlightBag, mav: str, out: Path) -> int:
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
    noise = "".join(f"{k}: {v!r}\n" for k, v in ADIS16448.items())
    (folder / "sensor.yaml").write_text(
        f"sensor_type: imu\ncomment: VI-sensor ADIS16448 (simulated)\nT_BS:\n{_matrix_yaml(np.eye(4))}" f"rate_hz: {rate:.3f}\n{noise}"
    )
    return len(lines)


def _write_ground_truth(bag: FlightBag, mav: str, out: Path) -> int:
    topic = bag.require(mav, "vi_sensor/ground_truth/odometry", "VI-sensor ground truth")
    folder = out / "mav0" / "state_groundtruth_estimate0"
    folder.mkdir(parents=True, exist_ok=True)
    lines = []
    for msg, _, _ in bag.messages(topic):
        pose, twist = msg.pose.pose, msg.twist.twist
        R_WL = _rotation(pose.orientation)
        p_WL = np.array([pose.position.x, pose.position.y, pose.position.z])
        # the IMU origin: p_WB = p_WL + R_WL p_L_IMU; v_WB = R_WL (v_L + w_L x p_L_IMU)
        p_WB = p_WL + R_WL @ P_L_IMU
        v_L = np.array([twist.linear.x, twist.linear.y, twist.linear.z])
        w_L = np.array([twist.angular.x, twist.angular.y, twist.angular.z])
        v_WB = R_WL @ (v_L + np.cross(w_L, P_L_IMU))
        q = pose.orientation  # B is parallel to L
        values = [*p_WB, q.w, q.x, q.y, q.z, *v_WB, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
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
            counts = {
                "cam0": _write_camera(bag, args.mav_name, "left", out, Image),
                "cam1": _write_camera(bag, args.mav_name, "right", out, Image),
                "imu0": _write_imu(bag, args.mav_name, out),
                "state_groundtruth_estimate0": _write_ground_truth(bag, args.mav_name, out),
            }
        finally:
            bag.close()
    except BagError as e:
        print(f"export_euroc.py: {e}", file=sys.stderr)
        return 1
    (out / "mav0" / "body.yaml").write_text("comment: body frame B = the VI-sensor IMU (as in EuRoC)\n")
    for name, n in counts.items():
        print(f"{name}: {n} rows")
    print(f"wrote {out / 'mav0'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
