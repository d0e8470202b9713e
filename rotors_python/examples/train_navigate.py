#!/usr/bin/env python3
"""Trains a policy for RotorS/NavigateClutter-v0 with Stable-Baselines3's PPO: 64 fireflies, each
through its own seeded course of clutter, seeing its 64 x 48 depth image (min-pooled to 16 x 12:
the nearest depth of each 4 x 4 block) and its state, acting at the camera's 30 Hz. Plots the mean
episode return and the share of courses that end at the goal against the environment steps, beside
random actions and the scripted free-direction baseline on the same evaluation courses, and prints
the three on 100 courses no training episode used (seeds 0..99; training courses come from seed
10,000 on). `make train-navigate` installs PyTorch (CPU) and Stable-Baselines3 into build/rl-site.
    python train_navigate.py [--steps 3000000] [--plot navigate_training.png]"""

import argparse
import json
import time

import matplotlib

matplotlib.use("Agg")
import gymnasium as gym  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from train_hover import FlightBatchVecEnv, learn, make_ppo  # noqa: E402

from rotors_sim.envs.navigate import FreeDirectionBaseline, NavigateClutterEnv, fly_courses  # noqa: E402

POOL = 4  # depth pixels per pooled cell along each axis
STATE_SCALE = np.array([20.0, 20.0, 5.0, 2.0, 2.0, 2.0, 1.0, 1.0, 1.0, 1.0], dtype=np.float32)


def features(obs: dict) -> np.ndarray:
    """What the policy sees: the depth image's 4 x 4 blocks' nearest depth (0..1) and the state scaled to about 1."""
    depth = obs["depth"][:, 0]
    n, h, w = depth.shape
    pooled = depth.reshape(n, h // POOL, POOL, w // POOL, POOL).min(axis=(2, 4)).reshape(n, -1)
    return np.hstack([pooled, obs["state"] / STATE_SCALE]).astype(np.float32)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=3_000_000, help="environment steps (all vehicles)")
    parser.add_argument("--envs", type=int, default=64)
    parser.add_argument("--plot", default="navigate_training.png")
    parser.add_argument("--seed", type=int, default=10_000)
    args = parser.parse_args()
    torch.set_num_threads(1)  # the engine's threads step the vehicles and cast the rays
    envs = NavigateClutterEnv(args.envs, sensor_seed=args.seed)
    h, w = envs.single_observation_space["depth"].shape[1:]
    space = gym.spaces.Box(-np.inf, np.inf, ((h // POOL) * (w // POOL) + len(STATE_SCALE),), np.float32)
    vec = FlightBatchVecEnv(envs, features=features, feature_space=space)
    vec.seed(args.seed)
    model = make_ppo(vec, 0, net_arch=(128, 128))
    evaluation = NavigateClutterEnv(100, autoreset=False, step_after_end=True)
    rng = np.random.default_rng(0)
    reference = {
        "random actions": fly_courses(evaluation, lambda obs: rng.uniform(-1, 1, (100, 4))),
        "free-direction baseline": fly_courses(evaluation, FreeDirectionBaseline(evaluation)),
    }

    def policy(obs):
        return model.predict(features(obs), deterministic=True)[0]

    t0 = time.perf_counter()
    points = learn(model, vec, args.steps, args.envs * 128 * 8, t0)  # (steps, mean return, mean length)
    wall = time.perf_counter() - t0
    trained = fly_courses(evaluation, policy)
    print(json.dumps({"steps": int(model.num_timesteps), "wall_s": wall, "evaluation_seeds_0_99": {"policy": trained, **reference}}))
    steps, returns, _ = np.array(points).T
    fig, ax = plt.subplots(figsize=(7.5, 3.8))
    ax.plot(steps, returns, color="tab:blue", label="PPO policy (mean return of the last 200 training episodes)")
    ax.set_xlabel(f"environment steps ({args.envs} fireflies, 30 Hz)")
    for (name, r), colour in zip(reference.items(), ("tab:red", "tab:green")):
        ax.axhline(r["mean_return"], color=colour, linestyle="--", label=f"{name} (mean return, held-out courses)")
    ax.set_ylabel("mean episode return")
    ax.legend(loc="lower right", fontsize=8)
    note = "; ".join(f"{k}: {v['goal']} %" for k, v in {"policy": trained, **reference}.items())
    ax.set_title(f"PPO on NavigateClutter-v0, {wall / 60:.0f} min on 2 cores\ngoal reached on 100 held-out courses: {note}", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
