"""A vectorised environment over many worlds in one process: every world is stepped by one call
(rotors_sim.step_all: threads, the GIL released), with per-world sensor seeds and reset seeds.
Autoreset in the same step (gymnasium AutoresetMode.SAME_STEP): an episode that ends returns the
first observation of the next one, its last observation in infos["final_obs"]."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from rotors_sim._engine import SimError, step_all


class BatchedEnv(VectorEnv):
    metadata = {"autoreset_mode": AutoresetMode.SAME_STEP}

    def __init__(self, make_env: Callable[[int], gym.Env], num_envs: int, threads: int = 0):
        if num_envs < 1:
            raise SimError(f"num_envs = {num_envs} must be >= 1")
        self.envs = [make_env(i) for i in range(num_envs)]
        self.num_envs = num_envs
        self.threads = threads
        self.single_observation_space = self.envs[0].observation_space
        self.single_action_space = self.envs[0].action_space
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self._engines = [env.flight.world.engine for env in self.envs]
        self._substeps = self.envs[0].flight.substeps

    def reset(self, *, seed: int | list[int] | None = None, options: dict[str, Any] | None = None):
        seeds = seed if isinstance(seed, list) else [None if seed is None else seed + i for i in range(self.num_envs)]
        if len(seeds) != self.num_envs:
            raise SimError(f"reset got {len(seeds)} seeds for {self.num_envs} environments")
        results = [env.reset(seed=s, options=options) for env, s in zip(self.envs, seeds)]
        return np.stack([obs for obs, _ in results]), {"time_s": np.array([i["time_s"] for _, i in results])}

    def step(self, actions):
        actions = np.asarray(actions)
        if actions.shape != self.action_space.shape:
            raise SimError(f"actions have shape {actions.shape}, this vector environment needs {self.action_space.shape}")
        for env, action in zip(self.envs, actions):
            env.begin_step(action)
        step_all(self._engines, self._substeps, self.threads)
        observations, rewards = [], np.zeros(self.num_envs)
        terminations = np.zeros(self.num_envs, dtype=bool)
        truncations = np.zeros(self.num_envs, dtype=bool)
        final_obs = np.full(self.num_envs, None, dtype=object)
        for i, env in enumerate(self.envs):
            obs, rewards[i], terminations[i], truncations[i], _ = env.end_step()
            if terminations[i] or truncations[i]:
                final_obs[i] = obs
                obs, _ = env.reset()
            observations.append(obs)
        infos = {"final_obs": final_obs, "_final_obs": terminations | truncations}
        return np.stack(observations), rewards, terminations, truncations, infos

    def close_extras(self, **kwargs: Any) -> None:
        self.envs = []
        self._engines = []
