"""mav_px4_sitl.launch's vehicle as PX4's own code reads it (px4_checks.py gives each rule and its
source): pymavlink stands in for PX4 on the TCP link (PX4 is not on these machines). One flight with
the launch's defaults (the iris, PX4's autopilot profile, 4 ms steps, lockstep): 20 s at rest, then a
controller on the autopilot's side estimates the state from HIL_SENSOR and HIL_GPS alone (no ground
truth), takes off to 2 m and holds it for 40 s. On that stream: PX4's stale-data rule on every
HIL_SENSOR channel, EKF2's GNSS checks with every check on, the gyro vibration metric of EKF2's
on-ground movement test, and the hold."""

from __future__ import annotations

import math
import time
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import yaml
from pygeomag import GeoMag

import rotors_sim as rs
from support.px4 import STRICT_LOCKSTEP_S, answer, frd, free_port, integrate_gyro, rotate, start_lockstep
from support.px4_checks import MAG_VALUE_EQUAL_COUNT, DataValidatorStale, GnssChecks, gyro_vibration_metric, hil_sensor_channels

LAUNCH = rs.paths.package_path("rotors_gazebo") / "launch" / "mav_px4_sitl.launch"
# PX4-SITL_gazebo-classic models/iris/iris.sdf.jinja: each rotor's motor model and the channels
PX4_IRIS = dict(motor_constant=5.84e-06, moment_constant=0.06, max_rot_velocity=1100.0, input_scaling=1000.0, zero_position_armed=100.0)
REST_S, FLIGHT_S, Z_REF = 20.0, 60.0, 2.0


def launch_defaults() -> dict[str, str]:
    return {a.get("name"): a.get("default") for a in ET.parse(LAUNCH).getroot().iter("arg") if a.get("default")}


def px4_iris_controller_yaml(tmp_path) -> str:
    """The Lee controller's vehicle file for the iris PX4 flies: our iris with PX4's rotor constants."""
    vehicle = yaml.safe_load(rs.paths.resource("iris.yaml").read_text())
    for rotor in vehicle["rotor_configuration"].values():
        rotor.update(
            rotor_force_constant=PX4_IRIS["motor_constant"],
            rotor_moment_constant=PX4_IRIS["moment_constant"],
            max_rot_velocity=PX4_IRIS["max_rot_velocity"],
        )
    path = tmp_path / "px4_iris.yaml"
    path.write_text(yaml.safe_dump(vehicle))
    return str(path)


