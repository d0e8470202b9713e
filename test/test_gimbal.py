"""The camera gimbal (gimbal_camera_macro, librotors_gazebo_gimbal_controller_plugin.so) holds its
camera at the commanded attitude in the world while the MAV rolls, pitches and yaws: in process
(Python, no ROS) through a waypoint step and a yaw turn, and over ROS on gimbal_pitch_cmd."""

import math

import numpy as np

import clients.gimbal
import rotors_sim as rs
from support import RosGraph, launch, stop_launch, wait_sim_time


def rotation(q) -> np.ndarray:
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def euler_zxy(R: np.ndarray) -> np.ndarray:
    """(yaw, roll, pitch) of R = R_z(yaw) R_x(roll) R_y(pitch), the gimbal's joint order."""
    return np.array([math.atan2(-R[0, 1], R[1, 1]), math.asin(R[2, 1]), math.atan2(-R[2, 0], R[2, 2])])


def tilt_deg(R: np.ndarray) -> float:
    """Angle between the body's z axis and the world's."""
    return math.degrees(math.acos(max(-1.0, min(1.0, R[2, 2]))))


def test_gimbal_holds_the_camera_while_the_mav_tilts_and_turns():
    pitch_cmd = 0.5  # [rad] looking down 28.6 deg (gimbal_pitch)
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=1, enable_gimbal=True, gimbal_pitch=pitch_cmd)
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0.0, 0.0, 1.5], due=0.5)
    world.attach_controller("firefly", lee)
    body_tilt, body_yaw, camera = [], [], []
    for k in range(1100):  # 11 s, sampled every 10 ms
        if k == 500:
            lee.set_point([1.5, 0.0, 1.5], due=5.0)
        if k == 800:
            lee.set_point([1.5, 1.5, 1.5], yaw=1.0, due=8.0)
        world.step(10)
        if world.time < 1.0:  # the camera swings to its initial pitch
            continue
        R_WB = rotation(world.link_state("firefly", "firefly/base_link")[1])
        body_tilt.append(tilt_deg(R_WB))
        body_yaw.append(math.atan2(R_WB[1, 0], R_WB[0, 0]))
        camera.append(euler_zxy(rotation(world.link_state("firefly", "firefly/gimbal_camera_link")[1])))
    camera = np.degrees(np.array(camera))
    err = np.abs(camera - [0.0, 0.0, math.degrees(pitch_cmd)]).max(axis=0)
    image = world.camera_image("firefly", "firefly_camera_gimbal")
    print(
        f"gimbal: body tilted up to {max(body_tilt):.1f} deg and yawed to {math.degrees(max(body_yaw)):.1f} deg; "
        f"camera off its command by at most yaw {err[0]:.3f}, roll {err[1]:.3f}, pitch {err[2]:.3f} deg; "
        f"image {image.shape}"
    )
    assert max(body_tilt) > 15.0 and max(body_yaw) > 0.9
    assert err.max() < 0.5
    assert image.shape == (480, 640, 3) and image.std() > 1.0  # ground and sky in view


def test_gimbal_pitch_command_over_ros(ros: RosGraph):
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "lockstep:=true", "real_time_factor:=10", "enable_gimbal:=true")
    try:
        wait_sim_time(ros, 7.0)
        got = ros.run_client(clients.gimbal.pitch_and_roll_beyond_the_joints, timeout=120)
    finally:
        stop_launch(proc)

    def about(axis, angle):
        c, s = math.cos(angle), math.sin(angle)
        return {
            "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
            "x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
        }[axis]

    # the camera's attitude from the body's and the joint angles (the gimbal's joint frames are not turned)
    R_WB = rotation(got["q_WB"])
    R_WC = R_WB @ about("z", got["yaw"]) @ about("x", got["roll"]) @ about("y", got["pitch"])
    ypr = euler_zxy(R_WC)
    print(
        f"gimbal over ROS: camera yaw {ypr[0]:.4f}, roll {ypr[1]:.4f} (commanded 3.0, clamped to the joint's pi/4), "
        f"pitch {ypr[2]:.4f} rad (commanded 3.0, clamped to the joint's pi/2: straight down); body tilt "
        f"{tilt_deg(R_WB):.2f} deg"
    )
    assert np.abs(ypr - [0.0, math.pi / 4, math.pi / 2]).max() < 0.01
