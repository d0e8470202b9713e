"""RotorS' remaining sensor files: rgbd_base.xacro (a RealSense D435),
pmd_monstar.xacro (a time-of-flight camera), asymmetric_quadrotor_two_cameras.gazebo and the
flow_cam model publish the ROS topics, types, image sizes and rates of RotorS' files, and the
noisy-depth plugin honours depthNoiseMinDist / depthNoiseMaxDist (one roslaunch:
launch/rotors_sensor_files.launch). From Python without ROS: firefly_two_generic_pose_sensors.gazebo
publishes at its two rates (10 and 20 Hz at the basic world's 100 Hz steps); the motor model's force
type turns its command into a joint effort (the disc's spin-up against omega = tau t / I) and
publishes it on motorForcePubTopic."""

from pathlib import Path

import numpy as np
import pytest

import clients.sensor_files
import rotors_sim as rs
from rotors_sim.paths import package_path
from support import RosGraph, rate_from_stamps, stop_launch, wait_sim_time

HERE = Path(__file__).resolve().parent
URDF = package_path("rotors_description") / "urdf"

CAMERA_TOPICS = {  # topic -> (type, rate [Hz] or None, (width, height) of an image or None)
    "/firefly/rgbd/camera_depth/depth/image_raw": ("sensor_msgs/Image", 30.0, (848, 480)),
    "/firefly/rgbd/camera_depth/depth/camera_info": ("sensor_msgs/CameraInfo", 30.0, None),
    "/firefly/rgbd/camera_depth/depth/points": ("sensor_msgs/PointCloud2", 30.0, None),
    "/firefly/rgbd/camera_depth/camera/image_raw": ("sensor_msgs/Image", 30.0, (848, 480)),
    "/firefly/rgbd/camera_depth/camera/camera_info": ("sensor_msgs/CameraInfo", 30.0, None),
    "/firefly/rgbd/camera_rgb/image_raw": ("sensor_msgs/Image", 30.0, (848, 480)),
    "/firefly/rgbd/camera_rgb/camera_info": ("sensor_msgs/CameraInfo", 30.0, None),
    "/tof/rgbd/camera_depth/depth/image_raw": ("sensor_msgs/Image", 5.0, (352, 287)),
    "/tof/rgbd/camera_depth/depth/points": ("sensor_msgs/PointCloud2", 5.0, None),
    "/tof/rgbd/camera_depth/intensity/image_raw": ("sensor_msgs/Image", 5.0, (352, 287)),
    "/tof/rgbd/camera_depth/intensity/camera_info": ("sensor_msgs/CameraInfo", 5.0, None),
    "/asymmetric_quadrotor/camera_left/image_raw": ("sensor_msgs/Image", 30.0, (752, 480)),
    "/asymmetric_quadrotor/camera_right/image_raw": ("sensor_msgs/Image", 30.0, (752, 480)),
    "/px4flow/raw/optical_flow_rad": ("mavros_msgs/OpticalFlowRad", None, None),
    "/probe/camera/depth/image_raw": ("sensor_msgs/Image", 10.0, (160, 120)),
}


