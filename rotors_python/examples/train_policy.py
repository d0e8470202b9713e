#!/usr/bin/env python3
"""Trains the hover-and-waypoint policy that rl_policy_node flies in the ROS simulator
(mav_policy_example.launch): PPO (Stable-Baselines3) on 64 fireflies in one FlightBatchEnv, hover
task (reach the target from up to 0.5 m per axis away and hold it), attitude actions (roll, pitch,
yaw rate, thrust through rotors_control's roll-pitch-yawrate-thrust controller, as in the ROS
launch). With --randomize every vehicle draws its airframe at every reset from POLICY_RANDOMIZATION
(docs/batched_flight.md says where each range comes from).

It then writes the policy as plain numpy arrays (np.savez, no torch needed to run it): the actor's
layers (w0, b0, w1, b1, w2, b2; tanh between them; the action is the last layer's output clipped
to [-1, 1]; the first takes policy_tools.features of the observation: the quaternion as a rotation
matrix), the observation's clip bounds and the action's scales, and scores it in the batch on
the xacro's firefly and on one with 20 % more mass and 15 % weaker motors.
`make train-policy` installs PyTorch (the CPU build) and Stable-Baselines3 into build/rl-site and
runs it for both shipped policies.
    python train_policy.py [--randomize] [--steps 12000000] --out policy.npz"""

from __future__ import annotations

import argparse
import json
import time

import gymnasium as gym
import numpy as np
import torch
from policy_tools import HEAVY_WEAK, features, forward, score
from stable_baselines3 import PPO
from train_hover import FlightBatchVecEnv, learn, make_ppo

from rotors_sim.envs import FlightBatchEnv, hover

# mass: 10 % lighter (no sensor payload) to 30 % heavier (a payload of 30 % of the airframe; the
# firefly's thrust-to-weight then falls from 2.3 to 1.8, 1.5 with the weakest motors); motorConstant: C_T is proportional to the air
# density (book eq. 1 with C_T = c rho), which the ISO 2533 standard atmosphere puts at 0.82 to
# 1.09 of its sea-level 15 C value between 0 and 2,000 m and -10 to 40 C (one factor per rotor)
POLICY_RANDOMIZATION = {"mass": ("uniform", 0.9, 1.3), "motorConstant": ("uniform", 0.82, 1.09)}
MAX_TILT_RAD, MAX_YAW_RATE_RAD_S = 0.6, 2.0
# the training objective beside the environment's hover reward (whose cost grows linearly with the
# error, so that 5 cm cost under 0.5 % of a step's reward): a precision term exp(-|e_p|^2 / (2 s^2))
# that pays for holding the set point to centimetres, as the Lee controller does
PRECISION_BONUS, PRECISION_SCALE_M = 1.0, 0.05


def precision_reward(last_obs: np.ndarray, terminated: np.ndarray) -> np.ndarray:
    e2 = np.sum(np.asarray(last_obs[:, 0:3], dtype=np.float64) ** 2, axis=1)
    return np.where(terminated, 0.0, PRECISION_BONUS * np.exp(-e2 / (2.0 * PRECISION_SCALE_M**2)))


def export(model: PPO, envs: FlightBatchEnv, path: str, randomized: bool) -> None:
    """The actor as numpy arrays: a = clip(W2 tanh(W1 tanh(W0 f(o) + b0) + b1) + b2, -1, 1), f = features."""
    layers = [m for m in model.policy.mlp_extractor.policy_net if isinstance(m, torch.nn.Linear)]
    layers.append(model.policy.action_net)
    arrays = {}
    for i, layer in enumerate(layers):
        arrays[f"w{i}"] = layer.weight.detach().cpu().numpy().astype(np.float64)
        arrays[f"b{i}"] = layer.bias.detach().cpu().numpy().astype(np.float64)
    np.savez(
        path,
        **arrays,
        observation_high=hover.OBSERVATION_HIGH.astype(np.float64),
        max_tilt_rad=np.float64(MAX_TILT_RAD),
        max_yaw_rate_rad_s=np.float64(MAX_YAW_RATE_RAD_S),
        hover_thrust_n=np.float64(envs.hover_thrust_N),
        max_offset_m=np.float64(hover.START_OFFSET_M),
        randomized=np.float64(randomized),
    )
    add_check_arrays(path)


def add_check_arrays(path: str) -> None:
    """Adds check_observations (8 observations drawn within the bounds) and check_actions (this
    script's forward() of them) to the policy file: rotors_control's gtest runs HoverPolicy on them."""
    policy = {k: v for k, v in np.load(path).items() if not k.startswith("check_")}
    rng = np.random.default_rng(7)
    obs = rng.uniform(-1.0, 1.0, (8, len(policy["observation_high"]))) * np.minimum(policy["observation_high"], 2.0)
    obs[:, 6:10] /= np.linalg.norm(obs[:, 6:10], axis=1, keepdims=True)  # unit quaternions
    np.savez(path, **policy, check_observations=obs, check_actions=forward(policy, obs))


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=16_000_000, help="environment steps (all vehicles)")
    parser.add_argument("--envs", type=int, default=64)
    parser.add_argument("--randomize", action="store_true", help="train on POLICY_RANDOMIZATION's airframes")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", required=True, help="the policy file (.npz)")
    args = parser.parse_args()
    torch.set_num_threads(1)  # the engine's threads step the vehicles; one for the network is enough
    spec = POLICY_RANDOMIZATION if args.randomize else None
    envs = FlightBatchEnv("hover", args.envs, action_type="attitude", episode_s=5.0, sensor_seed=args.seed, randomization=spec)
    high = np.concatenate([hover.OBSERVATION_HIGH[0:6], np.ones(9), hover.OBSERVATION_HIGH[10:13]]).astype(np.float32)
    space = gym.spaces.Box(-high, high, dtype=np.float32)
    vec = FlightBatchVecEnv(envs, extra_reward=precision_reward, features=lambda o: features(o).astype(np.float32), feature_space=space)
    vec.seed(args.seed)
    model = make_ppo(vec, args.seed)
    t0 = time.perf_counter()
    curve = [(steps, mean_return) for steps, mean_return, _ in learn(model, vec, args.steps, args.envs * 128 * 8, t0)]
    wall = time.perf_counter() - t0
    export(model, envs, args.out, args.randomize)
    policy = dict(np.load(args.out))
    result = {
        "out": args.out,
        "randomized": args.randomize,
        "steps": int(model.num_timesteps),
        "wall_s": wall,
        "curve": curve,
        "batch_xacro_firefly": score(policy, None),
        "batch_heavy_weak_firefly": score(policy, HEAVY_WEAK),
    }
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
