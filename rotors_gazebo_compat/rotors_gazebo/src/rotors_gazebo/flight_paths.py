"""Smooth camera flights for the perception tests: straight legs flown at a cruise speed with a
trapezoidal speed profile, and turns on the spot with a cosine yaw profile, sampled with the
velocity, acceleration and yaw-rate feed-forward the Lee position controller takes.

A path is a start (x, y, z, yaw) and a list of corners (x, y, z): the MAV first turns to face the
first leg, flies it facing along it, turns on the spot at each corner, and so on; or, given a fixed
`facing` yaw, turns to it once and keeps it (flying sideways past what it looks at). `sway` adds a
sinusoidal yaw on top; `shaped_like` picks the cruise speed and the sway's rate that give a flight
the mean speed and mean angular rate of a EuRoC sequence (EUROC_SHAPES); trajectory files hold a
sampled flight (write_trajectory_file / read_trajectory_file) for trajectory_publisher_file."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

# RotorS' warehouse, 1.5 m up, always facing -x (the world is open beyond x 10, and a camera facing
# there sees only sky and a plain ground plane): down the aisle between the shelf rows (x -4.2 to 6.0)
# at y 3.4 and y -1.5 towards the grey wall (x -8.35), sideways across the open end 2.2 m from it,
# backwards along the aisle between the rows at y -2.8 and y -7.8, sideways across the far end
# looking at the rows' ends, and backwards to the start (39.5 m in all)
WAREHOUSE_START = (0.0, 1.55, 1.5, np.pi)
WAREHOUSE_FACING = np.pi
WAREHOUSE_LOOP = [(-6.0, 1.55, 1.5), (-6.0, -4.7, 1.5), (7.5, -4.7, 1.5), (7.5, 1.55, 1.5), (0.0, 1.55, 1.5)]

# The power plant: sideways past its 12 m high south face (x -1), 3 m off and looking at it (+x),
# 2 m up from y 4 to y -13, then back 5 m up (34 m in all)
POWERPLANT_START = (-4.0, 4.0, 2.0, 0.0)
POWERPLANT_PATH = [(-4.0, -13.0, 2.0), (-4.0, -13.0, 5.0), (-4.0, 4.0, 5.0)]
POWERPLANT_FACING = 0.0


@dataclass
class Trajectory:
    t_s: np.ndarray  # (N,)
    p_W: np.ndarray  # (N, 3)
    v_W: np.ndarray  # (N, 3)
    a_W: np.ndarray  # (N, 3)
    yaw: np.ndarray  # (N,) unwrapped
    yaw_rate: np.ndarray  # (N,)

    @property
    def duration_s(self) -> float:
        return float(self.t_s[-1])

    def length_m(self) -> float:
        return float(np.sum(np.linalg.norm(np.diff(self.p_W, axis=0), axis=1)))


def _straight(length: float, v_max: float, a_max: float, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Distance, speed and acceleration along a leg at dt: accelerate, cruise, brake (a triangle if short)."""
    v_peak = min(v_max, np.sqrt(length * a_max))
    t_ramp = v_peak / a_max
    t_cruise = (length - v_peak * t_ramp) / v_peak
    total = 2 * t_ramp + t_cruise
    t = np.arange(0.0, total + 1e-9, dt)
    s, v, a = np.zeros_like(t), np.zeros_like(t), np.zeros_like(t)
    up = t < t_ramp
    cruise = (t >= t_ramp) & (t < t_ramp + t_cruise)
    down = t >= t_ramp + t_cruise
    s[up], v[up], a[up] = 0.5 * a_max * t[up] ** 2, a_max * t[up], a_max
    s[cruise] = 0.5 * a_max * t_ramp**2 + v_peak * (t[cruise] - t_ramp)
    v[cruise] = v_peak
    td = t[down] - t_ramp - t_cruise
    s[down] = length - 0.5 * a_max * (t_ramp - td) ** 2
    v[down], a[down] = a_max * (t_ramp - td), -a_max
    return np.minimum(s, length), np.maximum(v, 0.0), a


