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
from support.net import free_udp_port

DT = 0.0025  # [s] ArduPilot runs its frames at the physics rate: 400 Hz


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
        line = text[last + 1 :].split(b"\0")[0].decode()
        assert '": ' not in line, 'ArduPilot skips exactly `"key":`: no space after the colon'
        state = json.loads(line)
        self.read = sim_json_read(line)
        # what SIM_JSON reads is what the line says
        assert self.read["timestamp"] == pytest.approx(state["timestamp"], abs=1e-6)
        np.testing.assert_allclose(self.read["imu.gyro"], state["imu"]["gyro"], atol=1e-6)
        np.testing.assert_allclose(self.read["velocity"], state["velocity"], atol=1e-6)
        return state


# SIM_JSON.cpp's key table (section, key, kind, required): it finds the section with strstr and skips it
# and one more character, finds the key with strstr from there and skips it and 2 more (`":`), then
# reads a number with atof, a vector with sscanf("[%f, %f, %f]") (a space in a scanf format matches
# any whitespace, none included), a boolean with strncasecmp("true")
SIM_JSON_KEYS = [
    ("", "timestamp", "double", True),
    ("imu", "gyro", "vector3", True),
    ("imu", "accel_body", "vector3", True),
    ("", "position", "vector3", False),
    ("", "quaternion", "quaternion", False),
    ("", "velocity", "vector3", True),
    ("", "rng_1", "float", False),
    ("", "airspeed", "float", False),
    ("", "no_time_sync", "boolean", False),
]
C_FLOAT = r"\s*[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|inf|nan)"


def sim_json_read(line: str) -> dict:
    import re

    read = {}
    for section, key, kind, required in SIM_JSON_KEYS:
        p = 0
        if section:
            i = line.find(f'"{section}"')
            assert i >= 0 or not required, f"SIM_JSON finds no section {section}"
            p = i + len(section) + 3  # `"section"` and one more
        i = line.find(f'"{key}"', p)
        if i < 0:
            assert not required, f"SIM_JSON finds no required key {key}: the line is refused"
            continue
        rest = line[i + len(key) + 3 :]  # `"key":`
        name = f"{section}.{key}" if section else key
        if kind in ("double", "float"):
            m = re.match(C_FLOAT, rest)
            read[name] = float(m.group()) if m else 0.0  # atof
        elif kind == "boolean":
            read[name] = rest[:4].lower() == "true"
        else:
            n = 4 if kind == "quaternion" else 3
            m = re.match(r"\[" + r"\s*,".join([C_FLOAT] * n) + r"\s*\]", rest)
            assert m, f"sscanf reads no {n} numbers for {name}: {rest[:60]!r}"
            read[name] = [float(x) for x in re.findall(C_FLOAT, m.group())]
    return read


def world_with_ardupilot(port: int, seed: int = 4, **xacro) -> rs.World:
    world = rs.World("basic", step_size=DT)
    world.spawn_mav("iris", random_seed=seed, enable_ardupilot_interface=True, ardupilot_servo_port=port, **xacro)
    return world


def frd(v):
    return np.array([v[0], -v[1], -v[2]])


def test_servo_frames_answered_with_imu_truth_ardupilot_frames():
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
    for state, (t, imu, p, _q, v) in zip(states, expected):
        assert state["timestamp"] == pytest.approx(t, abs=1e-9)
        np.testing.assert_allclose(
            state["imu"]["gyro"], frd([imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z]), atol=1e-8
        )
        np.testing.assert_allclose(
            state["imu"]["accel_body"], frd([imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z]), atol=1e-7
        )
        np.testing.assert_allclose(state["position"], [p[1], p[0], -p[2]], atol=1e-8)  # NED
        np.testing.assert_allclose(state["velocity"], [v[1], v[0], -v[2]], atol=1e-8)
        qw, qx, qy, qz = state["quaternion"]
        assert qw**2 + qx**2 + qy**2 + qz**2 == pytest.approx(1.0, abs=1e-7)
    last = states[-1]
    print("last answer:", json.dumps(last, separators=(",", ":")))
    # the iris faces east, level: body->NED is yaw +90 deg
    np.testing.assert_allclose(last["quaternion"], [math.sqrt(0.5), 0, 0, math.sqrt(0.5)], atol=1e-3)
    assert last["imu"]["accel_body"][2] < -9.0  # FRD: at rest the specific force points up (-z)


def test_lockstep_one_step_per_servo_frame_pwm_drives_motors():
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


def test_non_servo_packet_is_one_line_and_changes_nothing(capfd):
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


def start_frames(world: rs.World, ap: ArduPilotSide, steps: int, pwm=(1000, 1000, 1000, 1000)) -> "SteppingWorld":
    """The first servo frame, sent before the world waits for frames, and the world stepping `steps`
    lockstep steps on its own thread."""
    world.step(2)
    ap.send_servos(pwm)
    return SteppingWorld(world, steps)


