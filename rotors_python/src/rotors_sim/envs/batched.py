"""The hover and waypoint tasks as native vector environments on rotors_sim.FlightBatch: one
engine call steps every vehicle (threads, no GIL), observations and rewards are numpy over all of
them. Same spaces, rewards, starts and ends as RotorS/Hover-v0 and RotorS/Waypoints-v0 (hover.py,
waypoints.py); the vehicle is the full world's to rounding (docs/batched_flight.md).
Autoreset in the same step (gymnasium AutoresetMode.SAME_STEP, the default): an episode that ends
returns the first observation of the next one, its last observation and info in infos["final_obs"]
and infos["final_info"] (masks "_final_obs", "_final_info"), as gymnasium's SyncVectorEnv does. With
autoreset=False (AutoresetMode.DISABLED) the caller resets ended vehicles with
reset(options={"reset_mask": mask}), which resets only the masked ones.

    envs = FlightBatchEnv("hover", num_envs=1024)
    obs, info = envs.reset(seed=0)
    obs, reward, terminated, truncated, info = envs.step(envs.action_space.sample())
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from rotors_sim import _engine
from rotors_sim._engine import SimError
from rotors_sim.envs import hover, waypoints
from rotors_sim.flight_batch import FlightBatch
from rotors_sim.randomization import check_spec, draw_airframe_rows

TASKS = ("hover", "waypoints")
ACTION_TYPES = ("motor", "attitude")


def rotation_rows(q_xyzw: np.ndarray) -> np.ndarray:
    """R(q) for rows of unit quaternions (x, y, z, w): N x 3 x 3."""
    x, y, z, w = np.asarray(q_xyzw, dtype=np.float64).T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
        ],
        axis=1,
    )


def reset_mask(options: dict[str, Any] | None, num_envs: int) -> np.ndarray:
    """The vehicles a reset resets: options["reset_mask"] (a numpy bool array, one per vehicle, not
    all False) or all; SimError naming what is wrong with it."""
    if options is None or "reset_mask" not in options:
        return np.ones(num_envs, dtype=bool)
    mask = options["reset_mask"]
    if not isinstance(mask, np.ndarray) or mask.dtype != np.bool_ or mask.shape != (num_envs,):
        raise SimError(f"options['reset_mask'] must be a numpy bool array of shape ({num_envs},), got {mask!r}")
    if not mask.any():
        raise SimError("options['reset_mask'] has no True value: nothing to reset")
    return mask


def reseed(rngs: list, seed: int | list[int | None] | None, mask: np.ndarray) -> None:
    """Vehicle i's episode generator from seed + i (or seed[i]) for the masked vehicles; None: kept."""
    if seed is None:
        return
    seeds = seed if isinstance(seed, list) else [seed + i for i in range(len(rngs))]
    if len(seeds) != len(rngs):
        raise SimError(f"reset got {len(seeds)} seeds for {len(rngs)} environments")
    for i in np.flatnonzero(mask):
        if seeds[i] is not None:
            rngs[i] = np.random.default_rng(seeds[i])


def checked_actions(actions: Any, shape: tuple[int, ...]) -> np.ndarray:
    """The actions as float64 clipped to [-1, 1], or SimError naming a wrong shape or a value that is not finite."""
    a = np.asarray(actions, dtype=np.float64)
    if a.shape != shape:
        raise SimError(f"actions have shape {a.shape}, this vector environment needs {shape}")
    if not np.isfinite(a).all():
        bad = np.argwhere(~np.isfinite(a))[0]
        raise SimError(f"actions[{bad[0]}, {bad[1]}] = {a[tuple(bad)]} is not finite")
    return np.minimum(np.maximum(a, -1.0), 1.0)  # np.clip's values, without its wrapper's cost


def step_infos(step_info: dict[str, np.ndarray]) -> dict[str, Any]:
    """A step's info for every vehicle, with gymnasium's masks."""
    infos: dict[str, Any] = {}
    for key, value in step_info.items():
        infos[key], infos["_" + key] = value, np.ones(len(value), dtype=bool)
    return infos


def autoreset_infos(infos: dict[str, Any], step_info: dict[str, np.ndarray], done: np.ndarray, final_obs: np.ndarray, kept=()) -> None:
    """Gymnasium's same-step autoreset, as SyncVectorEnv writes it: the ended vehicles' last
    observations and infos under "final_obs" and "final_info", and their infos now the new
    episode's (none: masked off), except the keys in `kept` (the caller's, already the new ones)."""
    final_info: dict[str, Any] = {}
    for key, value in step_info.items():
        final_info[key], final_info["_" + key] = np.where(done, value, np.zeros_like(value)), done.copy()
    for key in step_info:
        if key not in kept:
            infos[key] = np.where(done, np.zeros_like(infos[key]), infos[key])
            infos["_" + key] = ~done
    infos["final_obs"], infos["_final_obs"] = final_obs, done.copy()
    infos["final_info"], infos["_final_info"] = final_info, done.copy()


