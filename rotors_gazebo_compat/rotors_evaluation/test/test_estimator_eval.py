"""estimator_eval on a synthetic bag whose errors, bias errors, NEES and pose outage are known
exactly: the truth hovers at (0, 0, 1), the estimate sits 0.03 m off in x with a covariance that
makes each error exactly one sigma."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from rosbags.rosbag1 import Writer
from rosbags.typesys import get_types_from_msg
from synthetic_bags import TS, T, header, pose_stamped, twist_stamped, vec

SCRIPTS = Path(__file__).resolve().parents[1] / "scripts"
from rotors_evaluation.estimator import evaluate_estimator  # noqa: E402

for name, text in (
    ("rotors_comm/msg/ImuBias", "Header header\ngeometry_msgs/Vector3 gyroscope_bias\n" "geometry_msgs/Vector3 accelerometer_bias\n"),
    ("sensor_fusion_comm/msg/DoubleArrayStamped", "Header header\nfloat64[] data\n"),
    ("sensor_fusion_comm/msg/DoubleMatrixStamped", "Header header\nint32 rows\nint32 cols\nfloat64[] data\n"),
):
    TS.register(get_types_from_msg(text, name))

B_W_TRUE, B_A_TRUE = (0.01, 0.0, 0.0), (0.1, 0.0, 0.0)
B_W_EST, B_A_EST = (0.011, 0.0, 0.0), (0.08, 0.0, 0.0)  # 10 % and 20 % off
P_DIAG = np.full(15, 1.0)
P_DIAG[0] = 0.03**2  # dp_x = 0.03 m: one sigma
P_DIAG[9] = 0.001**2  # db_w,x = 0.001 rad/s: one sigma
P_DIAG[12] = 0.02**2  # db_a,x = 0.02 m/s^2: one sigma   -> NEES = 3 at every sample


def estimator_bag(path: Path) -> Path:
    with Writer(path) as w:
        conns = {
            name: w.add_connection(f"firefly/{topic}", msgtype, typestore=TS)
            for name, topic, msgtype in (
                ("pose", "ground_truth/pose", "geometry_msgs/msg/PoseStamped"),
                ("twist", "ground_truth/twist", "geometry_msgs/msg/TwistStamped"),
                ("odom", "msf_core/odometry", "nav_msgs/msg/Odometry"),
                ("cov", "msf_core/cov_core", "sensor_fusion_comm/msg/DoubleMatrixStamped"),
                ("state", "msf_core/state_out", "sensor_fusion_comm/msg/DoubleArrayStamped"),
                ("bias", "ground_truth/imu_bias", "rotors_comm/msg/ImuBias"),
                ("sensor", "odometry_sensor1/pose_with_covariance", "geometry_msgs/msg/PoseWithCovarianceStamped"),
            )
        }
        q = T["geometry_msgs/msg/Quaternion"](x=0, y=0, z=0, w=1)
        for k in range(1, 3001):
            t = k * 0.01
            ns = int(round(t * 1e9))
            odom = T["nav_msgs/msg/Odometry"](
                header=header(t),
                child_frame_id="imu",
                pose=T["geometry_msgs/msg/PoseWithCovariance"](
                    pose=T["geometry_msgs/msg/Pose"](position=T["geometry_msgs/msg/Point"](x=0.03, y=0.0, z=1.0), orientation=q),
                    covariance=np.zeros(36),
                ),
                twist=T["geometry_msgs/msg/TwistWithCovariance"](
                    twist=T["geometry_msgs/msg/Twist"](linear=vec(0, 0, 0), angular=vec(0, 0, 0)), covariance=np.zeros(36)
                ),
            )
            state = np.array([0.03, 0, 1, 0, 0, 0, 1, 0, 0, 0, *B_W_EST, *B_A_EST, 1, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0])
            msgs = [
                ("pose", pose_stamped(t, (0.0, 0.0, 1.0))),
                ("twist", twist_stamped(t, (0, 0, 0))),
                ("odom", odom),
                ("cov", T["sensor_fusion_comm/msg/DoubleMatrixStamped"](header=header(t), rows=15, cols=15, data=np.diag(P_DIAG).ravel())),
                ("state", T["sensor_fusion_comm/msg/DoubleArrayStamped"](header=header(t), data=state)),
                ("bias", T["rotors_comm/msg/ImuBias"](header=header(t), gyroscope_bias=vec(*B_W_TRUE), accelerometer_bias=vec(*B_A_TRUE))),
            ]
            if k % 10 == 0 and not 20.0 < t < 22.5:  # 10 Hz pose sensor with an outage
                msgs.append(
                    (
                        "sensor",
                        T["geometry_msgs/msg/PoseWithCovarianceStamped"](
                            header=header(t),
                            pose=T["geometry_msgs/msg/PoseWithCovariance"](
                                pose=T["geometry_msgs/msg/Pose"](position=T["geometry_msgs/msg/Point"](x=0, y=0, z=1), orientation=q),
                                covariance=np.zeros(36),
                            ),
                        ),
                    )
                )
            for name, msg in msgs:
                w.write(conns[name], ns, TS.serialize_ros1(msg, conns[name].msgtype))
    return path


def test_estimator_metrics_are_exact_on_a_known_bag(tmp_path: Path):
    r = evaluate_estimator(estimator_bag(tmp_path / "est.bag"), "firefly", begin=5.0, end=30.0)
    assert r.position_rms == pytest.approx(0.03, abs=1e-12)
    assert r.velocity_rms == 0.0 and r.attitude_rms_deg == 0.0
    assert r.gyroscope_bias_relative_error == pytest.approx(0.10, abs=1e-9)
    assert r.accelerometer_bias_relative_error == pytest.approx(0.20, abs=1e-9)
    assert r.nees_mean == pytest.approx(3.0, abs=1e-9)  # three one-sigma errors
    assert r.nees_fraction_inside_95 == 0.0 and r.nees_samples == 2501  # 3 < 6.26: too pessimistic a filter
    assert r.pose_gaps == [[pytest.approx(20.0), pytest.approx(22.5)]]


def test_estimator_eval_script_prints_and_writes_json(tmp_path: Path):
    bag = estimator_bag(tmp_path / "est.bag")
    res = subprocess.run(
        [
            sys.executable,
            str(SCRIPTS / "estimator_eval.py"),
            "-b",
            str(bag),
            "-n",
            "firefly",
            "--plot",
            "False",
            "--json",
            "-",
            "--begin_time",
            "5",
        ],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 0, res.stderr
    assert "Estimator position RMS error: 0.030 m" in res.stdout
    assert "Pose outage from 20.00 s to 22.50 s (2.50 s)" in res.stdout
    summary = json.loads(res.stdout[res.stdout.index("{") :])
    assert summary["nees_mean"] == pytest.approx(3.0)
    # a bag without an estimate: one line naming the topic
    res = subprocess.run(
        [
            sys.executable,
            str(SCRIPTS / "estimator_eval.py"),
            "-b",
            str(bag),
            "-n",
            "firefly",
            "--estimate_topic",
            "/odometry_sensor1/odometry",
            "--plot",
            "False",
        ],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 1 and len(res.stderr.strip().splitlines()) == 1
    assert "estimate topic 'firefly/odometry_sensor1/odometry' is not in bag" in res.stderr
