"""The images of the Python module equal the ROS images of the same step: the VI-sensor's left
camera of the hovering example (vehicle on the ground before its waypoint is due), received on
ROS from the simulator, and rendered by rotors_sim (no ROS) after as many steps."""

import hashlib
from pathlib import Path

import numpy as np

import clients.python_ros_images
import rotors_sim as rs
from support import RosGraph, launch, stop_launch, wait_sim_time


def test_python_images_equal_the_ros_images_of_the_same_step(ros: RosGraph, tmp_path: Path):
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example_with_vi_sensor.launch", "gui:=false", "real_time_factor:=1")
    raw = tmp_path / "left.raw"
    try:
        wait_sim_time(ros, 0.5)
        got = ros.run_client(clients.python_ros_images.vi_left_image, raw_path=str(raw))
    finally:
        stop_launch(proc)
    ros_image = np.frombuffer(raw.read_bytes(), np.uint8).reshape(got["height"], got["width"], -1)

    world = rs.World("basic")
    world.spawn_mav(
        "firefly", model=rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo", enable_vi_depth=False
    )
    world.step(int(round(got["stamp"] / world.step_size)))
    assert abs(world.time - got["stamp"]) < 1e-9
    ours = world.camera_image("firefly", "firefly_vi_sensor_stereo_camera", 0)
    print(
        f"ROS left image at t = {got['stamp']:.2f} s: {got['width']}x{got['height']} {got['encoding']}, "
        f"sha256 {hashlib.sha256(ros_image.tobytes()).hexdigest()[:16]}; Python: "
        f"{hashlib.sha256(ours.tobytes()).hexdigest()[:16]}"
    )
    assert ours.shape == ros_image.shape
    assert np.array_equal(ours, ros_image)
    assert ros_image.std() > 5  # a real picture, not a blank frame
