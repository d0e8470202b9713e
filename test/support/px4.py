"""PX4's side of the MAVLink simulator link as the tests play it: a world with the iris and PX4's
Gazebo plugin's link, a TCP client that answers HIL_SENSOR with HIL_ACTUATOR_CONTROLS, and PX4's frames."""

import math
import socket
import threading

import numpy as np
from pymavlink import mavutil
from pymavlink.dialects.v20 import common as mavlink2

import rotors_sim as rs
from support import retry_until


def quat_mul(a, b):
    """Hamilton product of (w, x, y, z) quaternions."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ]
    )


DT = 0.004  # [s] PX4's usual 250 Hz


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class SteppingWorld:
    """The world stepping on a thread of its own (step() releases the GIL) while the test speaks
    for the autopilot."""

    def __init__(self, world: rs.World):
        self.world = world
        self.thread: threading.Thread | None = None

    def run(self, steps: int) -> None:
        self.thread = threading.Thread(target=self.world.step, args=(steps,), daemon=True)
        self.thread.start()

    def join(self, timeout: float = 30.0) -> None:
        self.thread.join(timeout)
        assert not self.thread.is_alive(), "the world is still stepping"


# PX4's Gazebo plugin waits 10 ms for an answer (the default): these protocol tests wait as long as
# the stand-in takes, so that each HIL_SENSOR can be compared with the readings of its own step
STRICT_LOCKSTEP_S = 30.0


def make_world(port: int, urdf: str | None = None, seed: int = 11, **xacro) -> rs.World:
    world = rs.World("basic", step_size=DT)
    if urdf is None:
        xacro.setdefault("mavlink_answer_timeout", STRICT_LOCKSTEP_S)
        world.spawn_mav("firefly", random_seed=seed, enable_mavlink_interface=True, mavlink_tcp_port=port, pressure_variance=0.0, **xacro)
    else:
        world.spawn(urdf, "firefly", xyz=(0, 0, 0.1))
    return world


def start_lockstep(world: rs.World, port: int, steps: int):
    """Connects as PX4 does and answers the first HIL_SENSOR (lockstep starts with that answer; until
    then the world does not wait), then lets the world take `steps` lockstep steps on its thread."""
    stepper = SteppingWorld(world)
    stepper.run(1)  # the first step: no IMU reading yet
    stepper.join()
    link = connect(port)  # the kernel takes the connection; the next step accepts it and sends HIL_SENSOR
    stepper.run(1)
    stepper.join()
    next_sensor(link)
    answer(link, [0.0] * 6, armed=True)
    stepper.run(steps)
    return stepper, link


def connect(port: int, timeout_s: float = 10.0):
    """PX4's way in: a TCP client that retries until the simulator listens."""
    link = retry_until(
        lambda: mavutil.mavlink_connection(f"tcp:127.0.0.1:{port}", source_system=1, source_component=1, autoreconnect=False),
        timeout_s,
        f"the MAVLink interface listening on TCP {port}",
    )
    link.mav.heartbeat_send(mavlink2.MAV_TYPE_QUADROTOR, mavlink2.MAV_AUTOPILOT_PX4, 0, 0, 0)
    return link


def answer(link, controls, armed=True, t_us=0):
    mode = mavlink2.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED | (mavlink2.MAV_MODE_FLAG_SAFETY_ARMED if armed else 0)
    padded = list(controls) + [0.0] * (16 - len(controls))
    link.mav.hil_actuator_controls_send(t_us, padded, mode, 1)


def next_sensor(link, timeout=5.0):
    """The next HIL_SENSOR, with every other message that came before it."""
    others = []
    while True:
        m = link.recv_match(blocking=True, timeout=timeout)
        assert m is not None, "no message from the interface"
        if m.get_type() == "BAD_DATA":
            raise AssertionError(f"a frame pymavlink could not decode: {m}")
        if m.get_type() == "HIL_SENSOR":
            return m, others
        others.append(m)


def frd(v):
    return np.array([v[0], -v[1], -v[2]])


def integrate_gyro(q, w, dt):
    """q (w, x, y, z) turned by the body rate w [rad/s] over dt: q (cos a/2, sin a/2 w/|w|), a = |w| dt."""
    angle = np.linalg.norm(w) * dt
    if angle == 0:
        return q
    q = quat_mul(q, [math.cos(angle / 2), *(math.sin(angle / 2) * np.asarray(w) / np.linalg.norm(w))])
    return q / np.linalg.norm(q)


def rotate(q, v):
    return quat_mul(quat_mul(q, [0.0, *v]), [q[0], -q[1], -q[2], -q[3]])[1:]
