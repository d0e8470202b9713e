"""rotors_sim.FlightBatch: many copies of one RotorS multirotor flown by one engine call.

    import rotors_sim as rs
    batch = rs.FlightBatch("firefly", count=1024, step_size=0.002, control_divisor=5)
    batch.commands[:] = [0.0, 0.0, 1.0, 0.0]     # Lee position controller: x, y, z, yaw per vehicle
    batch.step(500)                              # 1 s of every vehicle, on all cores
    positions = batch.truth()[:, 0:3]

The vehicle is the xacro the full world spawns (spawn_mav, the same arguments), read once from a
World: the same mass and inertia, the motor plugins' constants, the wind plugin, the odometry and
IMU plugins with their noise; the controllers are rotors_control's, with the yaml files of the ROS
nodes. See docs/batched_flight.md for what it simulates, what it leaves out and how it compares.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from rotors_sim import _engine
from rotors_sim._engine import SimError
from rotors_sim.controllers import load_yamls
from rotors_sim.paths import resource
from rotors_sim.world import World

COMMAND_MODES = ("rotor_speeds", "normalized_thrust", "lee_position", "roll_pitch_yawrate_thrust", "attitude_thrust", "rate_thrust")
ODOMETRY_COLUMNS = {
    "position_W": slice(0, 3),
    "orientation": slice(3, 7),
    "velocity_B": slice(7, 10),
    "angular_velocity_B": slice(10, 13),
    "stamp": 13,
}


def controller_yamls(mav_name: str, mode: str) -> list[Path]:
    """The parameter files the ROS node of `mode` loads for `mav_name` (none for raw commands)."""
    if mode == "lee_position":
        return [resource(f"lee_controller_{mav_name}.yaml"), resource(f"{mav_name}.yaml")]
    if mode in ("roll_pitch_yawrate_thrust", "attitude_thrust", "rate_thrust"):
        return [resource(f"roll_pitch_yawrate_thrust_controller_{mav_name}.yaml"), resource(f"{mav_name}.yaml")]
    return []


class FlightBatch:
    """`count` copies of the RotorS vehicle `mav_name`, commanded by `mode` (one row of `commands`
    per vehicle):

    - "lee_position": x, y, z [m], yaw [rad] for Lee's position controller (the hovering example's);
    - "roll_pitch_yawrate_thrust": roll, pitch [rad], yaw rate [rad/s], thrust [N];
    - "attitude_thrust": q (x, y, z, w), thrust [N];  "rate_thrust": body rates [rad/s], thrust [N];
    - "rotor_speeds": one speed per rotor [rad/s];  "normalized_thrust": a fraction 0..1 of each
      rotor's maximum thrust.

    The controllers answer each odometry message (every `control_divisor` physics steps of
    `step_size` s; None: the world file's step), as the ROS nodes and World.attach_controller do.
    In "lee_position" a row of NaN means no set point yet: the rotors stay stopped until the first
    (as the ROS node before its first trajectory). `controller_overrides` (one dict per vehicle)
    changes Lee's yaml values per vehicle, e.g. {"position_gain/x": 4.0}, for sweeps. `seeds` (one per vehicle) seed
    the sensor and wind noise as spawn_mav's random_seed does; `noise=False` turns it off,
    `imu=False` skips the IMU. `controller_params` replaces the controller's yaml files. `kernel`
    picks the physics' and the Lee controllers' instruction set (avx512, avx2, sse2, scalar; default
    the fastest this CPU runs; avx512 steps groups of eight vehicles, or a lone vehicle's rotors,
    eight at a time): each gives the same flight bit for bit.
    Further keywords go to the xacro (enable_wind=True, ...).
    """

    def __init__(
        self,
        mav_name: str = "firefly",
        count: int = 1,
        *,
        mode: str = "lee_position",
        world: str = "basic",
        step_size: float | None = 0.002,
        control_divisor: int = 5,
        threads: int = 0,
        seeds: Sequence[int] | None = None,
        noise: bool = True,
        imu: bool = True,
        positions: Any = None,
        yaws: Any = None,
        controller_params: Sequence[str | Path] | None = None,
        controller_overrides: Sequence[dict[str, float]] | None = None,
        kernel: str = "",
        **xacro_args: Any,
    ):
        if mode not in COMMAND_MODES:
            raise SimError(f"mode '{mode}' is not known; use one of: {', '.join(COMMAND_MODES)}")
        if int(count) < 1:
            raise SimError(f"count = {count} must be >= 1")
        count = int(count)
        seeds = [int(s) for s in (range(count) if seeds is None else seeds)]
        if len(seeds) != count:
            raise SimError(f"{len(seeds)} seeds for {count} vehicles; give one per vehicle")
        if min(seeds) < 0:
            raise SimError(f"seeds must be >= 0 (got {min(seeds)})")
        self.world = World(world, step_size=step_size)
        # the description is read from the vehicle as the full world spawns it, at rest in the air
        self.world.spawn_mav(mav_name, xyz=(0.0, 0.0, 1.0), random_seed=seeds[0], odometry_divisor=control_divisor, **xacro_args)
        self.description = self.world.engine.describe_multirotor(mav_name, "odometry_sensor1/odometry")
        self.mav_name = mav_name
        self.mode = mode
        yamls = controller_params if controller_params is not None else controller_yamls(mav_name, mode)
        numbers, others, source = load_yamls(yamls) if yamls else ({}, [], "")
        each = []
        if controller_overrides is not None:
            if mode != "lee_position" or len(controller_overrides) != count:
                raise SimError(f"controller_overrides: one dict per vehicle ({count}) for mode lee_position")
            each = [{**numbers, **{k.replace(".", "/"): float(v) for k, v in o.items()}} for o in controller_overrides]
        self._b = _engine.FlightBatch(
            self.description,
            count,
            mode,
            numbers,
            others,
            source,
            threads=threads,
            imu=imu,
            noise=noise,
            seeds=seeds,
            description_seed=seeds[0],
            numbers_each=each,
            kernel=kernel,
        )
        self.commands: np.ndarray = self._b.commands
        """Writable view of the engine's command array (count x command_columns)."""
        start = np.zeros((count, 3)) if positions is None else np.asarray(positions, dtype=float)
        if positions is None:
            start[:, 2] = 1.0
        self.reset(positions=start, yaws=yaws)
        if mode == "lee_position":
            self.commands[:, 0:3] = start
            self.commands[:, 3] = 0.0 if yaws is None else np.asarray(yaws, dtype=float)

    # --- stepping ---
    def step(self, n: int = 1) -> None:
        """n physics steps of every vehicle (threads, the GIL released). A bad command raises
        SimError naming it, and no vehicle moves."""
        self._b.step(int(n))

    def reset(self, indices: Sequence[int] | None = None, positions: Any = None, yaws: Any = None) -> None:
        """Vehicles `indices` (all by default) at rest at `positions` (k x 3, the model frame's
        origin; default (0, 0, 1)) with `yaws` [rad], their time at 0 and their noise at its seed."""
        idx = list(range(self.count)) if indices is None else [int(i) for i in indices]
        p = np.tile([0.0, 0.0, 1.0], (len(idx), 1)) if positions is None else np.asarray(positions, dtype=float)
        y = np.zeros(len(idx)) if yaws is None else np.asarray(yaws, dtype=float)
        self._b.reset(idx, np.ascontiguousarray(p), np.ascontiguousarray(y))

    # --- each vehicle's airframe ---
    @property
    def nominal_airframe(self) -> dict[str, Any]:
        """The xacro's airframe: {"mass": kg, "inertia": 3 x 3 kg m^2 (about the CoG, body frame),
        "cog": the CoG in the model frame [m], and per rotor (arrays by motor number) "motorConstant",
        "momentConstant", "rotorDragCoefficient", "rollingMomentCoefficient", "timeConstantUp",
        "timeConstantDown", "maxRotVelocity"}, in the SDF parameters' units."""
        return self._b.nominal_airframe

    def airframe(self, i: int) -> dict[str, Any]:
        """Vehicle i's airframe (nominal_airframe's keys)."""
        return self._b.airframe(int(i))

    def set_airframe(self, i: int, **values: Any) -> None:
        """Vehicle i flies the nominal airframe with `values` in place (nominal_airframe's keys, any
        subset), from its next step: set it with a reset. Checked as the plugins check their SDF
        (a bad value raises SimError naming the vehicle and the value, and nothing changes). The
        controllers keep the yaml's vehicle: they do not know the airframe they fly."""
        self._b.set_airframe(int(i), values)

    def set_airframes(self, indices: Sequence[int], **values: Any) -> None:
        """Vehicle indices[j] flies the nominal airframe with row j of each of `values` in place
        (set_airframe's keys, each an array with one row per vehicle), in one call; checked as
        set_airframe checks, and on a bad value no vehicle changes."""
        self._b.set_airframes([int(i) for i in indices], values)

    def set_seed(self, i: int, seed: int) -> None:
        """Vehicle i's random_seed (its sensor and wind noise) from its next reset on."""
        if int(seed) < 0:
            raise SimError(f"seed = {seed} must be >= 0")
        self._b.set_seed(int(i), int(seed))

    def set_seeds(self, indices: Sequence[int], seeds: Sequence[int]) -> None:
        """set_seed for each of `indices` in one call (SimError on a bad index or seed, and none changes)."""
        self._b.set_seeds([int(i) for i in indices], [int(s) for s in seeds])

    # --- obstacles and the depth camera ---
    def set_obstacles(self, field: _engine.ObstacleField | None) -> None:
        """Vehicle i flies among environment i's obstacles of `field` (rotors_sim.clutter makes
        them; None: none). After every physics step `collided[i]` becomes True when the vehicle's
        sphere (collision_radius about its CoG, holding its rotors) touches one, until its reset.
        The batch does not bounce a vehicle off an obstacle: a collision ends an episode."""
        self._b.set_obstacles(field)

    @property
    def collided(self) -> np.ndarray:
        """Per vehicle: it touched an obstacle since its reset (a copy)."""
        return self._b.collided[:, 0].astype(bool)

    @property
    def collision_radius(self) -> float:
        """The radius [m] of the sphere about the CoG that holds every visual and collision."""
        return self._b.collision_radius

    def set_depth_camera(self, **params: Any) -> None:
        """A depth camera on every vehicle, looking along the model frame's x axis: "width",
        "height" [px] (64 x 48), "horizontal_fov", "vertical_fov" [rad] (the project's D435: 1.59174
        and 1.04724), "min_range", "max_range" [m] (0.195, 10), "xyz" (its place in the model frame),
        "noise" (the D435's depth noise, True). Its noise is seeded per vehicle at each reset."""
        self._b.set_depth_camera(dict(params))

    @property
    def depth_camera(self) -> dict[str, Any] | None:
        return self._b.depth_camera

    def render_depth(self, indices: Sequence[int] | None = None) -> np.ndarray:
        """The depth images now of vehicles `indices` (all by default; k x H x W float32, depth along
        the optical axis [m], NaN outside the camera's range): rays cast against each vehicle's
        obstacles and the ground z = 0."""
        return self._b.render_depth(None if indices is None else [int(i) for i in indices])

    def set_range_rays(self, dirs: Any, *, xyz: Any = (0.0, 0.0, 0.0), min_range: float = 0.0, max_range: float = 10.0) -> None:
        """Range rays on every vehicle (a rangefinder's beam, a ring of them): `dirs` (k x 3, the
        model frame; normalised here) from `xyz`, each reading the distance to the first obstacle or
        ground point along it, inf outside [min_range, max_range] (no return); None removes them."""
        self._b.set_range_rays(
            None if dirs is None else np.asarray(dirs, float), np.asarray(xyz, float), float(min_range), float(max_range)
        )

    def cast_ranges(self) -> np.ndarray:
        """Every vehicle's range per ray now (count x k [m]; inf: no return)."""
        return self._b.cast_ranges()

    # --- what it holds ---
    @property
    def count(self) -> int:
        return self._b.count

    @property
    def rotor_count(self) -> int:
        return self._b.rotor_count

    @property
    def step_size(self) -> float:
        return self._b.step_size

    @property
    def threads(self) -> int:
        return self._b.threads

    @property
    def kernel(self) -> str:
        """The instruction set the physics steps with: avx512, avx2, sse2 or scalar (the same bits)."""
        return self._b.kernel

    @property
    def odometry(self) -> np.ndarray:
        """The last odometry message of each vehicle (read-only view, count x 14): position_W (0:3),
        orientation x, y, z, w (3:7), velocity_B (7:10), angular_velocity_B (10:13), stamp [s] (13)."""
        return self._b.odometry

    @property
    def odometry_count(self) -> np.ndarray:
        return self._b.odometry_count[:, 0]

    @property
    def imu(self) -> np.ndarray:
        """The last IMU sample (count x 6): angular velocity [rad/s], specific force [m/s^2], IMU frame."""
        return self._b.imu

    @property
    def rotor_speeds(self) -> np.ndarray:
        """Signed rotor speeds [rad/s] (count x rotors), as RotorS publishes on motor_speed (a copy)."""
        return self._b.rotor_speeds.copy()

    @property
    def in_contact(self) -> np.ndarray:
        return self._b.in_contact[:, 0].astype(bool)

    @property
    def time(self) -> np.ndarray:
        """Sim time of each vehicle since its reset [s]."""
        return self._b.steps[:, 0] * self._b.step_size

    def truth(self) -> np.ndarray:
        """Ground truth of the model frame (count x 13): position_W, orientation (x, y, z, w),
        velocity_W, angular_velocity_B (a copy: computed from the state at this call)."""
        return self._b.truth().copy()

    @property
    def left_out(self) -> list[str]:
        """The vehicle's plugins that only measure and that the batch does not simulate."""
        return list(self.description.left_out)

    def memory(self) -> dict[str, int]:
        """Bytes per vehicle: the state arrays, the controller objects and the noise models."""
        return {
            "state": self._b.state_bytes_per_vehicle,
            "controller": self._b.controller_bytes_per_vehicle,
            "noise": self._b.noise_bytes_per_vehicle,
        }
