"""A stereo visual odometry made only of OpenCV calls, run on the EuRoC export of a VI-sensor flight
through RotorS' warehouse. It checks in one go what a VIO user depends on: the images,
the intrinsics in cam0/cam1 sensor.yaml, the camera-IMU extrinsics T_BS, the stamps and the ground
truth. The flight is RotorS' VI hovering example (ROS, lockstep) with enable_logging:=true, given a
39.5 m loop through the aisles (rotors_gazebo.flight_paths) on command/trajectory; export_euroc.py makes
the dataset.

The odometry: keyframes whose Shi-Tomasi corners are matched into the right image by KLT along the
row (stereo depth Z = f b / d); the corners are tracked by KLT from frame to frame, and each frame's
pose relative to its keyframe comes from solvePnPRansac and solvePnPRefineLM on the inliers. A new
keyframe is taken when fewer than 200 corners remain or the camera has moved 1 m from the keyframe."""

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest
import yaml

import clients.visual_odometry
from rotors_gazebo.flight_paths import WAREHOUSE_FACING, WAREHOUSE_LOOP, WAREHOUSE_START, sample
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time

TRAJECTORY_DUE_S = 6.0  # from take-off on the ground (it replaces the hovering example's waypoint)
KLT = dict(winSize=(21, 21), maxLevel=3, criteria=(cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 30, 0.01))


