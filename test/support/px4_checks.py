"""What PX4's own code checks on a simulator's stream, as stand-ins for PX4 (not on these machines).
Each class applies the rule of one PX4 source file, with its numbers (PX4/PX4-Autopilot):

- DataValidatorStale: src/modules/sensors/data_validator/DataValidator.{hpp,cpp}: a sensor's values
  go through put(); for each of its (up to 3) values, in order, a value within 1e-6 of the last one
  adds 1 to the equal count and any other value sets it to 0 (the count is shared by the values, the
  last value decides); a count above VALUE_EQUAL_COUNT_DEFAULT = 100 flags ERROR_FLAG_STALE_DATA and
  the sensor's confidence is 0 (the magnetometer's VehicleMagnetometer sets 1000). A scalar sensor
  fills its other two values with 0.
- GnssChecks: src/modules/ekf2/EKF/aid_sources/gnss/gnss_checks.cpp with params_gnss.yaml's
  defaults, every bit of EKF2_GPS_CHECK on (fix >= 3, satellites >= EKF2_REQ_NSATS 6, PDOP <=
  EKF2_REQ_PDOP 2.5, eph <= EKF2_REQ_EPH 3 m, epv <= EKF2_REQ_EPV 5 m, speed accuracy <=
  EKF2_REQ_SACC 0.5 m/s, not spoofed, the horizontal and vertical drift and speed filters against
  EKF2_REQ_HDRIFT 0.1 m/s and EKF2_REQ_VDRIFT 0.2 m/s), passed without a break for EKF2_REQ_GPS_H =
  10 s. The drift filters run only while the EKF thinks the vehicle is at rest on the ground; here
  they run on every fix, which is stricter. HIL_GPS as SimulatorMavlink.cpp turns it into
  sensor_gps: eph, epv in cm -> m, s_variance_m_s 0.25 (fixed), hdop = vdop = 0.
- gyro_vibration_metric: src/modules/sensors/vehicle_imu/VehicleIMU.cpp: gyro_vib = 0.99 gyro_vib +
  0.01 |w_k - w_k-1| per IMU sample; the land detector (LandDetector.cpp) records a move above 0.02,
  and EKF2 counts the vehicle at rest only after 1 s without one.
"""

from __future__ import annotations

import math

import numpy as np

VALUE_EQUAL_COUNT_DEFAULT = 100
MAG_VALUE_EQUAL_COUNT = 1000


class DataValidatorStale:
    def __init__(self, threshold: int = VALUE_EQUAL_COUNT_DEFAULT):
        self.threshold = threshold
        self.last: list[float] | None = None
        self.equal_count = 0
        self.max_equal_count = 0
        self.stale_samples = 0

    def put(self, values) -> bool:
        """One sample (1 to 3 values); True while the sensor is stale."""
        values = [float(v) for v in values] + [0.0] * (3 - len(values))
        if self.last is not None:
            for value, last in zip(values, self.last):
                if math.isfinite(value):
                    self.equal_count = self.equal_count + 1 if abs(value - last) < 1e-6 else 0
        self.last = values
        self.max_equal_count = max(self.max_equal_count, self.equal_count)
        stale = self.equal_count > self.threshold
        self.stale_samples += stale
        return stale


def hil_sensor_channels(m) -> dict[str, list[float]]:
    """The values PX4's sensors module validates, per HIL_SENSOR channel that fields_updated marks."""
    channels = {}
    if m.fields_updated & 0x7:
        channels["accelerometer"] = [m.xacc, m.yacc, m.zacc]
    if m.fields_updated & 0x38:
        channels["gyroscope"] = [m.xgyro, m.ygyro, m.zgyro]
    if m.fields_updated & 0x1C0:
        channels["magnetometer"] = [m.xmag, m.ymag, m.zmag]
    if m.fields_updated & 0x200:  # VehicleAirData: pressure [Pa], temperature, altitude
        channels["barometer"] = [m.abs_pressure * 100.0, m.temperature, m.pressure_alt]
    if m.fields_updated & 0x400:
        channels["differential pressure"] = [m.diff_pressure * 100.0]
    return channels


