"""The conversions of RotorS' HIL interface, ROS-free: sensor readings (SI units, our FLU body and
ENU world) to the fields of MAVLink's HIL_SENSOR, HIL_GPS and HIL_STATE_QUATERNION, through the
body-to-sensor rotation RotorS' node takes (roll pi by default: FLU -> FRD), and a real autopilot's
HIL_CONTROLS / HIL_ACTUATOR_CONTROLS back to the normalized actuator command."""
from __future__ import annotations

import math

import numpy as np

ISA_P0, ISA_T0, ISA_L, ISA_EXPONENT = 101325.0, 288.15, 0.0065, 0.190263
# HIL_SENSOR.fields_updated: accel, gyro, mag, abs pressure + pressure altitude + temperature
FIELDS_IMU, FIELDS_MAG, FIELDS_BARO = 0x3F, 0x1C0, 0x1A00


def rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R_BS = Rz(yaw) Ry(pitch) Rx(roll): the sensor frame in the body frame."""
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), math.sin(yaw)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def ned_from_enu(v) -> np.ndarray:
    return np.array([v[1], v[0], -v[2]])


def pressure_altitude(pressure_pa: float) -> float:
    """[m] of the international standard atmosphere."""
    return ISA_T0 / ISA_L * (1.0 - (pressure_pa / ISA_P0) ** ISA_EXPONENT)


def hil_sensor_fields(R_BS: np.ndarray, accel_B, gyro_B, mag_B_T, pressure_pa: float, new_mag: bool,
                      new_baro: bool) -> dict:
    """HIL_SENSOR's fields: body readings turned into the sensor frame (v_S = R_BS^T v_B)."""
    a, w, m = (R_BS.T @ np.asarray(v, float) for v in (accel_B, gyro_B, mag_B_T))
    altitude = pressure_altitude(pressure_pa)
    return dict(xacc=a[0], yacc=a[1], zacc=a[2], xgyro=w[0], ygyro=w[1], zgyro=w[2],
                xmag=m[0] * 1e4, ymag=m[1] * 1e4, zmag=m[2] * 1e4,  # T -> gauss
                abs_pressure=pressure_pa / 100.0, diff_pressure=0.0, pressure_alt=altitude,
                temperature=ISA_T0 - ISA_L * altitude - 273.15,
                fields_updated=FIELDS_IMU | (FIELDS_MAG if new_mag else 0) | (FIELDS_BARO if new_baro else 0))


def hil_gps_fields(latitude: float, longitude: float, altitude: float, hor_std: float, ver_std: float,
                   velocity_W) -> dict:
    v = ned_from_enu(velocity_W)
    speed = math.hypot(v[0], v[1])
    course = math.degrees(math.atan2(v[1], v[0])) % 360.0
    return dict(fix_type=3, lat=round(latitude * 1e7), lon=round(longitude * 1e7), alt=round(altitude * 1000),
                eph=min(65535, round(hor_std * 100)), epv=min(65535, round(ver_std * 100)),
                vel=min(65535, round(speed * 100)), vn=round(v[0] * 100), ve=round(v[1] * 100), vd=round(v[2] * 100),
                cog=min(35999, round(course * 100)) if speed > 0 else 65535, satellites_visible=10)


def quaternion_multiply(a, b) -> np.ndarray:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


def hil_state_fields(q_WB_wxyz, omega_B, v_W, latitude: float, longitude: float, altitude: float,
                     specific_force_B) -> dict:
    """HIL_STATE_QUATERNION: q NED <- FRD = q_NED_ENU q_ENU_FLU q_FLU_FRD."""
    s = math.sqrt(0.5)
    q = quaternion_multiply(quaternion_multiply([0.0, s, s, 0.0], q_WB_wxyz), [0.0, 1.0, 0.0, 0.0])
    if q[0] < 0:
        q = -q
    w = [omega_B[0], -omega_B[1], -omega_B[2]]
    v = ned_from_enu(v_W)
    f = np.array([specific_force_B[0], -specific_force_B[1], -specific_force_B[2]]) / 9.80665 * 1000.0
    return dict(attitude_quaternion=[float(x) for x in q], rollspeed=w[0], pitchspeed=w[1], yawspeed=w[2],
                lat=round(latitude * 1e7), lon=round(longitude * 1e7), alt=round(altitude * 1000),
                vx=round(v[0] * 100), vy=round(v[1] * 100), vz=round(v[2] * 100),
                ind_airspeed=round(float(np.linalg.norm(v_W)) * 100), true_airspeed=round(float(np.linalg.norm(v_W)) * 100),
                xacc=round(f[0]), yacc=round(f[1]), zacc=round(f[2]))


def normalized_from_hil_controls(m) -> list[float]:
    """RotorS' order: roll_ailerons, pitch_elevator, yaw_rudder, aux1, aux2, throttle."""
    return [m.roll_ailerons, m.pitch_elevator, m.yaw_rudder, m.aux1, m.aux2, m.throttle]
