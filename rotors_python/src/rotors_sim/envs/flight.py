"""One world with one MAV, stepped at the control rate: the part every environment shares.

Actions (both in [-1, 1], symmetric, as learning libraries expect):
  "motor":    one value per rotor, omega_i = (a_i + 1) / 2 * max_rot_velocity   [rad/s]
  "attitude": (roll, pitch, yaw rate, thrust): roll, pitch = a * max_tilt [rad], yaw rate =
              a * max_yaw_rate [rad/s], thrust = (a + 1) * m g [N] (a = 0: hover), flown by the
              roll-pitch-yawrate-thrust controller of rotors_control with the vehicle's yaml.
Observations come from the vehicle's odometry sensor (the noisy one the controllers use).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import gymnasium as gym
import numpy as np

from rotors_sim import _engine
from rotors_sim._engine import SimError
from rotors_sim.controllers import AttitudeLevelController, LeePositionController
from rotors_sim.paths import resource
from rotors_sim.world import Odometry, World

ACTION_TYPES = ("motor", "attitude")


def odometry_observation(odometry: Odometry, origins: Sequence[np.ndarray], high: np.ndarray) -> np.ndarray:
    """One odometry reading as the vector environments observe theirs (rotors_sim._engine.
    odometry_observations for one row): p_W - origin for each origin, velocity_W = R(q) velocity_B,
    q (x, y, z, w), angular_velocity_B, clipped to [-high, high], float32."""
    row = np.concatenate(
        [odometry.position_W, odometry.orientation, odometry.velocity_B, odometry.angular_velocity_B, [odometry.time_s]]
    ).reshape(1, 14)
    bound = np.asarray(high, dtype=np.float64)
    return _engine.odometry_observations(row, [np.asarray(o, dtype=np.float64) for o in origins], -bound, bound)[0]


@dataclass
class FlightConfig:
    mav_name: str = "firefly"
    action_type: str = "motor"
    world: str = "basic"
    physics_hz: float = 500.0  # the world's step is 1 / physics_hz
    control_hz: float = 100.0
    sensor_seed: int = 0  # seed of every sensor noise of the vehicle (xacro random_seed)
    max_tilt_rad: float = 0.6
    max_yaw_rate_rad_s: float = 2.0


class Flight:
    def __init__(self, config: FlightConfig):
        if config.action_type not in ACTION_TYPES:
            raise SimError(f"action_type '{config.action_type}' unknown (use one of: {', '.join(ACTION_TYPES)})")
        self.config = config
        self.world = World(config.world, step_size=1.0 / config.physics_hz)
        self.ns = config.mav_name
        self.substeps = max(1, round(1.0 / config.control_hz / self.world.step_size))
        # the odometry sensor publishes at the control rate
        self.world.spawn_mav(config.mav_name, xyz=(0.0, 0.0, 0.1), random_seed=config.sensor_seed, odometry_divisor=self.substeps)
        self.world.listen([f"/{self.ns}/odometry_sensor1/odometry"])
        self.attitude: AttitudeLevelController | None = None
        if config.action_type == "attitude":
            gains = resource(f"roll_pitch_yawrate_thrust_controller_{config.mav_name}.yaml")
            if not gains.exists():
                raise SimError(
                    f"attitude actions need {gains.name}, which {config.mav_name} does not have "
                    "(RotorS ships none); use action_type='motor'"
                )
            self.attitude = AttitudeLevelController.for_mav(config.mav_name)
        vehicle = (self.attitude or LeePositionController.for_mav(config.mav_name)).vehicle
        self.rotor_count = len(vehicle["rotors"])
        limits = [r["max_rot_velocity_rad_s"] for r in vehicle["rotors"]]
        if not all(limit > 0 for limit in limits):
            raise SimError(f"{config.mav_name}.yaml: every rotor needs max_rot_velocity for the motor action space")
        self.max_rot_velocity = np.array(limits)
        self.hover_thrust_N = vehicle["mass_kg"] * vehicle["gravity_m_s2"]
        self.action_size = self.rotor_count if config.action_type == "motor" else 4
        self.odometry: Odometry | None = None

    @property
    def dt(self) -> float:
        return self.substeps * self.world.step_size

    def reset(self, position: np.ndarray, yaw: float = 0.0) -> Odometry:
        self.world.reset()
        q = np.array([0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2)])
        self.world.set_model_state(self.ns, position, q)
        self.world.step(1)  # the sensors sample the new state
        self.odometry = self._read()
        return self.odometry

    def rotor_command(self, action: np.ndarray) -> np.ndarray:
        """Rotor speeds [rad/s] for a normalized action (checked: shape, finite)."""
        a = np.asarray(action, dtype=np.float64)
        if a.shape != (self.action_size,):
            raise SimError(
                f"action has shape {a.shape}, the '{self.config.action_type}' action space of " f"{self.ns} needs ({self.action_size},)"
            )
        if not np.all(np.isfinite(a)):
            raise SimError(f"action {a.tolist()} has NaN or inf")
        a = np.clip(a, -1.0, 1.0)
        if self.config.action_type == "motor":
            return (a + 1.0) / 2.0 * self.max_rot_velocity
        self.attitude.set_roll_pitch_yawrate_thrust(
            a[0] * self.config.max_tilt_rad,
            a[1] * self.config.max_tilt_rad,
            a[2] * self.config.max_yaw_rate_rad_s,
            (a[3] + 1.0) * self.hover_thrust_N,
        )
        return np.clip(self.attitude.rotor_speeds(self.odometry), 0.0, self.max_rot_velocity)

    def apply(self, action: np.ndarray) -> None:
        self.world.set_motor_speeds(self.ns, self.rotor_command(action))

    def after_step(self) -> Odometry:
        self.odometry = self._read()
        return self.odometry

    def collided(self) -> bool:
        return self.world.in_contact(self.ns)

    def _read(self) -> Odometry:
        odometry = self.world.odometry(self.ns)
        if odometry is None:
            raise SimError(f"no odometry from /{self.ns}/odometry_sensor1/odometry yet")
        return odometry


class FlightEnv(gym.Env):
    """What the environments share: an action goes to the motors, the world steps one control
    period, the subclass's end_step() observes and scores. The vector environment calls
    begin_step() and end_step() itself around one step of every world."""

    metadata = {"render_modes": []}
    flight: Flight

    def step(self, action):
        self.begin_step(action)
        self.flight.world.step(self.flight.substeps)
        return self.end_step()

    def begin_step(self, action) -> None:
        self.flight.apply(action)

    def end_step(self):
        raise NotImplementedError