class GpsInertialStandIn:
    """The autopilot's side: gyro bias, attitude, heading and ground altitude from 1 s at rest; then the
    attitude from the gyro, the height from the barometer and the horizontal position and velocity
    from the accelerometer corrected by HIL_GPS (complementary filters); RotorS' Lee controller on that
    estimate, its rotor speeds as PX4's outputs through the iris' channels (omega = 1000 u + 100)."""

    def __init__(self, controller: rs.LeePositionController):
        self.lee = controller
        self.rest = []
        self.q = None  # (w, x, y, z) ENU <- FLU
        self.p = np.zeros(3)
        self.v = np.zeros(3)
        self.origin = None
        self.t_us = None
        self.flying = False
        self.home = None

    def on_gps(self, m):
        lat, lon = m.lat * 1e-7, m.lon * 1e-7
        self.home = self.home or (lat, lon)
        if self.origin is None:
            self.origin = (lat, lon)
        east = math.radians(lon - self.origin[1]) * 6371000.0 * math.cos(math.radians(self.origin[0]))
        north = math.radians(lat - self.origin[0]) * 6371000.0
        if self.q is None:
            return
        # 5 Hz corrections of the horizontal position and velocity
        self.p[:2] += 0.3 * (np.array([east, north]) - self.p[:2])
        self.v[:2] += 0.3 * (np.array([m.ve, m.vn]) * 0.01 - self.v[:2])

    def on_sensor(self, s) -> list[float]:
        gyro, f = frd([s.xgyro, s.ygyro, s.zgyro]), frd([s.xacc, s.yacc, s.zacc])
        if self.q is None:
            self.rest.append((gyro, f, frd([s.xmag, s.ymag, s.zmag]), s.pressure_alt))
            self.t_us = s.time_usec
            if len(self.rest) < 250 or self.home is None:
                return [0.0] * 4
            self.initialise()
        dt = (s.time_usec - self.t_us) * 1e-6
        self.t_us = s.time_usec
        w = gyro - self.gyro_bias
        self.q = integrate_gyro(self.q, w, dt)
        a_W = rotate(self.q, f - self.accel_bias) - np.array([0, 0, 9.80665])
        self.v += a_W * dt
        self.p += self.v * dt
        error = (s.pressure_alt - self.ground_alt) - self.p[2]
        self.p[2] += 0.02 * error
        self.v[2] += 0.2 * error
        if not self.flying:
            return [0.0] * 4
        velocity_B = rotate([self.q[0], -self.q[1], -self.q[2], -self.q[3]], self.v)
        speeds = self.lee.engine.answer(self.p, np.array([self.q[1], self.q[2], self.q[3], self.q[0]]), velocity_B, w, s.time_usec * 1e-6)
        u = (np.asarray(speeds) - PX4_IRIS["zero_position_armed"]) / PX4_IRIS["input_scaling"]
        return list(np.clip(u, 0.0, 1.0))

    def initialise(self):
        gyro, f, mag, alt = (np.array(x) for x in zip(*self.rest))
        self.gyro_bias = gyro.mean(axis=0)
        self.ground_alt = alt.mean()
        # level on the ground: what the accelerometer reads beyond g is its bias
        self.accel_bias = f.mean(axis=0) - np.array([0, 0, 9.80665])
        m = mag.mean(axis=0)
        # the field's horizontal angle in ENU from the World Magnetic Model at the home position, as
        # PX4 takes its declination from its own WMM tables
        wmm = GeoMag().calculate(glat=self.home[0], glon=self.home[1], alt=0.5, time=2026.9)
        yaw = math.atan2(wmm.x, wmm.y) - math.atan2(m[1], m[0])
        self.yaw = yaw
        self.q = np.array([math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)])

    def take_off(self, z_ref):
        self.flying = True
        self.lee.set_point([self.p[0], self.p[1], z_ref], yaw=self.yaw)


@pytest.fixture(scope="module")
def px4_flight(tmp_path_factory):
    defaults = launch_defaults()
    step = float(defaults["step_size"])
    port = free_port()
    world = rs.World(defaults["world_name"], step_size=step)
    world.spawn_mav(
        defaults["mav_name"],
        enable_mavlink_interface=True,
        mavlink_tcp_port=port,
        autopilot_profile=defaults["autopilot_profile"],
        random_seed=5,
        mavlink_answer_timeout=STRICT_LOCKSTEP_S,
    )
    # PX4 connects, takes the first HIL_SENSOR and answers it: from then on each step waits for its answer
    stepper, link = start_lockstep(world, port, int(FLIGHT_S / step))
    controller = rs.LeePositionController(
        rs.paths.resource("lee_controller_iris.yaml"), px4_iris_controller_yaml(tmp_path_factory.mktemp("px4"))
    )
    pilot = GpsInertialStandIn(controller)
    sensors, fixes, truth = [], [], []
    start = time.monotonic()
    while True:
        m = link.recv_match(type=["HIL_SENSOR", "HIL_GPS"], blocking=True, timeout=5)
        if m is None:
            break
        t = m.time_usec * 1e-6
        if m.get_type() == "HIL_GPS":
            fixes.append((world.time, m))
            pilot.on_gps(m)
            continue
        if not pilot.flying and pilot.q is not None and t >= REST_S:
            pilot.take_off(Z_REF)
        answer(link, pilot.on_sensor(m), armed=True, t_us=m.time_usec)
        sensors.append(m)
        p, _, _, _ = world.link_state("iris")
        truth.append((t, *p, *pilot.p))
    wall = time.monotonic() - start
    stepper.join()
    link.close()
    print(
        f"{len(sensors)} HIL_SENSOR and {len(fixes)} HIL_GPS in {wall:.1f} s of wall time; initial yaw estimate "
        f"{math.degrees(pilot.yaw):.2f} deg (the iris faces east: 0)"
    )
    return world, sensors, fixes, np.array(truth), defaults