class FlightBatchEnv(VectorEnv):
    """`task` "hover" or "waypoints" for `num_envs` vehicles `mav_name`; `action_type` "motor" (a
    value in [-1, 1] per rotor: 0 to its maximum speed) or "attitude" (roll and pitch up to
    max_tilt_rad, yaw rate up to max_yaw_rate_rad_s, thrust 0 to twice the weight). Sensor noise
    seeded per vehicle from sensor_seed + i. `alive_bonus` (hover, default 0, >= 0) is added to the
    reward of every step that does not end in a crash (the hover reward is in [0, 1] already).
    `randomization` (rotors_sim.randomization's spec; also reset(options={"randomization": spec})
    from that reset on): every vehicle draws its airframe at every reset from its episode's
    generator, and its sensor noise a new seed; None (the default): every episode the xacro's
    airframe and the same noise. `imu` simulates the vehicles' IMU (self.batch.imu; off by default:
    the observations are the odometry's, and the IMU costs as much as the rest of the step).
    With autoreset off, stepping a vehicle that ended before it is reset raises, unless
    `step_after_end` (a plain gymnasium.Env's caller may step on: SingleVehicleEnv)."""

    metadata = {"autoreset_mode": AutoresetMode.SAME_STEP}

    def __init__(
        self,
        task: str = "hover",
        num_envs: int = 16,
        *,
        mav_name: str = "firefly",
        action_type: str = "motor",
        physics_hz: float = 500.0,
        control_hz: float = 100.0,
        episode_s: float | None = None,
        target: Sequence[float] = (0.0, 0.0, 1.0),
        waypoint_list: Sequence[Sequence[float]] = waypoints.SQUARE[1:],
        start: Sequence[float] = waypoints.SQUARE[0],
        reach_m: float = 0.3,
        sensor_seed: int = 0,
        threads: int = 0,
        max_tilt_rad: float = 0.6,
        max_yaw_rate_rad_s: float = 2.0,
        autoreset: bool = True,
        alive_bonus: float = 0.0,
        randomization: dict[str, Any] | None = None,
        imu: bool = False,
        step_after_end: bool = False,
    ):
        if task not in TASKS:
            raise SimError(f"task '{task}' is not known; use one of: {', '.join(TASKS)}")
        if action_type not in ACTION_TYPES:
            raise SimError(f"action_type '{action_type}' unknown (use one of: {', '.join(ACTION_TYPES)})")
        if int(num_envs) < 1:
            raise SimError(f"num_envs = {num_envs} must be >= 1")
        self.task, self.num_envs, self.action_type = task, int(num_envs), action_type
        if not float(alive_bonus) >= 0.0:
            raise SimError(f"alive_bonus = {alive_bonus} must be >= 0 (a negative one makes crashing early pay)")
        self.autoreset, self.step_after_end = autoreset, step_after_end
        self.metadata = {"autoreset_mode": AutoresetMode.SAME_STEP if autoreset else AutoresetMode.DISABLED}
        self.alive_bonus = float(alive_bonus)
        self.randomization = check_spec(randomization) if randomization is not None else None
        self.sensor_seed = int(sensor_seed)
        step_size = 1.0 / physics_hz
        self.substeps = max(1, round(1.0 / control_hz / step_size))
        mode = "rotor_speeds" if action_type == "motor" else "roll_pitch_yawrate_thrust"
        self.batch = FlightBatch(
            mav_name,
            self.num_envs,
            mode=mode,
            step_size=step_size,
            control_divisor=self.substeps,
            threads=threads,
            seeds=[sensor_seed + i for i in range(self.num_envs)],
            imu=imu,
        )
        d = self.batch.description
        self.max_rot_velocity = np.array([r["max_rot_velocity"] for r in d.rotors])
        self._half_max_rot_velocity = 0.5 * self.max_rot_velocity[None, :]
        self.hover_thrust_N = d.mass_kg * -d.gravity_W[2]
        self.max_tilt_rad, self.max_yaw_rate_rad_s = max_tilt_rad, max_yaw_rate_rad_s
        self.dt = self.substeps * step_size
        self.target = np.asarray(target, dtype=np.float64)
        self.waypoints = np.asarray(waypoint_list, dtype=np.float64).reshape(-1, 3)
        self.start = np.asarray(start, dtype=np.float64)
        self.reach_m = reach_m
        episode_s = episode_s if episode_s is not None else (10.0 if task == "hover" else 20.0)
        self.max_steps = int(round(episode_s / self.dt))
        high = hover.OBSERVATION_HIGH if task == "hover" else waypoints.OBSERVATION_HIGH
        action_size = self.batch.rotor_count if action_type == "motor" else 4
        self.single_observation_space = gym.spaces.Box(-high, high, dtype=np.float32)
        self.single_action_space = gym.spaces.Box(-1.0, 1.0, (action_size,), np.float32)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._high, self._low = high.astype(np.float64), -high.astype(np.float64)
        self._rngs = [np.random.default_rng(i) for i in range(self.num_envs)]
        self.steps = np.zeros(self.num_envs, dtype=np.int64)
        self.index = np.zeros(self.num_envs, dtype=np.int64)
        self.distance = np.zeros(self.num_envs)
        self._ended = np.zeros(self.num_envs, dtype=bool)  # with autoreset off: ended, not reset yet
        self._obs = np.zeros(self.observation_space.shape, np.float32)
        self._airframes_drawn = False  # some vehicle flies a drawn airframe: None restores the xacro's
        self._nominal = self.batch.nominal_airframe

    # --- Gymnasium ---
    def reset(self, *, seed: int | list[int | None] | None = None, options: dict[str, Any] | None = None):
        """All vehicles, or with options={"reset_mask": mask} (a bool array, one per vehicle) only
        the masked ones: their observations are new, the others' are those of the last step, and
        the info speaks for the masked ones (gymnasium's SyncVectorEnv semantics)."""
        mask = reset_mask(options, self.num_envs)
        if options is not None and "randomization" in options:
            spec = options["randomization"]
            self.randomization = check_spec(spec) if spec is not None else None
        reseed(self._rngs, seed, mask)
        ended = np.flatnonzero(mask)
        self._reset(ended)
        self._ended[ended] = False
        self._obs[ended] = self._observe(ended)
        return self._obs.copy(), {"time_s": self.batch.time.copy(), "_time_s": mask.copy()}

    def step(self, actions):
        if self._ended.any() and not self.step_after_end:
            raise SimError(
                f"environments {np.flatnonzero(self._ended).tolist()} have ended and autoreset is off; "
                "reset them first: reset(options={'reset_mask': mask})"
            )
        if self.action_type == "motor":
            # checked_actions' checks and clip in one C++ pass (nothing written on an error), then (a + 1) / 2 * max
            _engine.motor_commands(actions, self._half_max_rot_velocity, self.batch.commands)
        else:
            a = checked_actions(actions, self.action_space.shape)
            self.batch.commands[:] = np.column_stack(
                [
                    a[:, 0] * self.max_tilt_rad,
                    a[:, 1] * self.max_tilt_rad,
                    a[:, 2] * self.max_yaw_rate_rad_s,
                    (a[:, 3] + 1.0) * self.hover_thrust_N,
                ]
            )
        self.batch.step(self.substeps)
        self.steps += 1
        collided = self.batch.in_contact  # a new array, as batch.time below
        if self.task == "hover":
            obs = self._observe()
            # a contact or |e_p| beyond the bound on an axis ends it; else 1 - c / c_max + alive_bonus
            reward, terminated = _engine.hover_rewards(
                obs, collided, hover.BOUND_M, hover.COST_MAX, hover.TERMINATION_REWARD, self.alive_bonus
            )
            success = np.zeros(self.num_envs, dtype=bool)
        else:
            p = self.batch.odometry[:, 0:3]
            last = len(self.waypoints) - 1
            distance = np.linalg.norm(p - self.waypoints[np.minimum(self.index, last)], axis=1)
            reward = 10.0 * (self.distance - distance) - 0.01 * np.linalg.norm(self.batch.odometry[:, 10:13], axis=1)
            reached = distance < self.reach_m
            reward += 5.0 * reached
            self.index += reached
            success = self.index >= len(self.waypoints)
            moved_on = reached & ~success
            distance[moved_on] = np.linalg.norm(p[moved_on] - self.waypoints[self.index[moved_on]], axis=1)
            self.distance = distance
            crashed = collided | (~success & (distance > 3.0))
            reward = np.where(crashed, -10.0, reward)
            terminated = success | crashed
            obs = self._observe()
        truncated = ~terminated & (self.steps >= self.max_steps)
        done = terminated | truncated
        step_info: dict[str, np.ndarray] = {"time_s": self.batch.time, "collided": collided}
        if self.task == "waypoints":
            step_info["success"] = success.copy()
            step_info["waypoint"] = np.minimum(self.index, len(self.waypoints))
        infos = step_infos(step_info)
        if self.autoreset and done.any():
            ended = np.flatnonzero(done)
            final_obs = np.full(self.num_envs, None, dtype=object)
            for i in ended:
                final_obs[i] = obs[i].copy()
            self._reset(ended)
            obs[ended] = self._observe(ended)
            infos["time_s"] = self.batch.time
            autoreset_infos(infos, step_info, done, final_obs, kept=("time_s",))
        elif done.any():
            self._ended |= done
        self._obs[:] = obs
        return obs, reward, terminated, truncated, infos  # reward: float64 from np.where

    def close_extras(self, **kwargs: Any) -> None:
        self.batch = None

    # --- the tasks ---
    def _reset(self, ended: np.ndarray) -> None:
        # the start: uniform offsets from the target (and a uniform yaw) or from the start point,
        # low + (high - low) u as Generator.uniform computes them, from one call per vehicle
        rngs = [self._rngs[i] for i in ended]
        if self.task == "hover":
            u = np.array([rng.random(4) for rng in rngs]).reshape(len(rngs), 4)
            positions = self.target + (-hover.START_OFFSET_M + (2.0 * hover.START_OFFSET_M) * u[:, 0:3])
            positions[:, 2] = np.maximum(positions[:, 2], 0.3)
            yaws = -np.pi + (2.0 * np.pi) * u[:, 3]
        else:
            u = np.array([rng.random(3) for rng in rngs]).reshape(len(rngs), 3)
            positions = self.start + (-0.2 + 0.4 * u)
            yaws = np.zeros(len(rngs))
        if self.randomization is not None:
            self.batch.set_airframes(ended, **draw_airframe_rows(self.randomization, self._nominal, rngs))
            self.batch.set_seeds(ended, [int(rng.integers(0, 2**31)) for rng in rngs])
            self._airframes_drawn = True
        elif self._airframes_drawn:
            for i in ended:
                self.batch.set_airframe(i)  # the xacro's again, and the constructor's noise
                self.batch.set_seed(i, self.sensor_seed + i)
        self.batch.reset(ended, positions=positions, yaws=yaws)
        # the sensor's first message is the end of the first step; until then, the reset state
        self.batch.commands[ended] = 0.0
        self.steps[ended] = 0
        if self.task == "waypoints":
            self.index[ended] = 0
            self.distance[ended] = np.linalg.norm(self.batch.odometry[ended, 0:3] - self.waypoints[0], axis=1)

    def _observe(self, rows: np.ndarray | None = None) -> np.ndarray:
        """The observations of every vehicle, or of `rows` only: the position relative to the target
        (hover) or to the current and the next waypoint, then velocity_W, q and the body rates, clipped."""
        o = self.batch.odometry if rows is None else self.batch.odometry[rows]
        if self.task == "hover":
            origins = [self.target]
        else:
            index = self.index if rows is None else self.index[rows]
            last = len(self.waypoints) - 1
            origins = [self.waypoints[np.minimum(index, last)], self.waypoints[np.minimum(index + 1, last)]]
        return _engine.odometry_observations(o, origins, self._low, self._high)


