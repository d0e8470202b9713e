#!/usr/bin/env python3
"""Trains the hover-and-waypoint policy that rl_policy_node flies in the ROS simulator
(mav_policy_example.launch): PPO (Stable-Baselines3) on 64 fireflies in one FlightBatchEnv, hover
task (reach the target from up to 0.5 m per axis away and hold it), attitude actions (roll, pitch,
yaw rate, thrust through rotors_control's roll-pitch-yawrate-thrust controller, as in the ROS
launch). With --randomize every vehicle draws its airframe at every reset from POLICY_RANDOMIZATION
(docs/batched_flight.md says where each range comes from).

It then writes the policy as plain numpy arrays (np.savez, no torch needed to run it): the actor's
layers (w0, b0, w1, b1, w2, b2; tanh between them; the action is the last layer's output clipped
to [-1, 1]), the observation's clip bounds and the action's scales, and scores it in the batch on
the xacro's firefly and on one with 20 % more mass and 15 % weaker motors.
`make train-policy` installs PyTorch (the CPU build) and Stable-Baselines3 into build/rl-site and
runs it for both shipped policies.
    python train_policy.py [--randomize] [--steps 12000000] --out policy.npz"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
import torch
from stable_baselines3 import PPO

from rotors_sim.envs import FlightBatchEnv
from rotors_sim.envs import hover
from train_hover import FlightBatchVecEnv

# mass: 10 % lighter (no sensor payload) to 30 % heavier (a payload of 30 % of the airframe; the
# firefly's thrust-to-weight then falls from 2.3 to 1.8, 1.5 with the weakest motors); motorConstant: C_T is proportional to the air
# density (book eq. 1 with C_T = c rho), which the ISO 2533 standard atmosphere puts at 0.82 to
# 1.09 of its sea-level 15 C value between 0 and 2,000 m and -10 to 40 C (one factor per rotor)
POLICY_RANDOMIZATION = {"mass": ("uniform", 0.9, 1.3), "motorConstant": ("uniform", 0.82, 1.09)}
# the airframe the docs score: 20 % more mass, 15 % weaker motors (mass_scale:=1.2 motor_constant_scale:=0.85)
HEAVY_WEAK = {"mass": ("fixed", 1.2), "motorConstant": ("fixed", 0.85)}
MAX_TILT_RAD, MAX_YAW_RATE_RAD_S = 0.6, 2.0


def export(model: PPO, envs: FlightBatchEnv, path: str, randomized: bool) -> None:
    """The actor as numpy arrays: a = clip(W2 tanh(W1 tanh(W0 o + b0) + b1) + b2, -1, 1)."""
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
        randomized=np.float64(randomized),
    )
    add_check_arrays(path)


def add_check_arrays(path: str) -> None:
    """Adds check_observations (8 observations drawn within the bounds) and check_actions (this
    script's forward() of them) to the policy file: rotors_control's gtest runs HoverPolicy on them."""
    policy = {k: v for k, v in np.load(path).items() if not k.startswith("check_")}
    rng = np.random.default_rng(7)
    obs = rng.uniform(-1.0, 1.0, (8, len(policy["observation_high"]))) * np.minimum(policy["observation_high"], 2.0)
    np.savez(path, **policy, check_observations=obs, check_actions=forward(policy, obs))


def forward(policy: dict, obs: np.ndarray) -> np.ndarray:
    """The exported policy on rows of observations (what rl_policy_node computes)."""
    h = obs
    n = sum(1 for k in policy if k[0] == "w" and k[1:].isdigit())
    for i in range(n):
        h = h @ policy[f"w{i}"].T + policy[f"b{i}"]
        if i < n - 1:
            h = np.tanh(h)
    return np.clip(h, -1.0, 1.0)


def score(policy: dict, spec: dict | None, seconds: float = 10.0, vehicles: int = 16) -> dict:
    """Position RMS and final error of the exported policy over `seconds` from the hover starts."""
    envs = FlightBatchEnv(
        "hover", vehicles, action_type="attitude", episode_s=seconds + 1.0, autoreset=False, randomization=spec, sensor_seed=100
    )
    obs, _ = envs.reset(seed=1000)
    errors, alive = [], np.ones(vehicles, dtype=bool)
    for _ in range(int(round(seconds / envs.dt))):
        obs, _, terminated, _, _ = envs.step(forward(policy, obs.astype(np.float64)))
        alive &= ~terminated
        if terminated.any():
            break
        errors.append(np.linalg.norm(obs[:, 0:3], axis=1))
    e = np.array(errors)
    settled = e[len(e) // 2 :]
    return {
        "crashed": int((~alive).sum()),
        "rms_m": float(np.sqrt(np.mean(e**2))),
        "rms_second_half_m": float(np.sqrt(np.mean(settled**2))),
        "final_max_m": float(e[-1].max()),
    }


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=12_000_000, help="environment steps (all vehicles)")
    parser.add_argument("--envs", type=int, default=64)
    parser.add_argument("--randomize", action="store_true", help="train on POLICY_RANDOMIZATION's airframes")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", required=True, help="the policy file (.npz)")
    args = parser.parse_args()
    torch.set_num_threads(1)  # the engine's threads step the vehicles; one for the network is enough
    spec = POLICY_RANDOMIZATION if args.randomize else None
    envs = FlightBatchEnv("hover", args.envs, action_type="attitude", episode_s=5.0, sensor_seed=args.seed, randomization=spec)
    vec = FlightBatchVecEnv(envs)
    vec.seed(args.seed)
    model = PPO(
        "MlpPolicy",
        vec,
        n_steps=128,
        batch_size=2048,
        n_epochs=5,
        learning_rate=3e-4,
        gamma=0.99,
        policy_kwargs={"net_arch": [64, 64]},
        seed=args.seed,
        verbose=0,
    )
    t0 = time.perf_counter()
    curve = []
    chunk = args.envs * 128 * 8
    while model.num_timesteps < args.steps:
        model.learn(chunk, reset_num_timesteps=False)
        recent = vec.finished[-200:]
        if recent:
            curve.append((model.num_timesteps, float(np.mean([r for r, _ in recent]))))
            print(f"{model.num_timesteps:>10,d} steps, {time.perf_counter() - t0:6.0f} s: mean return {curve[-1][1]:7.1f}", flush=True)
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