def test_the_launch_flies_pxs_iris_constants(px4_flight):
    world, _, _, _, defaults = px4_flight
    assert defaults["mav_name"] == "iris" and defaults["autopilot_profile"] == "px4"
    assert float(defaults["step_size"]) == 0.004  # PX4's IMU_INTEG_RATE 250 Hz
    urdf = rs.paths.package_path("rotors_description") / "urdf" / "iris_base.xacro"
    text = (
        rs.xacro_to_urdf(urdf, mav_name="iris", namespace="iris", enable_mavlink_interface="true", autopilot_profile="px4")
        if hasattr(rs, "xacro_to_urdf")
        else None
    )
    if text is None:
        import subprocess

        text = subprocess.run(
            ["xacro", str(urdf), "enable_mavlink_interface:=true", "autopilot_profile:=px4"], check=True, capture_output=True, text=True
        ).stdout
    root = ET.fromstring(text)
    motors = [p for p in root.iter("plugin") if p.get("filename") == "librotors_gazebo_motor_model.so"]
    assert len(motors) == 4
    for motor in motors:
        assert float(motor.find("motorConstant").text) == PX4_IRIS["motor_constant"]
        assert float(motor.find("momentConstant").text) == PX4_IRIS["moment_constant"]
        assert float(motor.find("maxRotVelocity").text) == PX4_IRIS["max_rot_velocity"]
    channels = list(root.iter("channel"))
    assert len(channels) == 4
    for i, c in enumerate(channels):
        assert int(c.find("input_index").text) == i
        assert float(c.find("input_scaling").text) == PX4_IRIS["input_scaling"]
        assert float(c.find("zero_position_armed").text) == PX4_IRIS["zero_position_armed"]
        assert float(c.find("zero_position_disarmed").text) == 0.0
    # hover throttle and thrust-to-weight as airframe 10015 sees them
    mass = 1.5 + 4 * 0.005 + 0.015 * 3 + 0.015  # body, rotors, IMU and the three navigation sensors
    omega_hover = math.sqrt(mass * 9.81 / (4 * PX4_IRIS["motor_constant"]))
    print(
        f"hover: {omega_hover:.0f} rad/s, throttle u = {(omega_hover - 100) / 1000:.2f}; thrust to weight "
        f"{4 * PX4_IRIS['motor_constant'] * 1100 ** 2 / (mass * 9.81):.2f}"
    )


def test_no_hil_sensor_channel_goes_stale_at_rest_or_in_hover(px4_flight):
    _, sensors, _, _, _ = px4_flight
    validators = {}
    for m in sensors:
        for name, values in hil_sensor_channels(m).items():
            if name not in validators:
                validators[name] = DataValidatorStale(MAG_VALUE_EQUAL_COUNT if name == "magnetometer" else 100)
            validators[name].put(values)
    for name, v in validators.items():
        print(f"{name}: longest run of equal values {v.max_equal_count} (stale above {v.threshold}), " f"stale samples {v.stale_samples}")
    assert set(validators) >= {"accelerometer", "gyroscope", "magnetometer", "barometer"}
    assert all(v.stale_samples == 0 for v in validators.values())


def test_ekf2_gnss_checks_pass_for_10_s_within_30_s(px4_flight):
    _, _, fixes, _, _ = px4_flight
    checks = GnssChecks()
    for t, m in fixes:
        if t > 30.0:
            break
        checks.run(t, m)
    print(
        f"EKF2's GNSS checks (every bit on, drift filters on every fix) passed at t = {checks.passed_at} s; " f"failures {checks.failures}"
    )
    assert checks.passed_at is not None and checks.passed_at <= 30.0


