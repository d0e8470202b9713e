"""RotorS' MAVLink interface (librotors_gazebo_mavlink_interface.so) against PX4's side of a real
TCP socket. PX4 is not on these machines: pymavlink (the MAVLink project's Python implementation)
stands in for it here, connecting as PX4's simulator_mavlink module does (TCP client to 4560 +
instance) and answering each HIL_SENSOR with HIL_ACTUATOR_CONTROLS, lockstep flag set. What is
checked: every message decodes with pymavlink and carries the plugins' own readings of the same step
in PX4's units and frames; lockstep (no step without an answer, no answer lost); control_channels
and the disarmed values; and a closed loop: an attitude and altitude controller on the autopilot's
side, estimating from HIL_SENSOR alone, flies the firefly to 2 m above its take-off point, level
and on its heading, and holds it (its horizontal position is not observable from HIL_SENSOR).
"""

import math
import re
import subprocess
import threading
import time

import numpy as np
import pytest

import rotors_sim as rs
from support.px4 import (
    DT,
    STRICT_LOCKSTEP_S,
    SteppingWorld,
    answer,
    connect,
    frd,
    free_port,
    integrate_gyro,
    make_world,
    next_sensor,
    rotate,
    start_lockstep,
)

MAX_ROT = 838.0  # firefly maxRotVelocity [rad/s]


@pytest.fixture(scope="module")
def exchange():
    """40 lockstep steps at rest: each HIL_SENSOR with the plugins' readings at that moment (the world
    is blocked waiting for the answer) and the messages around it."""
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 400)
    records = []
    for _i in range(400):
        sensor, others = next_sensor(link)
        imu = world.message("/firefly/imu")[0]
        mag = world.message("/firefly/magnetic_field")[0]
        baro = world.message("/firefly/air_pressure")[0]
        gps = world.message("/firefly/gps")
        speed = world.message("/firefly/ground_speed")
        truth = world.link_state("firefly")
        records.append(
            dict(
                sensor=sensor,
                others=others,
                imu=imu,
                mag=mag,
                baro=baro,
                truth=truth,
                gps=gps[0] if gps else None,
                speed=speed[0] if speed else None,
                time=world.time,
            )
        )
        answer(link, [0.0] * 6, armed=True, t_us=sensor.time_usec)
    stepper.join()
    link.close()
    return records, world


