"""RotorS/Hover-v0: hold a MAV at a point.

Observation (13, float32), from the odometry sensor: position error p - p_target [m] (3, within
+-5), velocity in the world frame [m/s] (3, +-20), orientation quaternion (x, y, z, w) (4, +-1),
body rates [rad/s] (3, +-50); values are clipped to these bounds.
Action: see rotors_sim.envs.flight ("motor": one per rotor, "attitude": roll, pitch, yaw rate, thrust).
Reward per control step: 1 - c / c_max with the cost c = |p - p_target| + 0.1 |v| + 0.05 |omega|
and c_max its largest value before termination (|p - p_target| < 2 sqrt(3) m, |v| <= 20 sqrt(3) m/s,
|omega| <= 50 sqrt(3) rad/s), so in [0, 1]; -10 when terminated. Every step survived pays and a crash
costs: a crash scores below any episode that lasts longer.
Start: at rest, p_target + U(-0.5, 0.5) m per axis (z at least 0.3 m), yaw U(-pi, pi).
terminated: a contact (the ground included) or |p - p_target| > 2 m on some axis.
truncated: episode_s of simulated time (default 10 s).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np

from rotors_sim._engine import hover_costs
from rotors_sim.envs.flight import Flight, FlightConfig, FlightEnv, odometry_observation

OBSERVATION_HIGH = np.array([5.0] * 3 + [20.0] * 3 + [1.0] * 4 + [50.0] * 3, np.float32)
OBSERVATION_SIZE = len(OBSERVATION_HIGH)
BOUND_M = 2.0
START_OFFSET_M = 0.5  # the start's largest offset from the target per axis
TERMINATION_REWARD = -10.0
# the cost's largest value while the episode runs: each axis of the position error under BOUND_M,
# velocity and body rates at their observation bounds
COST_MAX = float(np.sqrt(3.0) * (BOUND_M + 0.1 * OBSERVATION_HIGH[3] + 0.05 * OBSERVATION_HIGH[10]))


def hover_observation(odometry, target: np.ndarray) -> np.ndarray:
    return odometry_observation(odometry, [target], OBSERVATION_HIGH)


def hover_cost(obs: np.ndarray) -> np.ndarray:
    """c = |e_p| + 0.1 |v| + 0.05 |omega| of one observation or of rows of them (_engine.hover_costs,
    the formula the vector environment's hover_rewards reads too)."""
    o = np.asarray(obs, dtype=np.float64)
    return hover_costs(o.reshape(-1, o.shape[-1])).reshape(o.shape[:-1])


def hover_reward(obs: np.ndarray) -> np.ndarray:
    """1 - c / c_max, in [0, 1] while the episode runs."""
    return 1.0 - hover_cost(obs) / COST_MAX


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
        start = self.target + self.np_random.uniform(-START_OFFSET_M, START_OFFSET_M, 3)
        start[2] = max(start[2], 0.3)
        odometry = self.flight.reset(start, yaw=float(self.np_random.uniform(-np.pi, np.pi)))
        self.steps = 0
        return hover_observation(odometry, self.target), {"time_s": odometry.time_s}

    def end_step(self):
        obs = hover_observation(self.flight.after_step(), self.target)
        self.steps += 1
        collided = self.flight.collided()
        terminated = collided or bool(np.any(np.abs(obs[0:3]) > BOUND_M))
        reward = TERMINATION_REWARD if terminated else float(hover_reward(obs))
        truncated = not terminated and self.steps >= self.max_steps
        return obs, reward, terminated, truncated, {"time_s": self.flight.odometry.time_s, "collided": collided}
