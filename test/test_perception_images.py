"""Images a feature-based VIO front end can use: VI-sensor flights through RotorS'
warehouse (textured Collada boxes and pallets, shelves, tarmac) and the textured power plant (cast
concrete, tarmac), with the sun's shadows. Every 0.5 s of flight after take-off the left camera's
frame goes through OpenCV as a VIO front end would:
- Shi-Tomasi corners (goodFeaturesToTrack, quality 0.01, min distance 10 px, max 1000),
- KLT tracks into the next frame (1/30 s later) kept with a forward-backward error < 1 px,
- StereoSGBM depth at the corners against the ground-truth depth rendered with the left image.

Through the Python module (no ROS): the same engine, plugins, renderer and Lee controller library
as under ROS; the vehicle flies rotors_gazebo.flight_paths's paths closed loop."""

from dataclasses import dataclass, field

import cv2
import numpy as np
import pytest

import rotors_sim as rs
from rotors_gazebo.flight_paths import (
    POWERPLANT_FACING,
    POWERPLANT_PATH,
    POWERPLANT_START,
    WAREHOUSE_FACING,
    WAREHOUSE_LOOP,
    WAREHOUSE_START,
    sample,
)

VI_SENSOR = rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo"
STEREO = "firefly_vi_sensor_stereo_camera"
W, H = 752, 480
F_PX, BASELINE_M = W / (2.0 * np.tan(1.3962634 / 2.0)), 0.11
SGBM = dict(
    minDisparity=0,
    numDisparities=128,
    blockSize=5,
    P1=8 * 25,
    P2=32 * 25,
    uniquenessRatio=10,
    speckleWindowSize=100,
    speckleRange=2,
    mode=cv2.STEREO_SGBM_MODE_SGBM_3WAY,
)


@dataclass
class Figures:
    corners: list[int] = field(default_factory=list)
    tracks: list[int] = field(default_factory=list)
    sgbm_within: int = 0
    sgbm_matched: int = 0
    relative: list[float] = field(default_factory=list)
    depth_m: list[float] = field(default_factory=list)  # ground truth of each corner with a disparity
    worst_tracking_m: float = 0.0

    def line(self, world: str) -> str:
        c, t = np.array(self.corners), np.array(self.tracks)
        z, good = np.array(self.depth_m), np.abs(np.array(self.relative)) <= 0.03
        bands = ", ".join(
            f"{lo}-{hi} m {100 * good[(z >= lo) & (z < hi)].mean():.0f} % of {np.sum((z >= lo) & (z < hi))}"
            for lo, hi in ((0, 4), (4, 8), (8, 30))
            if np.any((z >= lo) & (z < hi))
        )
        return (
            f"{world}: {len(c)} frames; Shi-Tomasi corners median {np.median(c):.0f}, 10th percentile "
            f"{np.percentile(c, 10):.0f}; KLT tracks kept median {np.median(t):.0f}, 10th percentile "
            f"{np.percentile(t, 10):.0f}; SGBM depth within 3 % for {100 * self.sgbm_within / self.sgbm_matched:.1f} % "
            f"of {self.sgbm_matched} corners with a disparity ({bands}; median relative error "
            f"{np.median(self.relative):+.4f}); "
            f"tracking error at most {self.worst_tracking_m:.2f} m"
        )


def left(world: rs.World) -> np.ndarray:
    return world.camera_image("firefly", STEREO, 0).reshape(H, W).copy()