def fly(world: rs.World, ap: ArduPilotSide, steps: int, pwm=(1000, 1000, 1000, 1000)) -> dict:
    """`steps` lockstep steps, one servo frame each; the last answer read."""
    stepper = start_frames(world, ap, steps, pwm)
    for _ in range(steps - 1):
        state = ap.receive_state()
        ap.send_servos(pwm)
    stepper.join()
    return state


class SteppingWorld:
    """The world stepping on its own thread (lockstep: it waits for ArduPilot's frames)."""

    def __init__(self, world: rs.World, steps: int):
        self.thread = threading.Thread(target=world.step, args=(steps,), daemon=True)
        self.thread.start()

    def join(self):
        self.thread.join(10)
        assert not self.thread.is_alive(), "the world is still waiting"


def test_a_repeated_frame_count_is_answered_again_without_a_step():
    """SIM_JSON resends a frame with the same frame_count when it got no answer within about 1 s;
    ArduPilot's Gazebo plugin answers it again with the last state and does not step."""
    port = free_udp_port()
    world = world_with_ardupilot(port)
    ap = ArduPilotSide(port)
    stepper = start_frames(world, ap, 12, [1500] * 4)
    for _ in range(10):
        first = ap.receive_state()
        ap.send_servos([1500] * 4)
    first = ap.receive_state()
    held = world.time
    ap.frame -= 1  # the same frame again
    ap.send_servos([1500] * 4)
    again = ap.receive_state()
    time.sleep(0.2)
    print(
        f"frame {ap.frame - 1} sent twice: answered with t = {first['timestamp']:.4f} s both times; "
        f"the world stayed at {world.time:.4f} s"
    )
    assert again == first and world.time == held
    ap.send_servos([1500] * 4)  # the next frame steps again
    stepper.join()
    assert world.time == pytest.approx(held + DT)


def test_a_frame_count_that_goes_back_is_an_ardupilot_restart(capfd):
    port = free_udp_port()
    world = world_with_ardupilot(port)
    ap = ArduPilotSide(port)
    stepper = start_frames(world, ap, 30, [1500] * 4)
    for i in range(29):
        ap.receive_state()
        if i == 19:
            ap.frame = 0  # a restarted ArduPilot counts from 0 again
        ap.send_servos([1500] * 4)
    stepper.join()
    captured = capfd.readouterr()
    line = next(line for line in (captured.out + captured.err).splitlines() if "went back" in line)
    print(line)
    assert "from 19 to 0" in line and "restarted" in line
    assert world.autopilot_answers("iris") == 30


def test_airspeed_is_the_airspeed_sensors_reading_in_wind():
    port = free_udp_port()
    world = world_with_ardupilot(port, enable_airspeed=True, enable_wind=True, wind_speed_mean=3.0)
    ap = ArduPilotSide(port)
    state = fly(world, ap, 50)
    sensor = world.message("/iris/air_speed")[0].vector
    reading = math.sqrt(sensor.x**2 + sensor.y**2 + sensor.z**2)
    ground_speed = float(np.linalg.norm(state["velocity"]))
    print(f"JSON airspeed {state['airspeed']:.3f} m/s; the airspeed sensor {reading:.3f} m/s; ground speed " f"{ground_speed:.4f} m/s")
    assert ap.read["airspeed"] == pytest.approx(reading, abs=0.02) and reading > 2.5 and ground_speed < 0.1


def sitl_command(tmp_path, *args: str) -> str:
    """scripts/ardupilot_sitl --print-command's output, as mav_ardupilot_sitl.launch runs it."""
    import subprocess

    script = rs.paths.package_path("rotors_gazebo") / "scripts" / "ardupilot_sitl"
    return subprocess.run(
        [str(script), "--ardupilot_dir", str(tmp_path / "ardupilot"), *args, "--print-command"],
        check=True,
        capture_output=True,
        text=True,
        env={**__import__("os").environ, "ROS_HOME": str(tmp_path)},
    ).stdout


def parm_values(path: str) -> dict:
    """A parameter file as AP_Param reads --defaults: `NAME VALUE` or `NAME,VALUE`, '#' a comment."""
    params = {}
    for line in open(path):
        line = line.split("#", 1)[0].strip()
        if line:
            name, value = line.replace(",", " ").split()[:2]
            params[name] = float(value)
    return params


