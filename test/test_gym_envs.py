"""The Gymnasium environments of rotors_sim: check_env passes for each (both action spaces), a
scripted policy (the Lee controller's rotor speeds as the action) holds the hover and reaches every
waypoint while a random policy crashes, bad actions raise one clear exception, and the vector
environment steps many worlds in one call with autoreset."""

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import rotors_sim as rs
import rotors_sim.envs  # noqa: F401  (registers RotorS/Hover-v0 and RotorS/Waypoints-v0)
from rotors_sim.envs import BatchedEnv, HoverEnv, WaypointsEnv


@pytest.mark.parametrize("env_id", ["RotorS/Hover-v0", "RotorS/Waypoints-v0"])
@pytest.mark.parametrize("action_type", ["motor", "attitude"])
def test_check_env_passes(env_id, action_type):
    env = gym.make(env_id, action_type=action_type).unwrapped
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a checker warning fails the test
        check_env(env, skip_render_check=True)
    assert env.observation_space.shape == ((13,) if "Hover" in env_id else (16,))
    assert env.action_space.shape == ((6,) if action_type == "motor" else (4,))


def lee_action(env, lee: rs.LeePositionController) -> np.ndarray:
    """The scripted policy: the Lee controller's rotor speeds, as a normalized motor action."""
    speeds = lee.rotor_speeds(env.flight.odometry)
    return (2.0 * speeds / env.flight.max_rot_velocity - 1.0).astype(np.float32)


def test_scripted_policy_holds_hover_and_random_one_crashes():
    env = HoverEnv(action_type="motor")
    lee = rs.LeePositionController.for_mav("firefly")
    obs, _ = env.reset(seed=0)
    lee.set_point(env.target, yaw=float(2.0 * np.arctan2(obs[8], obs[9])))  # the start heading
    total, steps, done = 0.0, 0, False
    while not done:
        obs, reward, terminated, truncated, info = env.step(lee_action(env, lee))
        total, steps, done = total + reward, steps + 1, terminated or truncated
    print(f"scripted: {steps} steps, return {total:.1f}, final error {np.linalg.norm(obs[:3]):.3f} m")
    assert truncated and not terminated and steps == 1000  # 10 s at 100 Hz
    assert np.linalg.norm(obs[:3]) < 0.1
    env.reset(seed=4)
    random_steps, done = 0, False
    while not done:
        _, _, terminated, truncated, info = env.step(env.action_space.sample())
        random_steps, done = random_steps + 1, terminated or truncated
    print(f"random: terminated after {random_steps} steps (collided: {info['collided']})")
    assert terminated and random_steps < 1000


def test_the_attitude_action_space_flies():
    env = HoverEnv(action_type="attitude")
    obs, _ = env.reset(seed=1)
    for _ in range(300):  # level, hover thrust: a damped vertical drop, still in the bound after 3 s
        obs, _, terminated, _, _ = env.step(np.array([0.0, 0.0, 0.0, 0.0], np.float32))
        assert not terminated
    tilt = 2 * np.arcsin(np.linalg.norm(obs[6:8]))
    print(f"attitude hold: tilt {np.degrees(tilt):.2f} deg, vertical speed {obs[5]:.3f} m/s")
    assert tilt < np.radians(2.0) and abs(obs[5]) < 0.5


def test_a_scripted_policy_reaches_every_waypoint():
    env = WaypointsEnv(action_type="motor")
    lee = rs.LeePositionController.for_mav("firefly")
    env.reset(seed=0)
    done, info = False, {}
    while not done:
        lee.set_point(env.waypoints[min(env.index, len(env.waypoints) - 1)])
        _, _, terminated, truncated, info = env.step(lee_action(env, lee))
        done = terminated or truncated
    print(f"waypoints: success {info['success']} at t = {info['time_s']:.2f} s")
    assert info["success"] and terminated


@pytest.mark.parametrize(
    "action, match",
    [
        (np.zeros(5, np.float32), r"action has shape \(5,\).*needs \(6,\)"),
        (np.full(6, np.nan, np.float32), "has NaN or inf"),
    ],
)
def test_bad_actions_raise_one_exception_and_env_keeps_working(action, match):
    env = HoverEnv()
    env.reset(seed=0)
    with pytest.raises(rs.SimError, match=match):
        env.step(action)
    obs, *_ = env.step(np.zeros(6, np.float32))
    assert np.all(np.isfinite(obs))
    with pytest.raises(rs.SimError, match="unknown vehicle mav_name 'ufo'"):
        HoverEnv(mav_name="ufo")
    with pytest.raises(rs.SimError, match="action_type 'rpm' unknown"):
        HoverEnv(action_type="rpm")
    with pytest.raises(rs.SimError, match="attitude actions need roll_pitch_yawrate_thrust_controller_neo9.yaml"):
        HoverEnv(mav_name="neo9", action_type="attitude")


def test_vector_env_steps_every_world_in_one_call_with_autoreset():
    envs = BatchedEnv(lambda i: HoverEnv(sensor_seed=i, episode_s=0.5), num_envs=8)
    obs, _ = envs.reset(seed=10)
    assert obs.shape == (8, 13) and len({tuple(o) for o in obs}) == 8  # per-world start states
    ended = 0
    for _ in range(60):  # 0.6 s: every episode (0.5 s) ends once, by truncation or a crash
        obs, rewards, terminated, truncated, infos = envs.step(envs.action_space.sample())
        assert obs.shape == (8, 13) and rewards.shape == (8,)
        ended += int(np.sum(terminated | truncated))
        for i in np.flatnonzero(terminated | truncated):
            assert infos["final_obs"][i] is not None
    assert ended >= 8
    with pytest.raises(rs.SimError, match=r"actions have shape \(3, 6\)"):
        envs.step(np.zeros((3, 6), np.float32))
    envs.close()
