"""The hover and waypoint tasks on the batched flight engine as Gymnasium vector environments:
gymnasium's env checker passes on one vehicle, and the checks it applies to a single environment
hold for the vector one (seeded resets and steps repeat, observations lie in their space and are
not reused, autoreset in the same step keeps the last observation); gym.make_vec finds them."""

import re
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


def sync_vector_env(task: str, n: int, mode, **kwargs) -> gym.vector.SyncVectorEnv:
    """Gymnasium's own vector environment over n single-vehicle environments, vehicle i with sensor
    seed i as FlightBatchEnv seeds its vehicle i."""
    return gym.vector.SyncVectorEnv([lambda i=i: SingleVehicleEnv(task, sensor_seed=i, **kwargs) for i in range(n)], autoreset_mode=mode)


# randomised airframes (rotors_sim.randomization): each vehicle's own, drawn again at every reset
RANDOMIZATION = {"mass": ("uniform", 0.8, 1.2), "motorConstant": ("normal", 1.0, 0.03), "cog": ("uniform", -0.01, 0.01)}


@pytest.mark.parametrize("task,randomization", [("hover", None), ("waypoints", None), ("hover", RANDOMIZATION)])
def test_vector_env_steps_as_gymnasiums_sync_vector_env(task, randomization):
    # the same seeds and actions: the same observations, rewards, ends, last observations and infos,
    # episodes ending at different steps (random actions) and starting again in the same step
    n = 4
    ours = FlightBatchEnv(task, n, randomization=randomization)
    theirs = sync_vector_env(task, n, gym.vector.AutoresetMode.SAME_STEP, randomization=randomization)
    assert ours.metadata["autoreset_mode"] == theirs.metadata["autoreset_mode"] == gym.vector.AutoresetMode.SAME_STEP
    o1, _ = ours.reset(seed=7)
    o2, _ = theirs.reset(seed=7)
    assert np.array_equal(o1, o2)
    rng = np.random.default_rng(7)
    ends = 0
    for _ in range(400):
        a = rng.uniform(-1.0, 1.0, ours.action_space.shape).astype(np.float32) * 0.3
        r1, r2 = ours.step(a), theirs.step(a)
        for x, y in zip(r1[:4], r2[:4]):
            assert np.array_equal(x, y)
        i1, i2 = r1[4], r2[4]
        if "_final_obs" in i2:
            ends += int(i2["_final_obs"].sum())
            assert np.array_equal(i1["_final_obs"], i2["_final_obs"]) and np.array_equal(i1["_final_info"], i2["_final_info"])
            for i in np.flatnonzero(i2["_final_obs"]):
                assert np.array_equal(i1["final_obs"][i], i2["final_obs"][i])
            for key in i2["final_info"]:
                assert np.array_equal(i1["final_info"][key], i2["final_info"][key]), key
        else:
            assert "_final_obs" not in i1
        for key in i2:
            if key not in ("final_obs", "final_info"):
                assert np.array_equal(i1[key], i2[key]), key
    print(
        f"{task}{' randomised' if randomization else ''}: 400 steps of {n} vehicles, {ends} episodes ended and "
        "started again, equal to SyncVectorEnv's"
    )
    assert ends >= 4


def test_reset_mask_resets_only_the_masked_vehicles():
    n = 4
    ours = FlightBatchEnv("hover", n, autoreset=False)
    theirs = sync_vector_env("hover", n, gym.vector.AutoresetMode.DISABLED)
    assert ours.metadata["autoreset_mode"] == gym.vector.AutoresetMode.DISABLED
    ours.reset(seed=3)
    theirs.reset(seed=3)
    a = np.zeros(ours.action_space.shape, np.float32)
    a[:2] = 1.0  # vehicles 0 and 1 climb at full speed and leave the 2 m bound; 2 and 3 hover-ish
    a[2:] = 0.0
    for _ in range(300):
        r1, r2 = ours.step(a), theirs.step(a)
        assert all(np.array_equal(x, y) for x, y in zip(r1[:4], r2[:4]))
        done = r1[2] | r1[3]
        if done.any():
            break
    assert done.any() and not done[2:].any(), done
    ended = np.flatnonzero(done).tolist()
    with pytest.raises(rs.SimError, match=rf"environments {re.escape(str(ended))} have ended and autoreset is off"):
        ours.step(a)
    mask = done.copy()
    before = r1[0].copy()
    o1, info1 = ours.reset(options={"reset_mask": mask})
    o2, info2 = theirs.reset(options={"reset_mask": mask})
    assert np.array_equal(o1, o2) and np.array_equal(info1["_time_s"], mask)
    assert np.array_equal(o1[~mask], before[~mask]) and not np.array_equal(o1[mask], before[mask])  # only the masked anew
    r1, r2 = ours.step(a), theirs.step(a)
    assert all(np.array_equal(x, y) for x, y in zip(r1[:4], r2[:4]))
    with pytest.raises(rs.SimError, match=r"reset_mask'\] has no True value"):
        ours.reset(options={"reset_mask": np.zeros(n, bool)})