class GnssChecks:
    EKF2_REQ_FIX = 3
    EKF2_REQ_NSATS = 6
    EKF2_REQ_PDOP = 2.5
    EKF2_REQ_EPH = 3.0
    EKF2_REQ_EPV = 5.0
    EKF2_REQ_SACC = 0.5
    EKF2_REQ_HDRIFT = 0.1
    EKF2_REQ_VDRIFT = 0.2
    EKF2_REQ_GPS_H = 10.0
    EKF2_VEL_LIM = 100.0
    HIL_SPEED_ACCURACY = 0.25  # SimulatorMavlink.cpp: s_variance_m_s for HIL_GPS
    FILTER_TIME_CONSTANT = 10.0
    EARTH_RADIUS = 6371000.0

    def __init__(self):
        self.t_fail: float | None = None
        self.passed_at: float | None = None
        self.previous: tuple[float, float, float, float] | None = None  # t, lat, lon, alt
        self.drift_rate = np.zeros(3)  # N, E, D filtered position derivative
        self.vel_ne = np.zeros(2)
        self.vel_d = 0.0
        self.failures: dict[str, int] = {}

    def run(self, t: float, m) -> bool:
        """One HIL_GPS at sim time t [s]; True once the checks have passed (they latch, as PX4's)."""
        lat, lon, alt = m.lat * 1e-7, m.lon * 1e-7, m.alt * 1e-3
        vel = np.array([m.vn, m.ve, m.vd]) * 0.01
        failed = []
        if m.fix_type < self.EKF2_REQ_FIX:
            failed.append("fix")
        if m.satellites_visible < self.EKF2_REQ_NSATS:
            failed.append("nsats")
        if 0.0 > self.EKF2_REQ_PDOP:  # hdop = vdop = 0 for HIL_GPS
            failed.append("pdop")
        if m.eph * 0.01 > self.EKF2_REQ_EPH:
            failed.append("eph")
        if m.epv * 0.01 > self.EKF2_REQ_EPV:
            failed.append("epv")
        if self.HIL_SPEED_ACCURACY > self.EKF2_REQ_SACC:
            failed.append("sacc")
        if np.hypot(vel[0], vel[1]) > self.EKF2_VEL_LIM or abs(vel[2]) > self.EKF2_VEL_LIM:
            failed.append("velocity limit")
        if self.previous is not None:
            t0, lat0, lon0, alt0 = self.previous
            dt = min(max(t - t0, 0.001), 10.0)
            k = dt / self.FILTER_TIME_CONSTANT
            d_north = math.radians(lat - lat0) * self.EARTH_RADIUS
            d_east = math.radians(lon - lon0) * self.EARTH_RADIUS * math.cos(math.radians(lat0))
            delta = np.array([d_north, d_east, alt0 - alt])
            limit = np.array([self.EKF2_REQ_HDRIFT, self.EKF2_REQ_HDRIFT, self.EKF2_REQ_VDRIFT])
            self.drift_rate = np.clip(delta / dt * k + self.drift_rate * (1 - k), -10 * limit, 10 * limit)
            if np.hypot(*self.drift_rate[:2]) > self.EKF2_REQ_HDRIFT:
                failed.append("horizontal drift")
            if abs(self.drift_rate[2]) > self.EKF2_REQ_VDRIFT:
                failed.append("vertical drift")
            vel_ne = np.clip(vel[:2], -10 * self.EKF2_REQ_HDRIFT, 10 * self.EKF2_REQ_HDRIFT)
            self.vel_ne = vel_ne * k + self.vel_ne * (1 - k)
            if np.hypot(*self.vel_ne) > self.EKF2_REQ_HDRIFT:
                failed.append("horizontal speed")
            vel_d = float(np.clip(vel[2], -10 * self.EKF2_REQ_VDRIFT, 10 * self.EKF2_REQ_VDRIFT))
            self.vel_d = vel_d * k + self.vel_d * (1 - k)
            if abs(self.vel_d) > self.EKF2_REQ_VDRIFT:
                failed.append("vertical speed")
        self.previous = (t, lat, lon, alt)
        for f in failed:
            self.failures[f] = self.failures.get(f, 0) + 1
        if self.t_fail is None or failed:
            self.t_fail = t
        if self.passed_at is None and not failed and t - self.t_fail > self.EKF2_REQ_GPS_H:
            self.passed_at = t
        return self.passed_at is not None


def gyro_vibration_metric(gyro_samples: np.ndarray) -> np.ndarray:
    """VehicleIMU's gyro vibration metric over consecutive gyro samples [rad/s]."""
    metric, out = 0.0, []
    for previous, current in zip(gyro_samples[:-1], gyro_samples[1:]):
        metric = 0.99 * metric + 0.01 * float(np.linalg.norm(current - previous))
        out.append(metric)
    return np.array(out)
