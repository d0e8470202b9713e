#!/usr/bin/env python3
"""The Gymnasium loop on RotorS/Hover-v0, nothing trained: a random policy and a scripted one (the
Lee controller's rotor speeds as the motor action), three episodes each, then the vector
environment over 16 worlds with random actions. Prints returns and episode lengths.
    python gym_loop.py"""

import time

import gymnasium as gym
import numpy as np

import rotors_sim as rs
import rotors_sim.envs  # noqa: F401  (registers the environments)
from rotors_sim.envs import BatchedEnv, HoverEnv


def yaw_of(obs) -> float:
    return float(2.0 * np.arctan2(obs[8], obs[9]))  # the quaternion's z and w (level start)


def episode(env, policy, seed: int, on_reset=lambda obs: None) -> tuple:
    obs, _ = env.reset(seed=seed)
    on_reset(obs)
    total, steps = 0.0, 0
    while True:
        obs, reward, terminated, truncated, info = env.step(policy(env, obs))
        total, steps = total + reward, steps + 1
        if terminated or truncated:
            return total, steps, "crashed" if terminated else "time up"


def main() -> int:
    env = gym.make("RotorS/Hover-v0", action_type="motor").unwrapped
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point(env.target)
    policies = {
        "random": lambda e, obs: e.action_space.sample(),
        "scripted (Lee)": lambda e, obs: 2.0 * lee.rotor_speeds(e.flight.odometry) / e.flight.max_rot_velocity - 1.0,
    }
    # the scripted policy holds the heading it starts with (Lee's attitude error is weak near a
    # half turn: a set point 180 deg away from a random start yaw turns too slowly to hold position)
    keep_heading = {"scripted (Lee)": lambda obs: lee.set_point(env.target, yaw=yaw_of(obs))}
    for name, policy in policies.items():
        for seed in range(3):
            total, steps, end = episode(env, policy, seed, keep_heading.get(name, lambda obs: None))
            print(f"{name:15s} seed {seed}: return {total:8.1f} over {steps:4d} steps ({end})")
    envs = BatchedEnv(lambda i: HoverEnv(sensor_seed=i), num_envs=16)
    envs.reset(seed=0)
    t0 = time.perf_counter()
    ended = 0
    for _ in range(500):
        _, _, terminated, truncated, _ = envs.step(envs.action_space.sample())
        ended += int(np.sum(terminated | truncated))
    wall = time.perf_counter() - t0
    print(
        f"vector env, 16 worlds, 500 steps of 10 ms: {ended} episodes ended, "
        f"{16 * 500 * 0.01 / wall:.0f} drone-s per wall second (random actions, Python in the loop)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