def test_hil_sensor_carries_imu_mag_baro_in_px4_units(exchange):
    records, _ = exchange
    for r in records[1:]:
        s, imu = r["sensor"], r["imu"]
        stamp_us = imu.header.stamp.secs * 1_000_000 + imu.header.stamp.nsecs // 1000
        assert s.time_usec == stamp_us == round(r["time"] * 1e6)
        a = frd([imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z])
        g = frd([imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z])
        np.testing.assert_allclose([s.xacc, s.yacc, s.zacc], a, rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose([s.xgyro, s.ygyro, s.zgyro], g, rtol=1e-6, atol=1e-7)
        m = frd([r["mag"].magnetic_field.x, r["mag"].magnetic_field.y, r["mag"].magnetic_field.z]) * 1e4  # T -> gauss
        np.testing.assert_allclose([s.xmag, s.ymag, s.zmag], m, rtol=1e-6, atol=1e-9)
        assert s.abs_pressure == pytest.approx(r["baro"].fluid_pressure / 100.0, rel=1e-6)  # Pa -> hPa
        assert s.fields_updated & 0b1101111111111 == 0b1101111111111  # accel, gyro, mag, baro bits
        assert s.fields_updated & 0b10000000000 == 0  # no differential pressure: no airspeed sensor
        assert s.id == 0
    s = records[-1]["sensor"]
    print(
        f"at rest: acc {s.xacc:.3f} {s.ygyro:.3f} {s.zacc:.3f} m/s^2 FRD, mag {s.xmag:.4f} {s.ymag:.4f} "
        f"{s.zmag:.4f} G, {s.abs_pressure:.2f} hPa, pressure altitude {s.pressure_alt:.1f} m, {s.temperature:.1f} C"
    )
    assert s.zacc == pytest.approx(-9.81, abs=0.1) and abs(s.xacc) < 0.1  # FRD: at rest the specific force is up = -z
    # the firefly faces east (yaw 0 in ENU): the field's north component lies along -y of FRD (its left)
    assert s.ymag < -0.1 and s.zmag > 0.3
    # the barometer plugin's reference altitude is 500 m: PX4's pressure altitude from the ISA
    assert s.pressure_alt == pytest.approx(500.0, abs=2.0) and s.temperature == pytest.approx(15.0 - 6.5 * 0.5, abs=0.1)


def test_hil_gps_carries_gps_fix_in_1e7_deg_mm_cm_per_s_ned(exchange):
    records, _ = exchange
    gps = [(m, r) for r in records for m in r["others"] if m.get_type() == "HIL_GPS"]
    print(f"{len(gps)} HIL_GPS in {records[-1]['time']:.2f} s")
    assert len(gps) == pytest.approx(records[-1]["time"] * 5, abs=1.5)  # the GPS plugin's 5 Hz
    for m, r in gps:
        # the fix the plugin published before this step
        fix, speed = r["gps"], r["speed"]
        assert m.lat == round(fix.latitude * 1e7) and m.lon == round(fix.longitude * 1e7)
        # UTC, as PX4's Gazebo plugin: the wall clock at sim time 0 plus the fix's sim time
        assert abs(m.time_usec * 1e-6 - (time.time() - records[-1]["time"] + fix.header.stamp.to_sec())) < 120
        assert m.alt == round(fix.altitude * 1000)
        assert m.eph == round(math.sqrt(fix.position_covariance[0]) * 100)
        assert m.epv == round(math.sqrt(fix.position_covariance[8]) * 100)
        v = speed.twist.linear
        assert (m.vn, m.ve, m.vd) == (round(v.y * 100), round(v.x * 100), round(-v.z * 100))
        assert m.fix_type == 3 and m.satellites_visible == 10


def test_hil_state_quaternion_is_the_ground_truth_in_ned_and_frd(exchange):
    records, _ = exchange
    states = [(m, r) for r in records for m in r["others"] if m.get_type() == "HIL_STATE_QUATERNION"]
    assert len(states) >= len(records) - 2  # one per HIL_SENSOR until PX4 asks otherwise
    m, r = states[-1]
    q = np.array(m.attitude_quaternion)
    # facing east, level: in NED that is yaw +90 deg about down: q = (cos 45, 0, 0, sin 45)
    np.testing.assert_allclose(q, [math.sqrt(0.5), 0, 0, math.sqrt(0.5)], atol=2e-3)
    # PX4 reads xacc / 1000 as the NED acceleration [m/s^2] (its Gazebo plugin sends a_NED * 1000): at rest 0
    assert abs(m.xacc) <= 20 and abs(m.yacc) <= 20 and abs(m.zacc) <= 20
    assert abs(m.vx) <= 1 and abs(m.vy) <= 1 and abs(m.vz) <= 1


def test_lockstep_waits_on_unanswered_hil_sensor_loses_no_answer():
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 60)
    sent = 1
    for _ in range(10):
        sensor, _ = next_sensor(link)
        answer(link, [0.0] * 6, armed=True)
        sent += 1
    sensor, _ = next_sensor(link)  # the world now waits for this one's answer
    held = world.time
    time.sleep(0.5)
    assert world.time == held == pytest.approx(sensor.time_usec * 1e-6), "the world stepped without an answer"
    answer(link, [0.0] * 6, armed=True)
    sent += 1
    while True:
        m = link.recv_match(type="HIL_SENSOR", blocking=True, timeout=2)
        if m is None:
            break
        answer(link, [0.0] * 6, armed=True)
        sent += 1
    stepper.join()
    print(f"{sent} answers sent, {world.autopilot_answers('firefly')} applied, t = {world.time:.3f} s")
    assert world.autopilot_answers("firefly") == sent
    assert world.time == pytest.approx(62 * DT)