def quaternion_matrix(w: float, x: float, y: float, z: float) -> np.ndarray:
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def transform(R: np.ndarray, t: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, t
    return T


class EuRoC:
    """The parts of an EuRoC sequence a stereo VO reads."""

    def __init__(self, mav0: Path):
        self.mav0 = mav0
        self.frames = {}
        for cam in ("cam0", "cam1"):
            with open(mav0 / cam / "data.csv") as f:
                self.frames[cam] = {int(r[0]): r[1] for r in csv.reader(f) if not r[0].startswith("#")}
        self.stamps = sorted(set(self.frames["cam0"]) & set(self.frames["cam1"]))
        sensor = [yaml.safe_load((mav0 / cam / "sensor.yaml").read_text()) for cam in ("cam0", "cam1")]
        fu, fv, cu, cv = sensor[0]["intrinsics"]
        assert sensor[1]["intrinsics"] == sensor[0]["intrinsics"], "the VO assumes one rectified pair"
        self.K = np.array([[fu, 0, cu], [0, fv, cv], [0, 0, 1]])
        self.T_BS = [np.array(s["T_BS"]["data"]).reshape(4, 4) for s in sensor]
        gt = np.loadtxt(mav0 / "state_groundtruth_estimate0" / "data.csv", delimiter=",", comments="#")
        self.gt_t, self.gt = gt[:, 0].astype(np.int64), gt

    def image(self, cam: str, stamp: int) -> np.ndarray:
        return cv2.imread(str(self.mav0 / cam / "data" / self.frames[cam][stamp]), cv2.IMREAD_GRAYSCALE)

    def T_WB(self, stamp: int) -> np.ndarray:
        """Ground truth at an image stamp (the sample on that stamp: the two share the sim clock)."""
        i = int(np.searchsorted(self.gt_t, stamp))
        assert i < len(self.gt_t) and self.gt_t[i] == stamp, f"no ground truth at image stamp {stamp}"
        row = self.gt[i]
        return transform(quaternion_matrix(*row[4:8]), row[1:4])


class StereoVO:
    def __init__(self, K: np.ndarray, baseline_m: float):
        self.K, self.b = K, baseline_m
        self.f, self.cu, self.cv = K[0, 0], K[0, 2], K[1, 2]

    def triangulate(self, left: np.ndarray, right: np.ndarray):
        """Corners of the left image with a stereo match: (N, 2) pixels and (N, 3) points in the left camera."""
        corners = cv2.goodFeaturesToTrack(left, maxCorners=1000, qualityLevel=0.01, minDistance=10)
        matched, ok, _ = cv2.calcOpticalFlowPyrLK(left, right, corners, None, **KLT)
        back, ok_back, _ = cv2.calcOpticalFlowPyrLK(right, left, matched, None, **KLT)
        uv, uv_r = corners.reshape(-1, 2), matched.reshape(-1, 2)
        d = uv[:, 0] - uv_r[:, 0]
        keep = (
            (ok.ravel() == 1)
            & (ok_back.ravel() == 1)
            & (np.linalg.norm(back.reshape(-1, 2) - uv, axis=1) < 0.5)
            & (np.abs(uv[:, 1] - uv_r[:, 1]) < 0.5)
            & (d > 0.5)
        )
        Z = self.f * self.b / d[keep]
        near = Z < 20.0  # beyond, a disparity under 2.5 px: too little depth information
        uv, Z = uv[keep][near], Z[near]
        X = np.column_stack([(uv[:, 0] - self.cu) * Z / self.f, (uv[:, 1] - self.cv) * Z / self.f, Z])
        return uv.astype(np.float32), X

    def run(self, frames, T_W_C_first: np.ndarray):
        """Camera poses in the world, one per stereo frame, starting from T_W_C_first."""
        poses = [T_W_C_first]
        left, right = next(frames)
        uv, X = self.triangulate(left, right)
        T_W_K = T_W_C_first  # the keyframe's pose
        T_C_K = np.eye(4)
        previous = left
        keyframes = 1
        for left, right in frames:
            tracked, ok, _ = cv2.calcOpticalFlowPyrLK(previous, left, uv.reshape(-1, 1, 2), None, **KLT)
            back, ok_back, _ = cv2.calcOpticalFlowPyrLK(left, previous, tracked, None, **KLT)
            keep = (ok.ravel() == 1) & (ok_back.ravel() == 1) & (np.linalg.norm(back.reshape(-1, 2) - uv, axis=1) < 1.0)
            uv, X = tracked.reshape(-1, 2)[keep], X[keep]
            found, rvec, tvec, inliers = cv2.solvePnPRansac(
                X, uv, self.K, None, iterationsCount=200, reprojectionError=1.0, confidence=0.999
            )
            assert found and inliers is not None and len(inliers) >= 20, "the VO lost track"
            inliers = inliers.ravel()
            rvec, tvec = cv2.solvePnPRefineLM(X[inliers], uv[inliers], self.K, None, rvec, tvec)
            T_new = transform(cv2.Rodrigues(rvec)[0], tvec.ravel())  # keyframe points into this camera
            # 1/30 s after the last frame: a jump of more than 0.2 m or 5 deg is a wrong solution
            step = T_new @ np.linalg.inv(T_C_K)
            turned_deg = np.degrees(np.arccos(np.clip((np.trace(step[:3, :3]) - 1) / 2, -1, 1)))
            assert np.linalg.norm(step[:3, 3]) < 0.2 and turned_deg < 5.0, "the VO jumped"
            T_C_K = T_new
            poses.append(T_W_K @ np.linalg.inv(T_C_K))
            uv, X = uv[inliers], X[inliers]
            if len(uv) < 200 or np.linalg.norm(T_C_K[:3, 3]) > 1.0:
                T_W_K, T_C_K = poses[-1], np.eye(4)
                uv, X = self.triangulate(left, right)
                keyframes += 1
            previous = left
        self.keyframes = keyframes
        return poses


def fly_and_export(ros: RosGraph, tmp_path: Path):
    """The flight's EuRoC folder (mav0) and the sim time [s] at which the loop begins (after take-off,
    facing down the first aisle)."""
    path = sample(
        (0.0, 0.0, 0.1, 0.0),
        [(0.0, 0.0, WAREHOUSE_START[2]), WAREHOUSE_START[:3]] + WAREHOUSE_LOOP,
        speed=1.5,
        accel=1.0,
        yaw_rate=0.8,
        facing=WAREHOUSE_FACING,
    )
    facing_start = np.abs(np.angle(np.exp(1j * (path.yaw - WAREHOUSE_START[3])))) < 1e-6
    at_start = (np.linalg.norm(path.p_W - WAREHOUSE_START[:3], axis=1) < 1e-6) & facing_start
    loop_begins_s = TRAJECTORY_DUE_S + float(path.t_s[np.argmax(at_start)])
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_hovering_example_with_vi_sensor.launch",
        "world_name:=warehouse",
        "enable_logging:=true",
        "lockstep:=true",
        "real_time_factor:=0",
        "gui:=false",
    )
    try:
        # the whole path on command/trajectory, due from TRAJECTORY_DUE_S on (each point at its time_from_start)
        points = tmp_path / "trajectory.json"
        points.write_text(
            json.dumps(
                [
                    dict(
                        p=path.p_W[i].tolist(),
                        v=path.v_W[i].tolist(),
                        a=path.a_W[i].tolist(),
                        yaw=float(path.yaw[i]),
                        rate=float(path.yaw_rate[i]),
                        t=float(path.t_s[i]),
                    )
                    for i in range(len(path.t_s))
                ]
            )
        )
        ros.run_client(clients.visual_odometry.send_trajectory, points_file=str(points), due_s=TRAJECTORY_DUE_S)
        wait_sim_time(ros, TRAJECTORY_DUE_S + path.duration_s, timeout_s=1500)
    finally:
        stop_launch(proc)
    bags = sorted(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    assert bags, Path(proc.log_path).read_text()[-3000:]
    out = tmp_path / "euroc"
    result = subprocess.run(
        [sys.executable, str(REPO / "rotors_gazebo_compat/rotors_evaluation/scripts/export_euroc.py"), "-b", str(bags[-1]), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert result.returncode == 0, result.stderr
    bags[-1].unlink()  # 1 GB of images, now in the export
    return out / "mav0", loop_begins_s


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_stereo_vo_on_euroc_export_of_warehouse_flight(ros: RosGraph, tmp_path: Path):
    mav0, loop_begins_s = fly_and_export(ros, tmp_path)
    data = EuRoC(mav0)
    # the right camera b metres along the left camera's x axis, the pair rectified (T_BS of both)
    T_C0_C1 = np.linalg.inv(data.T_BS[0]) @ data.T_BS[1]
    baseline_m = T_C0_C1[0, 3]
    assert np.allclose(T_C0_C1[:3, :3], np.eye(3)) and np.allclose(T_C0_C1[1:3, 3], 0.0) and baseline_m > 0.05

    stamps = [s for s in data.stamps if s >= loop_begins_s * 1e9]
    T_W_C_true = [data.T_WB(s) @ data.T_BS[0] for s in stamps]
    vo = StereoVO(data.K, baseline_m)
    frames = ((data.image("cam0", s), data.image("cam1", s)) for s in stamps)
    T_W_C_vo = vo.run(frames, T_W_C_true[0])

    p_true = np.array([T[:3, 3] for T in T_W_C_true])
    p_vo = np.array([T[:3, 3] for T in T_W_C_vo])
    flown_m = float(np.sum(np.linalg.norm(np.diff(p_true, axis=0), axis=1)))
    error_m = np.linalg.norm(p_vo - p_true, axis=1)
    R_end = T_W_C_vo[-1][:3, :3].T @ T_W_C_true[-1][:3, :3]
    yaw_error_deg = math.degrees(math.acos(np.clip((np.trace(R_end) - 1) / 2, -1, 1)))
    # stamps: the VO's frame-to-frame speed lines up with the ground truth's with no lag
    v_true, v_vo = np.diff(p_true, axis=0), np.diff(p_vo, axis=0)
    lags = range(-3, 4)
    misfit = [np.mean(np.linalg.norm(v_vo[3 + k : len(v_vo) - 3 + k] - v_true[3 : len(v_true) - 3], axis=1)) for k in lags]
    lag = list(lags)[int(np.argmin(misfit))]
    print(
        f"stereo VO over {len(stamps)} frames ({vo.keyframes} keyframes), {flown_m:.1f} m flown: end error "
        f"{error_m[-1]:.3f} m = {100 * error_m[-1] / flown_m:.2f} % of the distance (largest on the way "
        f"{error_m.max():.3f} m), end rotation error {yaw_error_deg:.2f} deg; speed misfit by lag "
        f"{dict(zip(lags, np.round(misfit, 4)))}"
    )
    assert flown_m >= 30.0
    assert error_m[-1] <= 0.02 * flown_m
    assert lag == 0
