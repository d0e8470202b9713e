"""The hover and waypoint tasks on the batched flight engine as Gymnasium vector environments:
gymnasium's env checker passes on one vehicle, and the checks it applies to a single environment
hold for the vector one (seeded resets and steps repeat, observations lie in their space and are
not reused, autoreset in the same step keeps the last observation); gym.make_vec finds them."""

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import rotors_sim as rs
import rotors_sim.envs  # noqa: F401  (registers the ids with their vector entry points)
from rotors_sim.envs import FlightBatchEnv
from rotors_sim.envs.batched import SingleVehicleEnv


@pytest.mark.parametrize("task", ["hover", "waypoints"])
@pytest.mark.parametrize("action_type", ["motor", "attitude"])
def test_env_checker_passes_on_one_vehicle(task, action_type):
    env = SingleVehicleEnv(task, action_type=action_type)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a checker warning fails the test
        check_env(env, skip_render_check=True)


def rollout(envs: FlightBatchEnv, seed: int, steps: int) -> list:
    obs, _ = envs.reset(seed=seed)
    actions = np.random.default_rng(seed).uniform(-0.2, 0.2, (steps, *envs.action_space.shape)).astype(np.float32)
    out = [obs.copy()]
    for a in actions:
        obs, reward, terminated, truncated, _ = envs.step(a)
        out += [obs.copy(), reward.copy(), terminated.copy(), truncated.copy()]
    return out


@pytest.mark.parametrize("task", ["hover", "waypoints"])
def test_vector_env_passes_the_checks_of_a_single_env(task):
    envs = gym.make_vec(f"RotorS/{task.capitalize()}-v0", num_envs=8, vectorization_mode="vector_entry_point")
    assert isinstance(envs, FlightBatchEnv)
    assert envs.observation_space.shape == (8, 13 if task == "hover" else 16)
    first = rollout(envs, 3, 50)
    again = rollout(envs, 3, 50)
    assert all(np.array_equal(a, b) for a, b in zip(first, again))  # seeded reset and step determinism
    other = rollout(envs, 4, 50)
    assert not np.array_equal(first[0], other[0])
    assert all(envs.observation_space.contains(o) for o in [first[0], *first[1::4]])
    obs, _ = envs.reset(seed=5)
    obs[:] = 0.0  # returned data is not the engine's: changing it changes nothing
    obs2, _ = envs.reset(seed=5)
    assert not np.array_equal(obs, obs2)
    with pytest.raises(rs.SimError, match=r"actions have shape \(3, 6\)"):
        envs.step(np.zeros((3, 6), np.float32))
    bad = np.zeros(envs.action_space.shape, np.float32)
    bad[2, 1] = np.nan
    with pytest.raises(rs.SimError, match=r"actions\[2, 1\] = nan is not finite"):
        envs.step(bad)


def test_autoreset_returns_next_episode_and_keeps_last_obs():
    envs = FlightBatchEnv("hover", 4, episode_s=0.3)
    envs.reset(seed=0)
    steps = 0
    while True:
        obs, _, terminated, truncated, info = envs.step(np.zeros((4, 6), np.float32))  # rotors off: it falls
        steps += 1
        if (terminated | truncated).any():
            break
    ended = np.flatnonzero(terminated | truncated)
    print(f"after {steps} control steps: ended {ended.tolist()}, terminated {terminated.tolist()}")
    assert steps == 30 and truncated.all()  # 0.3 s at 100 Hz, falling freely but still in bounds
    for i in ended:
        assert info["_final_obs"][i] and not np.array_equal(info["final_obs"][i], obs[i])
        assert envs.batch.time[i] == 0.0 and np.all(np.abs(obs[i, 0:3]) <= 0.5)  # a new start near the target