def hover_vector_env(num_envs: int = 16, **kwargs: Any) -> FlightBatchEnv:
    """RotorS/Hover-v0's vector entry point: gym.make_vec("RotorS/Hover-v0", num_envs,
    vectorization_mode="vector_entry_point")."""
    kwargs.pop("render_mode", None)
    return FlightBatchEnv("hover", num_envs, **kwargs)


def waypoints_vector_env(num_envs: int = 16, **kwargs: Any) -> FlightBatchEnv:
    """RotorS/Waypoints-v0's vector entry point (see hover_vector_env)."""
    kwargs.pop("render_mode", None)
    if "waypoints" in kwargs:
        kwargs["waypoint_list"] = kwargs.pop("waypoints")
    return FlightBatchEnv("waypoints", num_envs, **kwargs)


class SingleVehicleEnv(gym.Env):
    """One vehicle of FlightBatchEnv as a plain gymnasium.Env (no autoreset), e.g. for
    gymnasium.utils.env_checker.check_env; keywords as FlightBatchEnv's."""

    metadata = {"render_modes": []}

    def __init__(self, task: str = "hover", **kwargs: Any):
        self.vector = FlightBatchEnv(task, 1, autoreset=False, step_after_end=True, **kwargs)
        self.observation_space = self.vector.single_observation_space
        self.action_space = self.vector.single_action_space

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        obs, info = self.vector.reset(seed=seed, options=options)
        return obs[0], {"time_s": float(info["time_s"][0])}

    def step(self, action):
        obs, reward, terminated, truncated, info = self.vector.step(np.asarray(action)[None, :])
        keys = ("time_s", "collided", "success", "waypoint")
        return (
            obs[0],
            float(reward[0]),
            bool(terminated[0]),
            bool(truncated[0]),
            {k: info[k][0].item() for k in keys if k in info},
        )
