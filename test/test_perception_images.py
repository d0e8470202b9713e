"""Images a feature-based VIO front end can use: the VI-sensor's left camera in RotorS' warehouse
(textured Collada boxes and pallets, shelves, tarmac) gives OpenCV's Shi-Tomasi detector and KLT
tracker what they need, as issue 27 asks (corners >= 300 per frame, tracks >= 200 between frames).

Through the Python module (no ROS): the same engine, plugins and renderer as under ROS."""
import cv2
import numpy as np

import rotors_sim as rs

VI_SENSOR = rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo"
STEREO = "firefly_vi_sensor_stereo_camera"
W, H = 752, 480
# views along the warehouse's aisles and across its front, 1.5 m up (x, y, yaw)
VIEWS = [(3.5, 0.8, 3.1416), (-1.5, 0.8, 0.0), (5.5, -4.5, 2.5), (-6.0, -5.0, 0.6)]


def left_image(world: rs.World) -> np.ndarray:
    return world.camera_image("firefly", STEREO, 0).reshape(H, W).copy()


def test_the_warehouse_loads_with_its_models_and_the_vi_sensor_sees_corners_and_tracks():
    world = rs.World("warehouse")
    models = world.models()
    # RotorS' world: 12 shelves, pallets with boxes (nested models built as models of their own),
    # the stand-ins, the asphalt and the ground
    assert sum(m.startswith("shelves ") for m in models) == 12
    assert any(m.endswith("::small_box_1_lvl_1") for m in models)
    assert {"grey_wall", "first_2015_trash_can", "asphalt_plane", "ground_plane"} <= set(models)
    world.spawn_mav("firefly", model=VI_SENSOR, random_seed=3, xyz=(0.0, 0.0, 20.0))
    frame_steps = int(np.ceil(1.0 / 30.0 / world.step_size)) + 1  # steps to the camera's next update (30 Hz)
    corners, tracks = [], []
    for x, y, yaw in VIEWS:
        world.set_model_state("firefly", [x, y, 1.5], [0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2)])
        world.step(frame_steps)  # a camera update at the new pose
        first = left_image(world)
        found = cv2.goodFeaturesToTrack(first, maxCorners=1000, qualityLevel=0.01, minDistance=10)
        corners.append(0 if found is None else len(found))
        # 5 cm sideways, as between two frames of a flight at 1.5 m/s
        world.set_model_state("firefly", [x - 0.05 * np.sin(yaw), y + 0.05 * np.cos(yaw), 1.5],
                              [0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2)])
        world.step(frame_steps)
        second = left_image(world)
        assert np.abs(second.astype(int) - first).mean() > 1.0  # a new frame
        forward, ok, _ = cv2.calcOpticalFlowPyrLK(first, second, found, None)
        back, ok_back, _ = cv2.calcOpticalFlowPyrLK(second, first, forward, None)
        fb_error = np.linalg.norm((back - found).reshape(-1, 2), axis=1)
        tracks.append(int(np.sum((ok.ravel() == 1) & (ok_back.ravel() == 1) & (fb_error < 1.0))))
    print(f"warehouse, VI-sensor left camera, {len(VIEWS)} views: Shi-Tomasi corners {corners} "
          f"(median {np.median(corners):.0f}), KLT tracks kept (forward-backward < 1 px) {tracks} "
          f"(median {np.median(tracks):.0f})")
    assert np.median(corners) >= 300 and min(corners) >= 150
    assert np.median(tracks) >= 200