def test_an_answer_releases_only_the_step_whose_hil_sensor_it_answers():
    """PX4 answers every HIL_SENSOR it takes, stamped with that HIL_SENSOR's time (its lockstep clock).
    Before lockstep begins (the first answer) the world does not wait, so two HIL_SENSOR go out before
    the first answer. Each answered 4 ms after it came (within answer_timeout), the exchange must not
    stay one answer behind: an older answer is applied but does not release the waiting step. Counted
    as PX4 would see it: times it takes a HIL_SENSOR while another one is already waiting."""
    import queue

    port = free_port()
    world = make_world(port, mavlink_answer_timeout=0.5)
    stepper = SteppingWorld(world)
    stepper.run(1)
    stepper.join()
    link = connect(port)
    stepper.run(2)  # two HIL_SENSOR before any answer: lockstep has not begun, the world does not wait
    stepper.join()
    first, second = next_sensor(link)[0], next_sensor(link)[0]
    answer(link, [0.0] * 6, armed=True, t_us=first.time_usec)  # lockstep from this answer on
    steps = 500
    arrivals: queue.Queue = queue.Queue()

    def read() -> None:  # the autopilot's receive side: each HIL_SENSOR with the moment it came
        while (m := link.recv_match(type="HIL_SENSOR", blocking=True, timeout=3.0)) is not None:
            arrivals.put((time.monotonic(), m))

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    stepper.run(steps)
    third = arrivals.get(timeout=5.0)  # the world has taken the first answer and waits for this one's
    answer(link, [0.0] * 6, armed=True, t_us=second.time_usec)  # the answer to the second comes now
    answered, ahead, pending = 2, [], [third]
    while answered < steps:
        if pending:
            came, sensor = pending.pop()
        else:
            came, sensor = arrivals.get(timeout=5.0)
        time.sleep(max(0.0, came + 0.004 - time.monotonic()))
        if arrivals.qsize() > 0:  # the world has sent the next one before this one was answered
            ahead.append(answered)
        answer(link, [0.0] * 6, armed=True, t_us=sensor.time_usec)
        answered += 1
    print(f"{answered} answers, each 4 ms after its HIL_SENSOR; taken while the next was already there: {len(ahead)} {ahead[:8]}")
    assert ahead == []
    for _ in range(steps):  # the rest, answered at once
        try:
            _, sensor = arrivals.get(timeout=2.0)
        except queue.Empty:
            break
        answer(link, [0.0] * 6, armed=True, t_us=sensor.time_usec)
    stepper.join()
    reader.join(10.0)
    link.close()


