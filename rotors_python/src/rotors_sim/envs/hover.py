"""RotorS/Hover-v0: hold a MAV at a point.

Observation (13, float32), from the odometry sensor: position error p - p_target [m] (3, within
+-5), velocity in the world frame [m/s] (3, +-20), orientation quaternion (x, y, z, w) (4, +-1),
body rates [rad/s] (3, +-50); values are clipped to these bounds.
Action: see rotors_sim.envs.flight ("motor": one per rotor, "attitude": roll, pitch, yaw rate, thrust).
Reward per control step: -|p - p_target| - 0.1 |v| - 0.05 |omega|, and -10 when terminated.
Start: at rest, p_target + U(-0.5, 0.5) m per axis (z at least 0.3 m), yaw U(-pi, pi).
terminated: a contact (the ground included) or |p - p_target| > 2 m on some axis.
truncated: episode_s of simulated time (default 10 s).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np

from rotors_sim.envs.flight import Flight, FlightConfig, FlightEnv, rotate

OBSERVATION_HIGH = np.array([5.0] * 3 + [20.0] * 3 + [1.0] * 4 + [50.0] * 3, np.float32)
OBSERVATION_SIZE = len(OBSERVATION_HIGH)
BOUND_M = 2.0
TERMINATION_REWARD = -10.0


def hover_observation(odometry, target: np.ndarray) -> np.ndarray:
    v_W = rotate(odometry.orientation, odometry.velocity_B)
    obs = np.concatenate([odometry.position_W - target, v_W, odometry.orientation, odometry.angular_velocity_B])
    return np.clip(obs, -OBSERVATION_HIGH, OBSERVATION_HIGH).astype(np.float32)


def hover_reward(obs: np.ndarray) -> float:
    return float(-np.linalg.norm(obs[0:3]) - 0.1 * np.linalg.norm(obs[3:6]) - 0.05 * np.linalg.norm(obs[10:13]))


class HoverEnv(FlightEnv):
    def __init__(
        self,
        mav_name: str = "firefly",
        action_type: str = "motor",
        target=(0.0, 0.0, 1.0),
        episode_s: float = 10.0,
        physics_hz: float = 500.0,
        control_hz: float = 100.0,
        sensor_seed: int = 0,
    ):
        self.flight = Flight(
            FlightConfig(mav_name=mav_name, action_type=action_type, physics_hz=physics_hz, control_hz=control_hz, sensor_seed=sensor_seed)
        )
        self.target = np.asarray(target, dtype=np.float64)
        self.max_steps = int(round(episode_s / self.flight.dt))
        self.action_space = gym.spaces.Box(-1.0, 1.0, (self.flight.action_size,), np.float32)
        self.observation_space = gym.spaces.Box(-OBSERVATION_HIGH, OBSERVATION_HIGH, dtype=np.float32)
        self.steps = 0

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        start = self.target + self.np_random.uniform(-0.5, 0.5, 3)
        start[2] = max(start[2], 0.3)
        odometry = self.flight.reset(start, yaw=float(self.np_random.uniform(-np.pi, np.pi)))
        self.steps = 0
        return hover_observation(odometry, self.target), {"time_s": odometry.time_s}

    def end_step(self):
        obs = hover_observation(self.flight.after_step(), self.target)
        self.steps += 1
        collided = self.flight.collided()
        terminated = collided or bool(np.any(np.abs(obs[0:3]) > BOUND_M))
        reward = TERMINATION_REWARD if terminated else hover_reward(obs)
        truncated = not terminated and self.steps >= self.max_steps
        return obs, reward, terminated, truncated, {"time_s": self.flight.odometry.time_s, "collided": collided}
