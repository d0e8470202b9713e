"""ArduPilot's JSON interface (librotors_gazebo_ardupilot_interface.so) against ArduPilot's side of
a real UDP socket. ArduPilot is not on these machines: this test stands in for its SIM_JSON backend,
sending the binary servo packet ArduPilot sends (magic 18458, 16 channels of PWM; or 29569, 32)
and reading the answer the way SIM_JSON.cpp does: the text between the last two newlines, keys found
by position, `"key":` skipped. Checked: the values are the IMU plugin's reading and the ground truth
of the step in ArduPilot's frames (body FRD, NED from the origin); one answer per servo frame and no
step without a frame (lockstep); PWM 1000..2000 us drives the motors 0..maxRotVelocity; a packet that
is not a servo packet is one line and changes nothing.
"""
import json
import math
import socket
import struct
import threading
import time

import numpy as np
import pytest

import rotors_sim as rs

DT = 0.0025  # [s] ArduPilot runs its frames at the physics rate: 400 Hz


def free_udp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class ArduPilotSide:
    """SIM_JSON's side of the socket."""

    def __init__(self, port: int):
        self.port = port
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.settimeout(5.0)
        self.frame = 0

    def send_servos(self, pwm, channels=16, magic=None):
        pwm = list(pwm) + [0] * (channels - len(pwm))
        magic = magic or (18458 if channels == 16 else 29569)
        self.sock.sendto(struct.pack(f"<HHI{channels}H", magic, 400, self.frame, *pwm), ("127.0.0.1", self.port))
        self.frame += 1

    def receive_state(self) -> dict:
        data = self.sock.recv(4096)
        text = data.replace(b"\n", b"\0")
        last = text.rstrip(b"\0").rfind(b"\0")  # SIM_JSON: the text between the last two NULs
        assert last >= 0, f"the answer must begin with a newline: {data!r}"
        line = text[last + 1:].split(b"\0")[0].decode()
        assert '": ' not in line, "ArduPilot skips exactly `\"key\":`: no space after the colon"
        return json.loads(line)


def world_with_ardupilot(port: int, seed: int = 4) -> rs.World:
    world = rs.World("basic", step_size=DT)
    world.spawn_mav("iris", random_seed=seed, enable_ardupilot_interface=True, ardupilot_servo_port=port)
    return world


def frd(v):
    return np.array([v[0], -v[1], -v[2]])


def test_each_servo_frame_is_answered_with_the_imu_and_ground_truth_in_ardupilots_frames():
    port = free_udp_port()
    world = world_with_ardupilot(port)
    ap = ArduPilotSide(port)
    world.step(2)
    ap.send_servos([1000] * 4)
    states, expected = [], []
    for i in range(200):
        world_thread = threading.Thread(target=world.step, args=(1,))
        world_thread.start()
        if i > 0:
            states.append(ap.receive_state())
            ap.send_servos([1450] * 4)
        world_thread.join(5)
        imu = world.message("/iris/imu")[0]
        p, q, v, _ = world.link_state("iris")
        expected.append((world.time, imu, p, q, v))
    # the answer to the frame received at the start of step k is the state after step k, which the
    # world publishes at the start of step k + 1
    for state, (t, imu, p, q, v) in zip(states, expected):
        assert state["timestamp"] == pytest.approx(t, abs=1e-9)
        np.testing.assert_allclose(state["imu"]["gyro"], frd([imu.angular_velocity.x, imu.angular_velocity.y,
                                                              imu.angular_velocity.z]), atol=1e-8)
        np.testing.assert_allclose(state["imu"]["accel_body"], frd([imu.linear_acceleration.x,
                                                                    imu.linear_acceleration.y,
                                                                    imu.linear_acceleration.z]), atol=1e-7)
        np.testing.assert_allclose(state["position"], [p[1], p[0], -p[2]], atol=1e-8)  # NED
        np.testing.assert_allclose(state["velocity"], [v[1], v[0], -v[2]], atol=1e-8)
        qw, qx, qy, qz = state["quaternion"]
        assert qw ** 2 + qx ** 2 + qy ** 2 + qz ** 2 == pytest.approx(1.0, abs=1e-7)
    last = states[-1]
    print("last answer:", json.dumps(last, separators=(",", ":")))
    # the iris faces east, level: body->NED is yaw +90 deg
    np.testing.assert_allclose(last["quaternion"], [math.sqrt(0.5), 0, 0, math.sqrt(0.5)], atol=1e-3)
    assert last["imu"]["accel_body"][2] < -9.0  # FRD: at rest the specific force points up (-z)


def test_lockstep_one_step_per_servo_frame_and_pwm_drives_the_motors():
    port = free_udp_port()
    world = world_with_ardupilot(port)
    ap = ArduPilotSide(port)
    world.step(2)
    ap.send_servos([1500, 1600, 1700, 1800])
    done = threading.Thread(target=world.step, args=(400,))
    done.start()
    # step 3 takes frame 0; step k > 3 answers frame k - 4 and waits for frame k - 3
    for _ in range(399):
        ap.receive_state()
        if ap.frame < 399:
            ap.send_servos([1500, 1600, 1700, 1800])
    time.sleep(0.3)
    assert world.time == pytest.approx(401 * DT), "the world stepped without a servo frame"
    ap.send_servos([1500, 1600, 1700, 1800])
    done.join(10)
    assert not done.is_alive()
    assert world.time == pytest.approx(402 * DT)
    speeds = np.abs(world.rotor_speeds("iris"))
    print(f"PWM 1500/1600/1700/1800 us -> {speeds.round(1)} rad/s")
    np.testing.assert_allclose(speeds, np.array([0.5, 0.6, 0.7, 0.8]) * 838, rtol=3e-3)


def test_a_packet_that_is_not_a_servo_packet_is_one_line_and_changes_nothing(capfd):
    port = free_udp_port()
    world = world_with_ardupilot(port)
    ap = ArduPilotSide(port)
    world.step(2)
    ap.sock.sendto(b"\x00" * 13, ("127.0.0.1", port))
    ap.send_servos([1900] * 4, magic=1234)
    world.step(20)
    assert world.autopilot_answers("iris") == 0
    err = capfd.readouterr().err
    lines = [line for line in err.splitlines() if "not ArduPilot" in line or "is not 18458" in line]
    print("\n".join(lines))
    assert any("13 bytes" in line for line in lines) and any("magic 1234" in line for line in lines)