def test_rotors_sensor_files_publish_topics_types_sizes_rates(ros: RosGraph):
    """Rates in sim time, from the mean interval between the header stamps of consecutive messages
    (leaving out an interval that holds a message the client dropped)."""
    launch = ros.start(["roslaunch", "-p", str(ros.port), str(HERE / "launch/rotors_sensor_files.launch")], "launch")
    try:
        wait_sim_time(ros, 0.5)
        types = {t: k for t, (k, _, _) in CAMERA_TOPICS.items()}
        got = ros.run_client(clients.sensor_files.collect, timeout=240, topics=types)
    finally:
        stop_launch(launch)
    for topic, (kind, rate_hz, size) in CAMERA_TOPICS.items():
        stamps = np.array(got["stamps"][topic])
        assert got["types"].get(topic) == kind and len(stamps) >= 12, (topic, got["types"].get(topic), len(stamps))
        rate = rate_from_stamps(stamps)  # a message the client dropped does not count
        size_text = " {} x {} {}".format(*got["sizes"][topic]) if size else ""
        print(f"{topic}: {kind} at {rate:.1f} Hz{size_text}")
        if rate_hz is not None:
            assert abs(rate - rate_hz) < 0.05 * rate_hz, (topic, rate)
        if size is not None:
            assert tuple(got["sizes"][topic][:2]) == size, (topic, got["sizes"][topic])
    # valid depths: [depthNoiseMinDist, depthNoiseMaxDist] within the point-cloud cutoff (as
    # gazebo_ros, the cutoff applies to the depth image too): the probe's [1, 2] m inside 0.1-10 m;
    # the pmd's [0.1, 6] m inside the default 0.4-5 m
    for topic, (low, high) in (("/probe/camera/depth/image_raw", (1.0, 2.0)), ("/tof/rgbd/camera_depth/depth/image_raw", (0.4, 5.0))):
        d = got["depth"][topic]
        print(f"{topic}: {d['valid']} valid pixels in {d['min']:.3f}..{d['max']:.3f} m, {d['nan']} NaN")
        assert d["valid"] > 1000 and d["nan"] > 1000 and low <= d["min"] < low + 0.1 and high - 0.1 < d["max"] <= high


def run(world: rs.World, seconds: float) -> dict:
    """Steps `seconds` of sim time; topic -> (type, messages per second)."""
    before = {t: n for t, _, n in world.topics()}
    world.step(int(round(seconds / world.step_size)))
    return {t: (kind, (n - before.get(t, 0)) / seconds) for t, kind, n in world.topics()}


def test_two_generic_pose_sensors_publish_at_their_divisors():
    world = rs.World("basic")
    world.spawn_mav("firefly", model=URDF / "firefly_two_generic_pose_sensors.gazebo", random_seed=5)
    run(world, 1.0)  # past the measurement delays (10 and 8 steps)
    seen = run(world, 2.0)
    # the basic world steps at 100 Hz: divisors 10 and 5 give 10 Hz and 20 Hz
    for sensor, rate_hz in (("odometry_sensor1", 10.0), ("odometry_sensor2", 20.0)):
        for leaf, kind in (
            ("odometry", "nav_msgs/Odometry"),
            ("pose", "geometry_msgs/Pose"),
            ("pose_with_covariance", "geometry_msgs/PoseWithCovarianceStamped"),
            ("position", "geometry_msgs/PointStamped"),
            ("transform", "geometry_msgs/TransformStamped"),
        ):
            topic = f"/firefly/{sensor}/{leaf}"
            assert seen[topic][0] == kind, (topic, seen.get(topic))
        print(f"{sensor}: {seen[f'/firefly/{sensor}/odometry'][1]:.1f} Hz")
        assert abs(seen[f"/firefly/{sensor}/odometry"][1] - rate_hz) <= 0.5


def test_the_force_motor_type_spins_a_disc_up_as_tau_over_i():
    world = rs.World("basic")
    world.spawn(HERE / "descriptions/effort_joint.urdf", "effort", xyz=(0.0, 0.0, 0.1))
    world.step(50)  # settle on the ground
    world.set_motor_speeds("effort", [0.8])  # above maxForce 0.5: clipped
    world.step(int(round(1.0 / world.step_size)))
    omega = world.rotor_speeds("effort")[0]
    effort, _ = world.message("/effort/motor_force/0")
    print(f"effort {effort.data:.3f} N m for 1 s on I = 0.01 kg m^2: omega {omega:.3f} rad/s (tau t / I = 50)")
    assert effort.data == pytest.approx(0.5)
    assert omega == pytest.approx(0.5 * 1.0 / 0.01, rel=0.02)