def test_a_rangefinder_without_return_reads_out_of_range_high(tmp_path):
    """ArduPilot's AP_RangeFinder_SITL: a reading above RNGFNDx_MAX is OutOfRangeHigh, NaN is NoData
    and a negative one 0 m; ArduPilot's Gazebo plugin sends twice the maximum when the beam returns
    nothing. ArduPilot reads rng_1 only with RNGFND1_TYPE 100 (AP_RangeFinder.cpp: Type::SIM creates
    AP_RangeFinder_SITL); gazebo-iris.parm sets type 1, SITL's own analog sonar: with
    enable_rangefinder:=true the launch loads our file last, whose maximum is the sensor's."""
    port = free_udp_port()
    world = world_with_ardupilot(port, enable_lidar="rangefinder")
    world.set_model_state("iris", [0, 0, 200.0])
    ap = ArduPilotSide(port)
    fly(world, ap, 40)
    r = world.message("/iris/lidar")[0]
    print(f"rangefinder at 200 m: {r.range} (max {r.max_range} m) -> rng_1 = {ap.read['rng_1']} m")
    assert ap.read["rng_1"] == pytest.approx(2 * r.max_range, rel=1e-6) and ap.read["rng_1"] > r.max_range
    cmd = sitl_command(tmp_path, "--rangefinder").splitlines()[0].split()
    defaults = cmd[cmd.index("--defaults") + 1].split(",")
    assert defaults[-1].endswith("ardupilot_rangefinder.parm") and defaults[-2].endswith("ardupilot_iris.parm")
    p = parm_values(defaults[-1])
    assert p["RNGFND1_TYPE"] == 100 and p["RNGFND1_ORIENT"] == 25  # ROTATION_PITCH_270: down
    assert (p["RNGFND1_MIN"], p["RNGFND1_MAX"]) == pytest.approx((r.min_range, r.max_range))
    assert (p["RNGFND1_MIN_CM"], p["RNGFND1_MAX_CM"]) == pytest.approx((100 * r.min_range, 100 * r.max_range))
    assert ap.read["rng_1"] > p["RNGFND1_MAX"]  # OutOfRangeHigh in ArduPilot's own check
    plain = sitl_command(tmp_path).splitlines()[0].split()
    assert not plain[plain.index("--defaults") + 1].endswith("ardupilot_rangefinder.parm")


def test_launch_command_line_loads_x_quad_home_at_world_origin(tmp_path):
    """scripts/ardupilot_sitl as mav_ardupilot_sitl.launch runs it: the SITL binary with ArduPilot's
    gazebo-iris defaults and ours last (AP_Param loads --defaults files in order, a later file's value
    wins; a line is `NAME VALUE` or `NAME,VALUE`, '#' starts a comment). AP_Motors_Class.h: FRAME_CLASS
    1 = quad, FRAME_TYPE 1 = X."""
    world_file = rs.paths.package_path("rotors_gazebo") / "worlds" / "basic.world"
    out = sitl_command(tmp_path, "--instance", "2", "--world", str(world_file))
    print(out)
    cmd = out.splitlines()[0].split()
    assert cmd[0].endswith("build/sitl/bin/arducopter") and cmd[cmd.index("--model") + 1] == "JSON"
    assert cmd[cmd.index("-I") + 1] == "2" and f"cwd: {tmp_path}/ardupilot/2" in out
    defaults = cmd[cmd.index("--defaults") + 1].split(",")
    assert [d.rsplit("/", 1)[1] for d in defaults[:2]] == ["copter.parm", "gazebo-iris.parm"]
    params = parm_values(defaults[-1])
    assert params["FRAME_CLASS"] == 1 and params["FRAME_TYPE"] == 1
    home = [float(x) for x in cmd[cmd.index("--home") + 1].split(",")]
    assert home[:3] == pytest.approx([47.3667, 8.55, 500.0])  # basic.world's spherical_coordinates


def techpod_speed_after(pwm: list[int]) -> float:
    """The techpod launched at 15 m/s, 100 m up, flown 1 s by ArduPlane's servo outputs."""
    port = free_udp_port()
    world = rs.World("basic", step_size=DT)
    world.spawn(
        str(rs.paths.package_path("rotors_description") / "urdf" / "techpod_base.xacro"),
        "techpod",
        xyz=(0, 0, 100),
        mav_name="techpod",
        namespace="techpod",
        enable_ardupilot_interface="true",
        ardupilot_servo_port=str(port),
        random_seed="4",
    )
    world.set_model_state("techpod", [0, 0, 100], velocity=[15.0, 0, 0])
    ap = ArduPilotSide(port)
    fly(world, ap, 400, pwm)
    p, q, v, w = world.link_state("techpod")
    return float(v[0]), float(w[0])


def test_arduplanes_default_servo_functions_drive_the_techpod():
    """ArduPlane's default servo functions (Plane::load_parameters: SERVO1 aileron, SERVO2 elevator,
    SERVO3 throttle, SERVO4 rudder) on the techpod's normalized channels: surfaces centred on 1500 us,
    the throttle 1000..2000 us, 0 us no output (the channel rests at neutral)."""
    neutral = [1500, 1500, 1000, 1500]
    full, _ = techpod_speed_after([1500, 1500, 2000, 1500])
    idle, _ = techpod_speed_after(neutral)
    unused, _ = techpod_speed_after([1500, 1500, 0, 1500])
    _, roll_rate = techpod_speed_after([1900, 1500, 1000, 1500])
    _, level_rate = techpod_speed_after(neutral)
    print(
        f"after 1 s from 15 m/s: {full:.2f} m/s at full throttle, {idle:.2f} m/s idle, {unused:.2f} m/s with "
        f"no throttle output; roll rate {roll_rate:.3f} rad/s with aileron 1900 us, {level_rate:.3f} neutral"
    )
    assert full > idle + 0.3 and unused == pytest.approx(idle, abs=1e-6)
    assert roll_rate > 10 * abs(level_rate) + 0.05  # high PWM rolls right (+x in FLU and FRD alike)