def channels_urdf(port: int) -> str:
    """The firefly with RotorS-style control_channels: u -> (u + offset) * scaling + zero_armed."""
    text = subprocess.run(
        [
            "xacro",
            str(rs.paths.package_path("rotors_description") / "urdf" / "firefly_base.xacro"),
            "mav_name:=firefly",
            "namespace:=firefly",
            "enable_mavlink_interface:=true",
            f"mavlink_tcp_port:={port}",
            "random_seed:=3",
            f"mavlink_answer_timeout:={STRICT_LOCKSTEP_S}",
        ],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    channels = "".join(
        f'<channel name="rotor{i}"><input_index>{5 - i}</input_index><input_offset>0.1</input_offset>'
        f"<input_scaling>500</input_scaling><zero_position_disarmed>{10 * i}</zero_position_disarmed>"
        f"<zero_position_armed>100</zero_position_armed><joint_control_type>velocity</joint_control_type>"
        f"<joint_name>firefly/rotor_{i}_joint</joint_name></channel>"
        for i in range(6)
    )
    return re.sub(r"(<enable_lockstep>[^<]*</enable_lockstep>)", r"\1<control_channels>" + channels + "</control_channels>", text, count=1)


def settle_on(link, controls, armed, steps):
    for _ in range(steps):
        next_sensor(link)
        answer(link, controls, armed=armed)


def test_control_channels_map_as_rotors_disarmed_values_apply():
    port = free_port()
    world = make_world(port, urdf=channels_urdf(port))
    stepper, link = start_lockstep(world, port, 600)
    u = [0.2, 0.3, 0.4, 0.5, 0.6, 0.7]
    settle_on(link, u, True, 300)  # 1.2 s: the motors reach their command (time constants 12.5/25 ms)
    armed = np.abs(world.rotor_speeds("firefly"))
    settle_on(link, u, False, 300)
    stepper.join()
    disarmed = np.abs(world.rotor_speeds("firefly"))
    expected = [(u[5 - i] + 0.1) * 500 + 100 for i in range(6)]  # channel i reads output 5 - i
    print(f"armed {armed.round(1)} (expected {np.round(expected, 1)}), disarmed {disarmed.round(1)}")
    np.testing.assert_allclose(armed, expected, rtol=2e-3)
    np.testing.assert_allclose(disarmed, [10 * i for i in range(6)], atol=0.5)


def test_no_control_channels_output_i_drives_motor_i_to_max(exchange):
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 300)
    settle_on(link, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6], True, 300)
    stepper.join()
    np.testing.assert_allclose(np.abs(world.rotor_speeds("firefly")), np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]) * MAX_ROT, rtol=2e-3)


class HilSensorAutopilot:
    """The autopilot's side of a closed loop on HIL_SENSOR alone (no ground truth, no GPS): the gyro
    bias, tilt, heading (magnetometer, with the field's declination) and ground pressure altitude
    from 1 s at rest; then the attitude from the gyro, the height and climb rate from the barometer
    and the accelerometer (complementary filter), an altitude PID on the thrust and a level attitude
    at the initial heading, flown by the rotors_control attitude controller library."""

    def __init__(self, z_ref):
        self.z_ref = z_ref
        self.attitude = rs.AttitudeLevelController.for_mav("firefly")
        self.mass = self.attitude.vehicle["mass_kg"]
        self.rest = []
        self.q = None  # (w, x, y, z) ENU <- FLU
        self.z = self.vz = self.integral = 0.0
        self.t_us = None

    def on_sensor(self, s):
        gyro = frd([s.xgyro, s.ygyro, s.zgyro])  # FRD -> FLU (the same flip both ways)
        f = frd([s.xacc, s.yacc, s.zacc])
        if self.q is None:
            self.rest.append((gyro, f, frd([s.xmag, s.ymag, s.zmag]), s.pressure_alt))
            if len(self.rest) < 250:
                self.t_us = s.time_usec
                return [0.0] * 6
            self.initialise()
        dt = (s.time_usec - self.t_us) * 1e-6
        self.t_us = s.time_usec
        w = gyro - self.gyro_bias
        self.q = integrate_gyro(self.q, w, dt)
        a_up = rotate(self.q, f)[2] - 9.80665
        self.vz += a_up * dt
        self.z += self.vz * dt
        error = (s.pressure_alt - self.ground_alt) - self.z
        self.z += 0.02 * error
        self.vz += 0.2 * error
        e = self.z_ref - self.z
        self.integral = float(np.clip(self.integral + e * dt, -2, 2))
        tilt = rotate(self.q, [0, 0, 1])[2]
        thrust = self.mass * (9.80665 + 4.0 * e - 3.0 * self.vz + 1.0 * self.integral) / max(tilt, 0.7)
        self.attitude.set_attitude_thrust(self.q_level_xyzw, thrust)
        q_xyzw = [self.q[1], self.q[2], self.q[3], self.q[0]]
        speeds = self.attitude.engine.answer(np.zeros(3), np.array(q_xyzw), np.zeros(3), w, s.time_usec * 1e-6)
        return list(np.clip(np.asarray(speeds) / MAX_ROT, 0.0, 1.0))

    def initialise(self):
        gyro, f, mag, alt = (np.array(x) for x in zip(*self.rest))
        self.gyro_bias = gyro.mean(axis=0)
        self.ground_alt = alt.mean()
        up = f.mean(axis=0) / np.linalg.norm(f.mean(axis=0))  # at rest the specific force points up
        roll, pitch = math.atan2(up[1], up[2]), -math.asin(np.clip(up[0], -1, 1))
        m = mag.mean(axis=0)
        # level: the field's horizontal angle in the body is its angle in ENU minus the yaw; in ENU it
        # points north-east of east by 90 deg - the declination (refMagEast, refMagNorth of the plugin)
        field_angle_enu = math.atan2(2.1493e-5, 8.15e-7)
        yaw = field_angle_enu - math.atan2(m[1], m[0])
        self.initial = (roll, pitch, yaw)
        cy, sy, cp, sp, cr, sr = (
            math.cos(yaw / 2),
            math.sin(yaw / 2),
            math.cos(pitch / 2),
            math.sin(pitch / 2),
            math.cos(roll / 2),
            math.sin(roll / 2),
        )
        self.q = np.array(
            [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy]
        )
        self.q_level_xyzw = [0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]


