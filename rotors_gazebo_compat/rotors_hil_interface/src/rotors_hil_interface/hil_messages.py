"""The conversions of RotorS' HIL interface, ROS-free: sensor readings (SI units, our FLU body and
ENU world) to the fields of MAVLink's HIL_SENSOR, HIL_GPS and HIL_STATE_QUATERNION, through the
body-to-sensor rotation RotorS' node takes (roll pi by default: FLU -> FRD), and a real autopilot's
HIL_CONTROLS / HIL_ACTUATOR_CONTROLS back to the normalized actuator command. Frames and the
standard atmosphere are the autopilot codecs' own (rotors_sim.frames and rotors_sim.atmosphere, bound
from rotors_plugins' autopilot/frames.h and models/standard_atmosphere.h): one conversion for the
simulator's interfaces and this node."""

from __future__ import annotations

import math

import numpy as np

from rotors_sim import atmosphere, frames

STANDARD_GRAVITY = 9.80665
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
    return np.asarray(frames.ned_from_enu(np.asarray(v, float)))


def pressure_altitude(pressure_pa: float) -> float:
    """[m] of the international standard atmosphere."""
    return atmosphere.pressure_altitude_m(pressure_pa)


def hil_sensor_fields(R_BS: np.ndarray, accel_B, gyro_B, mag_B_T, pressure_pa: float, new_mag: bool, new_baro: bool) -> dict:
    """HIL_SENSOR's fields: body readings turned into the sensor frame (v_S = R_BS^T v_B)."""
    a, w, m = (R_BS.T @ np.asarray(v, float) for v in (accel_B, gyro_B, mag_B_T))
    altitude = pressure_altitude(pressure_pa)
    return dict(
        xacc=a[0],
        yacc=a[1],
        zacc=a[2],
        xgyro=w[0],
        ygyro=w[1],
        zgyro=w[2],
        xmag=m[0] * 1e4,
        ymag=m[1] * 1e4,
        zmag=m[2] * 1e4,  # T -> gauss
        abs_pressure=pressure_pa / 100.0,
        diff_pressure=0.0,
        pressure_alt=altitude,
        temperature=atmosphere.temperature_C(altitude),
        fields_updated=FIELDS_IMU | (FIELDS_MAG if new_mag else 0) | (FIELDS_BARO if new_baro else 0),
    )


def hil_gps_fields(latitude: float, longitude: float, altitude: float, hor_std: float, ver_std: float, velocity_W) -> dict:
    v = ned_from_enu(velocity_W)
    speed = math.hypot(v[0], v[1])
    course = math.degrees(math.atan2(v[1], v[0])) % 360.0
    return dict(
        fix_type=3,
        lat=round(latitude * 1e7),
        lon=round(longitude * 1e7),
        alt=round(altitude * 1000),
        eph=min(65535, round(hor_std * 100)),
        epv=min(65535, round(ver_std * 100)),
        vel=min(65535, round(speed * 100)),
        vn=round(v[0] * 100),
        ve=round(v[1] * 100),
        vd=round(v[2] * 100),
        cog=min(35999, round(course * 100)) if speed > 0 else 65535,
        satellites_visible=10,
    )


def world_from_body(q_WB_wxyz, v_B) -> np.ndarray:
    """v_W = R_WB v_B for q_WB = (w, x, y, z)."""
    qw, qx, qy, qz = q_WB_wxyz
    R_WB = np.array(
        [
            [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)],
            [2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)],
            [2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)],
        ]
    )
    return R_WB @ np.asarray(v_B, float)


def hil_state_fields(q_WB_wxyz, omega_B, v_W, latitude: float, longitude: float, altitude: float, specific_force_B) -> dict:
    """HIL_STATE_QUATERNION: q NED <- FRD; the acceleration in NED as m/s^2 * 1000 (PX4 reads xacc /
    1000 as m/s^2): a_W = R_WB f_B + g_W."""
    q = np.asarray(frames.ned_frd_from_enu_flu(np.asarray(q_WB_wxyz, float)))
    w = frames.frd_from_flu(np.asarray(omega_B, float))
    v = ned_from_enu(v_W)
    a_NED = ned_from_enu(world_from_body(q_WB_wxyz, specific_force_B) - np.array([0.0, 0.0, STANDARD_GRAVITY])) * 1000.0
    return dict(
        attitude_quaternion=[float(x) for x in q],
        rollspeed=w[0],
        pitchspeed=w[1],
        yawspeed=w[2],
        lat=round(latitude * 1e7),
        lon=round(longitude * 1e7),
        alt=round(altitude * 1000),
        vx=round(v[0] * 100),
        vy=round(v[1] * 100),
        vz=round(v[2] * 100),
        ind_airspeed=round(float(np.linalg.norm(v_W)) * 100),
        true_airspeed=round(float(np.linalg.norm(v_W)) * 100),
        xacc=round(a_NED[0]),
        yacc=round(a_NED[1]),
        zacc=round(a_NED[2]),
    )


def normalized_from_hil_controls(m) -> list[float]:
    """RotorS' order: roll_ailerons, pitch_elevator, yaw_rudder, aux1, aux2, throttle."""
    return [m.roll_ailerons, m.pitch_elevator, m.yaw_rudder, m.aux1, m.aux2, m.throttle]