def _turn(delta: float, yaw_rate_max: float, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Yaw change and rate of a turn by delta: (1 - cos(pi t / T)) / 2 of it, peak rate yaw_rate_max."""
    T = max(np.pi * abs(delta) / (2 * yaw_rate_max), dt)
    t = np.arange(0.0, T + 1e-9, dt)
    return delta * (1 - np.cos(np.pi * t / T)) / 2, delta * np.pi / (2 * T) * np.sin(np.pi * t / T)


def sample(
    start: Sequence[float],
    corners: Sequence[Sequence[float]],
    speed: float = 1.2,
    accel: float = 0.8,
    yaw_rate: float = 0.6,
    dt: float = 0.02,
    hold_s: float = 1.0,
    facing: float | None = None,
) -> Trajectory:
    """The path sampled every dt, ending with hold_s on the last corner."""
    p = np.array(start[:3], float)
    yaw = float(start[3])
    rows: list[tuple] = []  # t-less rows: p, v, a, yaw, yaw_rate

    def hold(seconds: float) -> None:
        for _ in range(int(round(seconds / dt))):
            rows.append((p.copy(), np.zeros(3), np.zeros(3), yaw, 0.0))

    hold(hold_s)
    for corner in corners:
        corner = np.array(corner, float)
        leg = corner - p
        length = float(np.linalg.norm(leg))
        if length < 1e-6:
            continue
        if np.linalg.norm(leg[:2]) > 1e-6:  # face the leg (or `facing`): the shortest turn there
            heading = np.arctan2(leg[1], leg[0]) if facing is None else facing
            delta = (heading - yaw + np.pi) % (2 * np.pi) - np.pi
            if abs(delta) > 1e-3:
                d_yaw, rate = _turn(delta, yaw_rate, dt)
                rows += [(p.copy(), np.zeros(3), np.zeros(3), yaw + dy, r) for dy, r in zip(d_yaw, rate)]
                yaw += delta
        s, v, a = _straight(length, speed, accel, dt)
        e = leg / length
        rows += [(p + si * e, vi * e, ai * e, yaw, 0.0) for si, vi, ai in zip(s, v, a)]
        p = corner
        hold(0.3)
    hold(hold_s)
    t = dt * np.arange(len(rows))
    return Trajectory(
        t,
        np.array([r[0] for r in rows]),
        np.array([r[1] for r in rows]),
        np.array([r[2] for r in rows]),
        np.array([r[3] for r in rows]),
        np.array([r[4] for r in rows]),
    )


def sway(trajectory: Trajectory, amplitude_rad: float, rate_rad_s: float) -> Trajectory:
    """The yaw swung by amplitude sin(rate t) over the whole flight (a camera that looks around)."""
    t = trajectory.t_s
    return replace(
        trajectory,
        yaw=trajectory.yaw + amplitude_rad * np.sin(rate_rad_s * t),
        yaw_rate=trajectory.yaw_rate + amplitude_rad * rate_rad_s * np.cos(rate_rad_s * t),
    )


@dataclass(frozen=True)
class FlightShape:
    """A flight's mean speed and mean angular rate (the magnitude of the body's rotation rate)."""

    mean_speed_m_s: float
    mean_angular_rate_deg_s: float


# The Vicon-room sequences of the EuRoC MAV dataset (Burri et al., IJRR 2016), computed from their
# Vicon ground truth (200 Hz; speeds and rotation angles over 50 ms): mean speed and mean angular rate.
EUROC_SHAPES = {
    "easy": ("V1_01_easy", FlightShape(0.41, 15.0)),
    "medium": ("V1_02_medium", FlightShape(0.91, 31.9)),
    "difficult": ("V1_03_difficult", FlightShape(0.75, 35.6)),
}
SWAY_AMPLITUDE_RAD = np.radians(30.0)


def mean_speed(trajectory: Trajectory) -> float:
    return float(np.mean(np.linalg.norm(trajectory.v_W, axis=1)))


def mean_yaw_rate_deg_s(trajectory: Trajectory) -> float:
    return float(np.degrees(np.mean(np.abs(trajectory.yaw_rate))))


def shaped_like(
    shape: FlightShape, start: Sequence[float], corners: Sequence[Sequence[float]], facing: float | None = None, accel: float = 0.8
) -> Trajectory:
    """The path at the cruise speed whose mean speed is the shape's, its yaw swung by 30 deg at the
    rate whose mean yaw rate is the shape's mean angular rate (both found by bisection)."""

    def flight(speed: float, rate: float = 0.0) -> Trajectory:
        t = sample(start, corners, speed=speed, accel=accel, facing=facing)
        return sway(t, SWAY_AMPLITUDE_RAD, rate) if rate > 0.0 else t

    def bisect(f, lo: float, hi: float, target: float) -> float:
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) < target else (lo, mid)
        return 0.5 * (lo + hi)

    speed = bisect(lambda v: mean_speed(flight(v)), 0.05, 5.0, shape.mean_speed_m_s)
    rate = bisect(lambda w: mean_yaw_rate_deg_s(flight(speed, w)), 0.0, 10.0, shape.mean_angular_rate_deg_s)
    return flight(speed, rate)