def test_autopilot_side_controller_flies_on_hil_sensor_to_2_m():
    # with the launch's own answer timeout (mavlink_answer_timeout 0.01 s, PX4's plugin's): the flight
    # as PX4 would have it, the world going on when an answer is late
    port = free_port()
    world = make_world(port, seed=21, mavlink_answer_timeout=0.01)
    stepper, link = start_lockstep(world, port, int(12.0 / DT))
    pilot = HilSensorAutopilot(z_ref=2.0)
    truth = []
    start = time.monotonic()
    while True:
        m = link.recv_match(type="HIL_SENSOR", blocking=True, timeout=2)
        if m is None:
            break
        answer(link, pilot.on_sensor(m), armed=True, t_us=m.time_usec)
        p, q, _, _ = world.link_state("firefly")
        truth.append((m.time_usec * 1e-6, *p, *q))
    wall = time.monotonic() - start
    stepper.join()
    truth = np.array(truth)
    roll0, pitch0, yaw0 = pilot.initial
    print(
        f"estimated at rest: roll {math.degrees(roll0):.2f} pitch {math.degrees(pitch0):.2f} "
        f"yaw {math.degrees(yaw0):.2f} deg (truth 0, 0, 0); {len(truth)} steps through the bridge in {wall:.1f} s "
        f"({len(truth) / wall:.0f} steps/s)"
    )
    held = truth[truth[:, 0] > 8.0]
    z_rest = truth[0, 3]
    tilt = np.degrees(2 * np.arcsin(np.clip(np.hypot(held[:, 4], held[:, 5]), 0, 1)))
    yaw = np.degrees(2 * np.arctan2(held[:, 6], held[:, 7]))  # about up: q = (0, 0, sin, cos) when level
    drift = np.hypot(held[:, 1] - truth[0, 1], held[:, 2] - truth[0, 2])
    print(
        f"t > 8 s: height above the rest {held[:, 3].min() - z_rest:.3f}..{held[:, 3].max() - z_rest:.3f} m, "
        f"tilt <= {tilt.max():.2f} deg, yaw {yaw.min():.2f}..{yaw.max():.2f} deg, horizontal drift <= {drift.max():.2f} m "
        "(not observable from HIL_SENSOR: the accelerometer's turn-on bias reads as a tilt)"
    )
    # the estimates at rest: within the accelerometer's turn-on bias (sigma 0.196 m/s^2: 1.1 deg) and
    # the magnetometer's heading
    assert abs(math.degrees(roll0)) < 2.5 and abs(math.degrees(pitch0)) < 2.5 and abs(math.degrees(yaw0)) < 2.0
    # the set point: 2 m above the take-off point, level, the initial heading
    assert np.all(np.abs(held[:, 3] - z_rest - 2.0) < 0.15)
    assert tilt.max() < 3.0 and np.abs(yaw).max() < 3.0


