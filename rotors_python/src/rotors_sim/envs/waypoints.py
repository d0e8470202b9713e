"""RotorS/Waypoints-v0: fly through a list of waypoints in order.

Observation (16, float32), from the odometry sensor: p - current waypoint [m] (3, +-10), p - next
waypoint [m] (3, +-10; the current one again at the last), velocity in the world frame [m/s]
(3, +-20), orientation quaternion (x, y, z, w) (4, +-1), body rates [rad/s] (3, +-50); clipped.
Action: see rotors_sim.envs.flight.
Reward per control step: 10 x (distance to the current waypoint before the step - after it)
- 0.01 |omega|, +5 for each waypoint reached (within reach_m), -10 when terminated by a crash.
Start: at rest at `start` (default (0, 0, 1)) + U(-0.2, 0.2) m per axis.
terminated: every waypoint reached (info["success"]), a contact, or 3 m away from the current waypoint.
truncated: episode_s of simulated time (default 20 s).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np

from rotors_sim.envs.flight import Flight, FlightConfig, FlightEnv, odometry_observation

OBSERVATION_HIGH = np.array([10.0] * 6 + [20.0] * 3 + [1.0] * 4 + [50.0] * 3, np.float32)
SQUARE = ((0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 1.0, 1.0), (0.0, 1.0, 1.0), (0.0, 0.0, 1.0))


class WaypointsEnv(FlightEnv):
    def __init__(
        self,
        waypoints: Sequence[Sequence[float]] = SQUARE[1:],
        start=SQUARE[0],
        mav_name: str = "firefly",
        action_type: str = "motor",
        reach_m: float = 0.3,
        episode_s: float = 20.0,
        physics_hz: float = 500.0,
        control_hz: float = 100.0,
        sensor_seed: int = 0,
    ):
        self.flight = Flight(
            FlightConfig(mav_name=mav_name, action_type=action_type, physics_hz=physics_hz, control_hz=control_hz, sensor_seed=sensor_seed)
        )
        self.waypoints = np.asarray(waypoints, dtype=np.float64).reshape(-1, 3)
        self.start = np.asarray(start, dtype=np.float64)
        self.reach_m = reach_m
        self.max_steps = int(round(episode_s / self.flight.dt))
        self.action_space = gym.spaces.Box(-1.0, 1.0, (self.flight.action_size,), np.float32)
        self.observation_space = gym.spaces.Box(-OBSERVATION_HIGH, OBSERVATION_HIGH, dtype=np.float32)
        self.index = 0
        self.steps = 0

    def _observe(self, odometry) -> np.ndarray:
        current = self.waypoints[min(self.index, len(self.waypoints) - 1)]
        following = self.waypoints[min(self.index + 1, len(self.waypoints) - 1)]
        return odometry_observation(odometry, [current, following], OBSERVATION_HIGH)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        start = self.start + self.np_random.uniform(-0.2, 0.2, 3)
        odometry = self.flight.reset(start)
        self.index, self.steps = 0, 0
        self.distance = float(np.linalg.norm(odometry.position_W - self.waypoints[0]))
        return self._observe(odometry), {"waypoint": 0}

    def end_step(self):
        odometry = self.flight.after_step()
        self.steps += 1
        distance = float(np.linalg.norm(odometry.position_W - self.waypoints[self.index]))
        reward = 10.0 * (self.distance - distance) - 0.01 * float(np.linalg.norm(odometry.angular_velocity_B))
        if distance < self.reach_m:
            reward += 5.0
            self.index += 1
            if self.index < len(self.waypoints):
                distance = float(np.linalg.norm(odometry.position_W - self.waypoints[self.index]))
        self.distance = distance
        success = self.index >= len(self.waypoints)
        collided = self.flight.collided()
        crashed = collided or (not success and distance > 3.0)
        if crashed:
            reward = -10.0
        terminated = success or crashed
        truncated = not terminated and self.steps >= self.max_steps
        info = {"waypoint": min(self.index, len(self.waypoints)), "success": success, "collided": collided, "time_s": odometry.time_s}
        return self._observe(odometry), reward, terminated, truncated, info