def test_gyro_vibration_metric_against_ekf2s_at_rest_limit(px4_flight):
    _, sensors, _, _, _ = px4_flight
    gyro = np.array([[m.xgyro, m.ygyro, m.zgyro] for m in sensors if m.time_usec * 1e-6 < REST_S])
    metric = gyro_vibration_metric(gyro)[500:]
    # PX4's own simulation: gazebo_imu_plugin's gyroscopeNoiseDensity 0.0008726646 rad/s/sqrt(Hz) at
    # 250 Hz: per-axis sigma 0.0138 rad/s, E|w_k - w_k-1| = sqrt(2) sigma sqrt(8 / pi)
    sigma = 0.0008726646 / math.sqrt(0.004)
    px4_own = math.sqrt(2) * sigma * math.sqrt(8 / math.pi)
    print(
        f"gyro vibration metric at rest: ours {metric.mean():.4f} rad/s, PX4's own iris {px4_own:.4f} rad/s, "
        "the land detector's limit 0.02: neither counts as at rest, so EKF2's drift checks do not run "
        "in PX4's own simulation either (GnssChecks runs them anyway)"
    )
    assert metric.mean() == pytest.approx(px4_own, rel=0.1)


def test_gps_inertial_controller_takes_off_to_2_m_and_holds_it(px4_flight):
    _, _, _, truth, _ = px4_flight
    rest = truth[truth[:, 0] < REST_S]
    held = truth[truth[:, 0] > REST_S + 15.0]
    start = rest[-1, 1:4]
    error = held[:, 1:4] - (start + np.array([0, 0, Z_REF]))
    horizontal = np.hypot(error[:, 0], error[:, 1])
    print(
        f"t > {REST_S + 15:.0f} s: height error {np.abs(error[:, 2]).max():.3f} m, horizontal <= "
        f"{horizontal.max():.3f} m (the estimate's: {np.abs(held[:, 4:7] - held[:, 1:4]).max(axis=0).round(3)})"
    )
    assert np.abs(error[:, 2]).max() < 0.2 and horizontal.max() < 0.3


# --- negative controls: the stand-in checks fail where PX4's would ---


def test_the_stale_rule_catches_a_constant_stream(px4_flight):
    """The flight's barometer held at its first value: PX4's DataValidator counts every equal value of
    its three (the barometer's two unused are 0, always equal) and calls the sensor stale past 100,
    from the 35th sample, as it would a frozen sensor."""
    _, sensors, _, _, _ = px4_flight
    first = next(v for m in sensors for name, v in hil_sensor_channels(m).items() if name == "barometer")
    validator = DataValidatorStale(100)
    stale_from = next(i for i in range(1, 500) if validator.put(first))
    print(f"a constant barometer ({first[0]:.2f} hPa): stale from sample {stale_from}")
    assert stale_from == 35


def test_rotors_own_gps_fails_ekf2s_gnss_checks():
    """RotorS' GPS (the rotors profile: white noise of 3 m / 6 m, eph 3 m, epv 6 m) on the launch's
    iris at rest for 30 s: EKF2's GNSS checks never pass (epv 6 m is above EKF2_REQ_EPV 5 m on every
    fix), where the px4 profile's pass in 10 s."""
    defaults = launch_defaults()
    step = float(defaults["step_size"])
    port = free_port()
    world = rs.World(defaults["world_name"], step_size=step)
    world.spawn_mav(defaults["mav_name"], enable_mavlink_interface=True, mavlink_tcp_port=port, autopilot_profile="rotors", random_seed=5)
    stepper, link = start_lockstep(world, port, int(30.0 / step))
    checks, fixes = GnssChecks(), 0
    while (m := link.recv_match(type=["HIL_SENSOR", "HIL_GPS"], blocking=True, timeout=5)) is not None:
        if m.get_type() == "HIL_GPS":
            fixes += 1
            checks.run(world.time, m)
        else:
            answer(link, [0.0] * 4, armed=False, t_us=m.time_usec)  # disarmed: the world does not wait
    stepper.join()
    link.close()
    print(f"{fixes} fixes of RotorS' GPS in 30 s: checks passed at {checks.passed_at}; failures {checks.failures}")
    assert fixes > 100 and checks.passed_at is None and checks.failures.get("epv", 0) == fixes