def test_distance_sensor_carries_rangefinder_reading_in_cm():
    port = free_port()
    world = make_world(port, enable_lidar="rangefinder")
    world.set_model_state("firefly", [0.0, 0.0, 3.0])  # falling from 3 m: in the rangefinder's range
    stepper, link = start_lockstep(world, port, 100)
    seen = []
    for _ in range(100):
        _, others = next_sensor(link)
        ranges = [m for m in others if m.get_type() == "DISTANCE_SENSOR"]
        lidar = world.message("/firefly/lidar")
        if ranges and lidar:
            seen.append((ranges[-1], lidar[0]))
        answer(link, [0.0] * 6, armed=True)
    stepper.join()
    m, r = seen[-1]
    print(
        f"{len(seen)} DISTANCE_SENSOR; last {m.current_distance} cm (Range {r.range:.4f} m), "
        f"{m.min_distance}-{m.max_distance} cm, orientation {m.orientation}"
    )
    assert len(seen) >= 7  # the rangefinder's 20 Hz over 0.4 s, each one sent once
    assert 2.0 < r.range < 3.0
    assert m.current_distance == round(r.range * 100) and m.min_distance == round(r.min_range * 100)
    assert m.max_distance == round(r.max_range * 100) and m.orientation == 25  # MAV_SENSOR_ROTATION_PITCH_270: down


def test_two_vehicles_own_ports_step_in_lockstep_with_autopilots():
    ports = free_port(), free_port()
    world = rs.World("basic", step_size=DT)
    for i, port in enumerate(ports):
        world.spawn_mav(
            "firefly",
            namespace=f"firefly_{i}",
            xyz=(0, 2 * i, 0.1),
            random_seed=30 + i,
            enable_mavlink_interface=True,
            mavlink_tcp_port=port,
            mavlink_answer_timeout=STRICT_LOCKSTEP_S,
        )
    stepper = SteppingWorld(world)
    stepper.run(1)
    stepper.join()
    links = [connect(port) for port in ports]
    stepper.run(1)
    stepper.join()
    for link in links:
        next_sensor(link)
        answer(link, [0.0] * 6, armed=True)
    stepper.run(50)
    for _ in range(49):
        for i, link in enumerate(links):
            next_sensor(link)
            answer(link, [0.5 if i == 0 else 0.0] * 6, armed=True)
    next_sensor(links[0])
    answer(links[0], [0.5] * 6, armed=True)
    next_sensor(links[1])  # the world waits for the second autopilot's answer
    held = world.time
    time.sleep(0.3)
    assert world.time == held
    answer(links[1], [0.0] * 6, armed=True)
    stepper.join()
    speeds = [np.abs(world.rotor_speeds(f"firefly_{i}")) for i in range(2)]
    print(f"vehicle 0 rotors {speeds[0].round(0)}, vehicle 1 rotors {speeds[1].round(0)}")
    assert speeds[0].min() > 300 and speeds[1].max() < 1.0  # each autopilot drives its own vehicle


