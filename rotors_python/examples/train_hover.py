#!/usr/bin/env python3
"""Trains a hovering policy with Stable-Baselines3's PPO on the batched flight engine: 64 fireflies
in one FlightBatchEnv (hover task, attitude actions: roll, pitch, yaw rate, thrust through
rotors_control's roll-pitch-yawrate-thrust controller), and plots the mean episode return against
the environment steps. `make train-example` installs PyTorch (the CPU build) and Stable-Baselines3
into build/rl-site and runs it.
    python train_hover.py [--steps 8000000] [--plot docs/hover_training.png]"""

import argparse
import json
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.vec_env import VecEnv  # noqa: E402

from rotors_sim.envs import FlightBatchEnv  # noqa: E402


def one_row(obs):
    """One environment's observation as a batch of one (an array's row, or a dict of them)."""
    return {k: np.asarray(v)[None] for k, v in obs.items()} if isinstance(obs, dict) else np.asarray(obs)[None, :]


class FlightBatchVecEnv(VecEnv):
    """FlightBatchEnv (or NavigateClutterEnv) as Stable-Baselines3's VecEnv: both reset an ended
    episode in the same step; SB3 wants the last observation in info["terminal_observation"]."""

    def __init__(self, envs: FlightBatchEnv, extra_reward=None, features=None, feature_space=None):
        self.envs = envs
        # extra_reward(last_obs, terminated) -> a reward added to the environment's (a training
        # objective of its own, e.g. train_policy.py's precision term); last_obs is the step's
        # observation before any autoreset. features(obs) -> what the policy sees (feature_space),
        # e.g. train_policy.py's rotation matrix in place of the quaternion
        self.extra_reward = extra_reward
        self.features = features if features is not None else (lambda obs: obs)
        space = feature_space if feature_space is not None else envs.single_observation_space
        super().__init__(envs.num_envs, space, envs.single_action_space)
        self._actions = None
        self.returns = np.zeros(envs.num_envs)
        self.lengths = np.zeros(envs.num_envs, dtype=int)
        self.finished: list[tuple[float, int]] = []  # (return, length) of each episode that ended

    def reset(self):
        obs, _ = self.envs.reset(seed=self._seeds[0] if self._seeds and self._seeds[0] is not None else None)
        self._seeds = []
        return self.features(obs)

    def step_async(self, actions):
        self._actions = actions

    def step_wait(self):
        obs, reward, terminated, truncated, info = self.envs.step(self._actions)
        done = terminated | truncated
        if self.extra_reward is not None:
            last = obs.copy()
            for i in np.flatnonzero(done):
                last[i] = info["final_obs"][i]
            reward = reward + self.extra_reward(last, terminated)
        self.returns += reward
        self.lengths += 1
        infos = [{} for _ in range(self.num_envs)]
        for i in np.flatnonzero(done):
            infos[i] = {
                "terminal_observation": self.features(one_row(info["final_obs"][i]))[0],
                "TimeLimit.truncated": bool(truncated[i]),
                "episode": {"r": float(self.returns[i]), "l": int(self.lengths[i])},
            }
            self.finished.append((float(self.returns[i]), int(self.lengths[i])))
            self.returns[i], self.lengths[i] = 0.0, 0
        return self.features(obs), reward.astype(np.float32), done, infos

    def close(self):
        self.envs.close()

    def get_attr(self, attr_name, indices=None):
        return [getattr(self.envs, attr_name)] * len(self._get_indices(indices))

    def set_attr(self, attr_name, value, indices=None):
        setattr(self.envs, attr_name, value)

    def env_method(self, method_name, *args, indices=None, **kwargs):
        raise NotImplementedError("FlightBatchVecEnv has no per-environment methods")

    def env_is_wrapped(self, wrapper_class, indices=None):
        return [False] * len(self._get_indices(indices))


def make_ppo(vec: VecEnv, seed: int, net_arch: tuple[int, ...] = (64, 64)) -> PPO:
    """PPO as the examples train it: 128 steps per vehicle per update, batches of 2,048, 5 epochs,
    tanh networks of `net_arch` (64 x 64) for the actor and the critic."""
    return PPO(
        "MlpPolicy",
        vec,
        n_steps=128,
        batch_size=2048,
        n_epochs=5,
        learning_rate=3e-4,
        gamma=0.99,
        policy_kwargs={"net_arch": list(net_arch)},
        seed=seed,
        verbose=0,
    )


def learn(model: PPO, vec: FlightBatchVecEnv, steps: int, chunk: int, t0: float) -> list[tuple[int, float, float]]:
    """Trains in chunks of `chunk` environment steps up to `steps`; after each, (steps so far, mean
    return, mean length) of the last 200 episodes, also printed."""
    points = []
    while model.num_timesteps < steps:
        model.learn(chunk, reset_num_timesteps=False)
        recent = vec.finished[-200:]
        if recent:
            points.append((model.num_timesteps, float(np.mean([r for r, _ in recent])), float(np.mean([n for _, n in recent]))))
            print(
                f"{model.num_timesteps:>10,d} steps, {time.perf_counter() - t0:6.0f} s: mean return "
                f"{points[-1][1]:7.1f}, mean length {points[-1][2]:5.1f} steps",
                flush=True,
            )
    return points


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=8_000_000, help="environment steps (all vehicles)")
    parser.add_argument("--envs", type=int, default=64)
    parser.add_argument("--plot", default="hover_training.png")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    torch.set_num_threads(1)  # the engine's threads step the vehicles; one for the network is enough
    envs = FlightBatchEnv("hover", args.envs, action_type="attitude", episode_s=3.0, sensor_seed=args.seed)
    vec = FlightBatchVecEnv(envs)
    vec.seed(args.seed)
    model = make_ppo(vec, args.seed)
    t0 = time.perf_counter()
    points = learn(model, vec, args.steps, args.envs * 128 * 4, t0)
    wall = time.perf_counter() - t0
    steps, returns, lengths = np.array(points).T
    fig, ax = plt.subplots(figsize=(7, 3.6))
    ax.plot(steps, returns, color="tab:blue")
    ax.set_xlabel("environment steps (64 fireflies, 100 Hz control)")
    ax.set_ylabel("mean episode return", color="tab:blue")
    ax2 = ax.twinx()
    ax2.plot(steps, lengths / 100.0, color="tab:orange", linestyle="--")
    ax2.set_ylabel("mean episode length [s] (3 s max)", color="tab:orange")
    ax.set_title(f"PPO (Stable-Baselines3) on FlightBatchEnv hover, {wall / 60:.1f} min on 2 cores")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(
        json.dumps(
            {
                "steps": int(model.num_timesteps),
                "wall_s": wall,
                "first_return": float(returns[0]),
                "last_return": float(returns[-1]),
                "first_length": float(lengths[0]),
                "last_length": float(lengths[-1]),
                "plot": args.plot,
            }
        )
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