def fly_and_measure(world_name: str, start, corners, facing=None, every_s: float = 0.5) -> Figures:
    """Flies the path closed loop and measures a frame every `every_s` after take-off."""
    world = rs.World(world_name)
    x, y, z, yaw = start
    world.spawn_mav("firefly", model=VI_SENSOR, random_seed=3, xyz=(x, y, 0.1), rpy=(0.0, 0.0, yaw), enable_vi_ground_truth_depth=True)
    controller = rs.LeePositionController.for_mav("firefly")
    world.attach_controller("firefly", controller)
    path = sample((x, y, 0.1, yaw), [(x, y, z)] + list(corners), facing=facing)
    take_off_end = float(np.argmax(path.p_W[:, 2] >= z - 1e-6)) * 0.02 + 1.0
    sgbm = cv2.StereoSGBM_create(**SGBM)
    frame_steps = int(np.ceil(1.0 / 30.0 / world.step_size)) + 1
    figures, next_frame_s = Figures(), take_off_end
    t0 = world.time
    while (i := int((world.time - t0) / 0.02)) < len(path.t_s):
        controller.set_point(path.p_W[i], path.yaw[i], path.v_W[i], path.a_W[i], path.yaw_rate[i])
        world.step(max(1, int(round(0.02 / world.step_size))))
        position = world.odometry("firefly").position_W
        if world.time - t0 > take_off_end:
            figures.worst_tracking_m = max(figures.worst_tracking_m, float(np.linalg.norm(position - path.p_W[i])))
            assert not world.in_contact("firefly"), f"{world_name}: the firefly hit something at {position}"
        if world.time - t0 < next_frame_s:
            continue
        next_frame_s += every_s
        first, right = left(world), world.camera_image("firefly", STEREO, 1).reshape(H, W).copy()
        depth_gt = world.camera_depth("firefly", STEREO, 0).copy()
        found = cv2.goodFeaturesToTrack(first, maxCorners=1000, qualityLevel=0.01, minDistance=10)
        figures.corners.append(0 if found is None else len(found))
        if found is None:
            continue
        # SGBM depth Z = f b / d at the corners against the rendered depth
        disparity = sgbm.compute(first, right).astype(np.float32) / 16.0  # fixed point, 4 fractional bits
        u, v = np.round(found[:, 0, 0]).astype(int), np.round(found[:, 0, 1]).astype(int)
        d, z_gt = disparity[v, u], depth_gt[v, u]
        has = (d > 0.5) & np.isfinite(z_gt)
        z_stereo = F_PX * BASELINE_M / d[has]
        figures.sgbm_within += int(np.sum(np.abs(z_stereo - z_gt[has]) <= 0.03 * z_gt[has]))
        figures.sgbm_matched += int(np.sum(has))
        figures.relative.extend(((z_stereo - z_gt[has]) / z_gt[has]).tolist())
        figures.depth_m.extend(z_gt[has].tolist())
        # the next frame, 1/30 s on (the set point held)
        world.step(frame_steps)
        second = left(world)
        forward, ok, _ = cv2.calcOpticalFlowPyrLK(first, second, found, None)
        back, ok_back, _ = cv2.calcOpticalFlowPyrLK(second, first, forward, None)
        fb_error = np.linalg.norm((back - found).reshape(-1, 2), axis=1)
        figures.tracks.append(int(np.sum((ok.ravel() == 1) & (ok_back.ravel() == 1) & (fb_error < 1.0))))
    return figures


def test_warehouse_loads_rotors_models_nested_and_stand_ins():
    models = rs.World("warehouse").models()
    # RotorS' world: 12 shelves, pallets with boxes (nested models built as models of their own),
    # the stand-ins, the asphalt and the ground
    assert sum(m.startswith("shelves ") for m in models) == 12
    assert any(m.endswith("::small_box_1_lvl_1") for m in models)
    assert {"grey_wall", "first_2015_trash_can", "asphalt_plane", "ground_plane"} <= set(models)


# the warehouse flight (about 90 s here) in the long tier, which keeps make test under 25 min; the
# power plant flight stays in the quick tier
@pytest.mark.parametrize(
    "world_name", [pytest.param("warehouse", marks=pytest.mark.long), pytest.param("powerplant", marks=pytest.mark.long)]
)
def test_vi_sensor_flight_gives_corners_tracks_stereo_depth(world_name):
    start, corners, facing = {
        "warehouse": (WAREHOUSE_START, WAREHOUSE_LOOP, WAREHOUSE_FACING),
        "powerplant": (POWERPLANT_START, POWERPLANT_PATH, POWERPLANT_FACING),
    }[world_name]
    figures = fly_and_measure(world_name, start, corners, facing)
    print(figures.line(world_name))
    assert figures.worst_tracking_m < 0.5  # the flight went where the path goes
    assert np.median(figures.corners) >= 300 and np.percentile(figures.corners, 10) >= 150
    assert np.median(figures.tracks) >= 200
    assert figures.sgbm_matched > 0.5 * sum(figures.corners)
    assert figures.sgbm_within / figures.sgbm_matched >= 0.8
    assert abs(np.median(figures.relative)) < 0.005  # no bias: baseline, focal length and depth agree