def test_hil_optical_flow_carries_the_flow_plugins_integrals():
    """RotorS' flow camera (test_optical_flow.py's) with an IMU and the MAVLink interface, moving at
    0.5 m/s 2 m over RotorS' asphalt: HIL_OPTICAL_FLOW is the flow plugin's OpticalFlowRad."""
    import test_optical_flow as flow

    port = free_port()
    world = rs.World(
        sdf=f"""<?xml version="1.0"?><sdf version="1.6"><world name="flow">
      <physics type="ode"><max_step_size>0.002</max_step_size><real_time_factor>0</real_time_factor></physics>
      <gravity>0 0 0</gravity>{flow.GROUND["asphalt"]}</world></sdf>"""
    )
    interface = f"""<plugin name="mavlink_interface" filename="librotors_gazebo_mavlink_interface.so">
        <robotNamespace>cam</robotNamespace><linkName>link</linkName><mavlink_tcp_port>{port}</mavlink_tcp_port>
        <answer_timeout>{STRICT_LOCKSTEP_S}</answer_timeout>
      </plugin>
      <plugin name="imu" filename="librotors_gazebo_imu_plugin.so"><robotNamespace>cam</robotNamespace>
        <linkName>link</linkName><imuTopic>imu</imuTopic></plugin>"""
    world.spawn(flow.CAMERA.replace("</link></model>", "</link>" + interface + "</model>"), "cam")
    world.set_model_state("cam", [0, 0, 2.0], [0, math.sin(math.pi / 4), 0, math.cos(math.pi / 4)], velocity=[0.5, 0.0, 0.0])
    stepper, link = start_lockstep(world, port, 500)
    pairs = []
    for _ in range(500):
        _, others = next_sensor(link)
        flows = [m for m in others if m.get_type() == "HIL_OPTICAL_FLOW"]
        if flows:
            pairs.append((flows[-1], world.message(flow.TOPIC)[0]))
        answer(link, [], armed=True)
    stepper.join()
    m, r = pairs[-1]
    print(
        f"{len(pairs)} HIL_OPTICAL_FLOW; last integrated_x {m.integrated_x:.4f} rad over {m.integration_time_us} us "
        f"(OpticalFlowRad {r.integrated_x:.4f}), quality {m.quality}"
    )
    assert len(pairs) >= 15  # the plugin's 20 Hz over 1 s
    for m, r in pairs:
        assert m.integration_time_us == r.integration_time_us and m.quality == r.quality
        np.testing.assert_allclose(
            [m.integrated_x, m.integrated_y, m.distance], [r.integrated_x, r.integrated_y, r.distance], rtol=1e-6, atol=1e-7
        )
    assert m.integrated_x / (m.integration_time_us * 1e-6) == pytest.approx(0.5 / (2.0 - flow.ASPHALT_TOP), rel=0.15)


def techpod_flight(throttle: float, armed: bool) -> float:
    """The techpod launched at 15 m/s, 100 m up, for 2 s on PX4's outputs; its forward speed at the end."""
    port = free_port()
    world = rs.World("basic", step_size=DT)
    world.spawn(
        str(rs.paths.package_path("rotors_description") / "urdf" / "techpod_base.xacro"),
        "techpod",
        xyz=(0, 0, 100),
        mav_name="techpod",
        namespace="techpod",
        enable_mavlink_interface="true",
        mavlink_tcp_port=str(port),
        random_seed="4",
        mavlink_answer_timeout=str(STRICT_LOCKSTEP_S),
    )
    world.set_model_state("techpod", [0, 0, 100], velocity=[15.0, 0, 0])
    stepper, link = start_lockstep(world, port, 500)
    for _ in range(500):
        next_sensor(link)
        answer(link, [0.0, 0.0, 0.0, 0.0, 0.0, throttle], armed=armed)  # techpod.yaml: throttle is channel 5
    stepper.join()
    return float(world.link_state("techpod")[2][0])


def test_fixed_wing_normalized_channels_take_autopilot_outputs():
    full, idle = techpod_flight(1.0, armed=True), techpod_flight(1.0, armed=False)
    print(f"techpod after 2 s from 15 m/s: {full:.2f} m/s at full throttle, {idle:.2f} m/s disarmed")
    assert full > idle + 1.0  # the throttle channel drives the propeller; disarmed it is at zero
