"""RotorS' optical flow plugin (librotors_gazebo_optical_flow_plugin.so, OpenCV's corner tracker) on
RotorS' flow camera (64 x 64, 100 Hz) over RotorS' textured asphalt_plane (an OGRE material script
with tarmac.png): the integrated flow rate is v / h, the translation over the height, as a
downward camera sees the ground move; over an untextured ground there is nothing to track."""

import math

import numpy as np
import pytest

import rotors_sim as rs

ASPHALT_TOP = 0.05  # [m] asphalt_plane is a 0.1 m box centred at z = 0
GROUND = {
    "asphalt": "<include><uri>model://asphalt_plane</uri></include>",
    "flat": """<model name="flat"><static>true</static><link name="link"><visual name="v">
                 <geometry><box><size>20 20 .1</size></box></geometry>
                 <material><diffuse>0.5 0.5 0.5 1</diffuse></material></visual></link></model>""",
}
CAMERA = """<?xml version="1.0"?><sdf version="1.6"><model name="cam"><link name="link">
  <inertial><mass>0.1</mass><inertia><ixx>1e-3</ixx><iyy>1e-3</iyy><izz>1e-3</izz></inertia></inertial>
  <sensor name="flow_cam" type="camera"><update_rate>100</update_rate>
    <camera><horizontal_fov>0.1</horizontal_fov><image><width>64</width><height>64</height><format>L8</format></image>
      <clip><near>0.05</near><far>100</far></clip></camera>
    <plugin name="optical_flow" filename="librotors_gazebo_optical_flow_plugin.so">
      <robotNamespace>cam</robotNamespace></plugin>
  </sensor></link></model></sdf>"""
TOPIC = "/cam/px4flow/raw/optical_flow_rad"


def fly(ground: str, velocity_W, height: float, seconds: float = 2.0) -> np.ndarray:
    """(integration time [s], integrated_x, integrated_y [rad], quality) of every sample of a camera
    looking straight down from `height`, moving at `velocity_W` (no gravity: it keeps its speed)."""
    world = rs.World(
        sdf=f"""<?xml version="1.0"?><sdf version="1.6"><world name="flow">
      <physics type="ode"><max_step_size>0.001</max_step_size><real_time_factor>0</real_time_factor></physics>
      <gravity>0 0 0</gravity>{GROUND[ground]}</world></sdf>"""
    )
    world.spawn(CAMERA, "cam")
    # pitched down by 90 deg: the camera's x (its optical axis) along -z of the world
    world.set_model_state("cam", [0, 0, height], [0, math.sin(math.pi / 4), 0, math.cos(math.pi / 4)], velocity=list(velocity_W))
    seen, rows = 0, []
    for _ in range(int(seconds / 0.01)):
        world.step(10)
        got = world.message(TOPIC)
        if got is not None and got[1] != seen:
            seen, msg = got[1], got[0]
            rows.append((msg.integration_time_us * 1e-6, msg.integrated_x, msg.integrated_y, msg.quality))
    return np.array(rows[1:])  # the first interval starts with the first frame


@pytest.mark.parametrize("velocity_W, height", [((0.5, 0.0, 0.0), 2.0), ((1.0, 0.5, 0.0), 1.5), ((0.3, 0.0, 0.0), 0.8)])
def test_flow_rate_is_speed_over_height(velocity_W, height):
    s = fly("asphalt", velocity_W, height)
    h = height - ASPHALT_TOP
    rate_x, rate_y = np.median(s[:, 1] / s[:, 0]), np.median(s[:, 2] / s[:, 0])
    # the camera's image x is the world's -y, its image y the world's -x (camera pitched down): moving
    # along world +x is motion along image -y (MAVLink: positive integrated_x), along world +y is
    # motion along image -x (negative integrated_y)
    want_x, want_y = velocity_W[0] / h, -velocity_W[1] / h
    print(
        f"v = {velocity_W[:2]} m/s at h = {h:.2f} m: flow {rate_x:.4f}, {rate_y:.4f} rad/s, v/h {want_x:.4f}, "
        f"{want_y:.4f}; quality {s[:, 3].mean():.0f}/255 over {len(s)} samples of "
        f"{1000 * np.median(s[:, 0]):.0f} ms"
    )
    assert len(s) >= 30 and np.allclose(s[:, 0], 0.05, atol=1e-6)  # 20 Hz, RotorS' output rate
    assert rate_x == pytest.approx(want_x, rel=0.10)
    assert rate_y == pytest.approx(want_y, rel=0.10, abs=0.005)
    assert s[:, 3].mean() > 200


def test_untextured_ground_gives_no_flow():
    s = fly("flat", (0.5, 0.0, 0.0), 2.0)
    print(f"flat grey ground: quality {s[:, 3].mean():.0f}/255, flow {np.median(s[:, 1] / s[:, 0]):.4f} rad/s")
    assert s[:, 3].max() < 50


def test_optical_flow_on_a_depth_camera_is_one_line():
    world = rs.World(sdf="""<?xml version="1.0"?><sdf version="1.6"><world name="w"></world></sdf>""")
    with pytest.raises(
        rs.SimError, match=r"librotors_gazebo_optical_flow_plugin.so belongs in a <sensor " r"type=\"camera\">, not type 'depth'"
    ):
        world.spawn(CAMERA.replace('type="camera"', 'type="depth"'), "cam")


def test_a_world_with_a_camera_steps_from_a_new_thread_each_time():
    """A world may step from any thread (a stepper thread per call, as test_px4_mavlink's lockstep
    helper does): the camera renders from each, with no error and about a flow sample per call (at
    least 20). 21 calls come each from a fresh thread started after the previous one has ended (one
    more from the main thread after the first), and each fresh thread holds thread-local state of
    another size, so no thread starts at an ended one's bookkeeping address: the renderer's context
    has to be made current on each new thread itself (Mesa refuses a context left current on an
    ended thread: EGL_BAD_ACCESS)."""
    import threading

    world = rs.World(
        sdf=f"""<?xml version="1.0"?><sdf version="1.6"><world name="flow">
      <physics type="ode"><max_step_size>0.001</max_step_size><real_time_factor>0</real_time_factor></physics>
      <gravity>0 0 0</gravity>{GROUND["asphalt"]}</world></sdf>"""
    )
    world.spawn(CAMERA, "cam")
    world.set_model_state("cam", [0, 0, 2.0], [0, math.sin(math.pi / 4), 0, math.cos(math.pi / 4)], velocity=[0.5, 0.0, 0.0])
    errors, keep = [], []

    def step():
        keep.append(threading.local())  # the thread's own state, of a different size each time
        keep[-1].pad = bytearray(len(keep) * 4096)
        try:
            world.step(50)  # five frames at 100 Hz, one flow sample at 20 Hz
        except rs.SimError as e:
            errors.append(str(e))

    worker = threading.Thread(target=step)
    worker.start()
    worker.join()
    world.step(50)  # this thread, while the first thread's state is still held
    threads = [threading.Thread(target=step) for _ in range(20)]
    for t in threads:
        t.start()
        t.join()
    seen = world.message(TOPIC)
    print(f"{len(threads) + 2} threads stepped the world to t = {world.time:.2f} s; errors: {errors[:1]}")
    assert errors == [] and seen is not None and seen[1] >= 20