def test_a_crash_scores_below_any_hover_that_lasts_longer():
    # every step survived earns a reward in [0, 1] and the crash step -10: whatever came before, an
    # episode that ends in a crash at step k scores below one that lasts past k
    envs = FlightBatchEnv("hover", 16, action_type="attitude")
    envs.reset(seed=1)
    rng = np.random.default_rng(1)
    survived, crashed = [], []
    for _ in range(300):
        _, reward, terminated, _, _ = envs.step(rng.uniform(-1.0, 1.0, envs.action_space.shape).astype(np.float32))
        survived += reward[~terminated].tolist()
        crashed += reward[terminated].tolist()
    print(f"{len(survived)} steps survived: rewards {min(survived):.3f} to {max(survived):.3f}; {len(crashed)} crashes")
    assert crashed and min(survived) >= 0.0 and max(survived) <= 1.0 and set(crashed) == {-10.0}
    # rotors off: it falls and crashes at step k; level at hover thrust it lasts longer and scores more
    falling = FlightBatchEnv("hover", 1, action_type="attitude", target=(0.0, 0.0, 0.3), autoreset=False)
    hovering = FlightBatchEnv("hover", 1, action_type="attitude", target=(0.0, 0.0, 0.3), autoreset=False)
    falling.reset(seed=2)
    hovering.reset(seed=2)
    fall_return, k = 0.0, 0
    while True:
        _, reward, terminated, truncated, _ = falling.step(np.array([[0.0, 0.0, 0.0, -1.0]], np.float32))
        fall_return, k = fall_return + reward[0], k + 1
        if terminated[0] or truncated[0]:
            break
    hover_return = sum(hovering.step(np.zeros((1, 4), np.float32))[1][0] for _ in range(k + 1))
    print(f"rotors off: crashed at step {k}, return {fall_return:.2f}; hover thrust for {k + 1} steps: {hover_return:.2f}")
    assert terminated[0] and hover_return > fall_return
    with pytest.raises(rs.SimError, match="alive_bonus = -1.0 must be >= 0"):
        FlightBatchEnv("hover", 1, alive_bonus=-1.0)


def test_the_row_math_of_the_observations_matches_its_definition():
    """rotate_rows is R(q) v (against the rotation matrix of q), odometry_observations is
    (p - origin, R(q) v_B, q, omega_B) clipped and in float32 (a NaN stays NaN), block_norms the
    Euclidean norms of its 3-column blocks."""
    from rotors_sim import _engine
    from rotors_sim.envs.batched import rotation_rows

    rng = np.random.default_rng(3)
    q = rng.normal(size=(50, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    v = rng.normal(scale=5.0, size=(50, 3))
    expected = np.einsum("nij,nj->ni", rotation_rows(q), v)
    assert np.allclose(_engine.rotate_rows(q, v), expected, rtol=0, atol=1e-13)
    quarter_turn_z = np.array([[0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)]])
    assert np.allclose(_engine.rotate_rows(quarter_turn_z, np.array([[1.0, 0.0, 0.0]])), [[0.0, 1.0, 0.0]], atol=1e-15)

    odometry = np.column_stack([rng.normal(scale=4.0, size=(50, 3)), q, v, rng.normal(scale=40.0, size=(50, 3)), np.zeros(50)])
    odometry[7, 0] = np.nan
    high = np.array([5.0] * 3 + [20.0] * 3 + [1.0] * 4 + [50.0] * 3)
    target = np.array([0.0, 0.0, 1.0])
    obs = _engine.odometry_observations(odometry, [target], -high, high)
    reference = np.column_stack([odometry[:, 0:3] - target, expected, q, odometry[:, 10:13]])
    reference = np.minimum(np.maximum(reference, -high), high).astype(np.float32)
    assert obs.dtype == np.float32 and obs.shape == (50, 13)
    assert np.isnan(obs[7, 0]) and np.array_equal(np.isnan(obs), np.isnan(reference))
    assert np.allclose(obs, reference, rtol=1e-6, atol=1e-6, equal_nan=True)
    assert np.all(np.abs(obs[~np.isnan(obs)].reshape(-1)) <= np.tile(high, 50)[~np.isnan(obs).reshape(-1)])
    with pytest.raises(rs.SimError, match="odometry must be N x 14"):
        _engine.odometry_observations(odometry[:, :13], [target], -high, high)

    x = rng.normal(size=(20, 13))
    assert np.array_equal(
        _engine.block_norms(x, [0, 3, 10]), np.column_stack([np.linalg.norm(x[:, k : k + 3], axis=1) for k in (0, 3, 10)])
    )
    with pytest.raises(rs.SimError, match="columns 11..13 are outside the 13 columns"):
        _engine.block_norms(x, [11])