TRAJECTORY_FILE_HEADER = "# t [s], x, y, z [m], yaw [rad], vx, vy, vz [m/s], ax, ay, az [m/s^2], yaw_rate [rad/s]"


def write_trajectory_file(trajectory: Trajectory, path: Path, comment: str = "") -> None:
    rows = np.column_stack([trajectory.t_s, trajectory.p_W, trajectory.yaw, trajectory.v_W, trajectory.a_W, trajectory.yaw_rate])
    header = "\n".join(f"# {line}" for line in comment.splitlines()) + "\n" if comment else ""
    np.savetxt(path, rows, fmt="%.6f", delimiter=",", header=header + TRAJECTORY_FILE_HEADER, comments="")


def read_trajectory_file(path: Path) -> Trajectory:
    """A file written by write_trajectory_file: 12 comma-separated columns per row, times increasing."""
    try:
        rows = np.loadtxt(path, delimiter=",", comments="#", ndmin=2)
    except ValueError as e:
        raise ValueError(f"{path}: not a trajectory file ({e}); expected the columns {TRAJECTORY_FILE_HEADER[2:]}") from None
    if rows.shape[1] != 12 or len(rows) < 2:
        raise ValueError(f"{path}: {rows.shape[1]} columns in {len(rows)} rows; expected 12 columns ({TRAJECTORY_FILE_HEADER[2:]})")
    if not np.all(np.isfinite(rows)):
        raise ValueError(f"{path}: row {int(np.argmax(~np.all(np.isfinite(rows), axis=1))) + 1} has a NaN or inf")
    if np.any(np.diff(rows[:, 0]) <= 0.0):
        raise ValueError(f"{path}: the times must increase (row {int(np.argmax(np.diff(rows[:, 0]) <= 0.0)) + 2})")
    return Trajectory(rows[:, 0], rows[:, 1:4], rows[:, 5:8], rows[:, 8:11], rows[:, 4], rows[:, 11])


# The VIO flights of mav_vio_flight.launch: from the ground at the spawn point (facing as the path
# faces) up to the path's height, then the path, shaped like each EuRoC difficulty.
VIO_PLACES = {
    "warehouse": (
        (0.0, 0.0, 0.1, WAREHOUSE_FACING),
        [(0.0, 0.0, WAREHOUSE_START[2]), WAREHOUSE_START[:3]] + WAREHOUSE_LOOP,
        WAREHOUSE_FACING,
    ),
    "powerplant": (
        (POWERPLANT_START[0], POWERPLANT_START[1], 0.1, POWERPLANT_FACING),
        [POWERPLANT_START[:3]] + POWERPLANT_PATH,
        POWERPLANT_FACING,
    ),
}


def vio_flight(place: str, difficulty: str) -> Trajectory:
    start, corners, facing = VIO_PLACES[place]
    return shaped_like(EUROC_SHAPES[difficulty][1], start, corners, facing)


def write_vio_flights(folder: Path) -> list[Path]:
    """resource/vio_flights/<place>_<difficulty>.csv, every place and difficulty."""
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for place in VIO_PLACES:
        for difficulty, (sequence, shape) in EUROC_SHAPES.items():
            path = folder / f"{place}_{difficulty}.csv"
            flight = vio_flight(place, difficulty)
            comment = (
                f"mav_vio_flight.launch world_name:={place} difficulty:={difficulty}: shaped like EuRoC {sequence}\n"
                f"(mean speed {shape.mean_speed_m_s} m/s, mean angular rate {shape.mean_angular_rate_deg_s} deg/s);\n"
                f"made by rotors_gazebo.flight_paths.write_vio_flights: {flight.duration_s:.1f} s, {flight.length_m():.1f} m"
            )
            write_trajectory_file(flight, path, comment)
            written.append(path)
    return written


if __name__ == "__main__":
    import sys

    for written_path in write_vio_flights(Path(sys.argv[1])):
        print(written_path)
