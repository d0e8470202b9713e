"""RotorS/NavigateClutter-v0: reach a goal through clutter from depth images, as a native vector
environment on rotors_sim.FlightBatch (one engine call steps every vehicle; each vehicle flies its
own course of rotors_sim.clutter, drawn again at every reset from its episode's generator).

Each vehicle is the xacro's (the firefly by default) under Lee's position controller, carrying a
depth camera (FlightBatch.set_depth_camera: the project's D435 at 64 x 48) that looks along its
heading. The policy steps at the camera's 30 Hz.

- Action (4, in [-1, 1]): velocity forward, left and up in the heading's frame (times max_speed_m_s,
  max_speed_m_s and max_climb_m_s) and yaw rate (times max_yaw_rate_rad_s). A reference position
  and yaw move at that velocity and rate (held where they are at zero; pulled along when they fall
  more than REFERENCE_LEASH_M or REFERENCE_LEASH_RAD behind the vehicle, as after a push), and Lee's
  position controller gets the reference plus v k_v / k_p and yaw plus r k_omega / k_R, the offsets
  at which its steady state flies at v and r: the controller's own gains, from its yaml.
- Observation (dict): "depth" (1, H, W) float32 in [0, 1], depth / max_range (1 where the camera
  sees nothing within its range); "state" (10,) float32: the goal minus the position in the
  heading's frame [m] (3), the velocity in the heading's frame [m/s] (3), the world's up in the body
  frame (3: roll and pitch), the yaw rate [rad/s].
- Reward: the metres gained toward the goal in the step; +10 on reaching it (within goal_radius_m);
  -10 on a collision (an obstacle, the ground) or on leaving the course (below 0.2 m, above its
  height, behind the start).
- An episode ends at the goal, a collision or the course's end, and is truncated at episode_s.
  info: "collided", "success", "goal_distance".

Autoreset and reset(options={"reset_mask": ...}) as FlightBatchEnv (docs/batched_flight.md).
"""

from __future__ import annotations

import warnings
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from rotors_sim import _engine, clutter
from rotors_sim._engine import SimError
from rotors_sim.controllers import load_yamls
from rotors_sim.envs.batched import autoreset_infos, checked_actions, reseed, reset_mask, rotation_rows, step_infos
from rotors_sim.flight_batch import FlightBatch, controller_yamls

CAMERA_HZ = 30.0
REFERENCE_LEASH_M, REFERENCE_LEASH_RAD = 1.0, 0.5
STATE_SIZE = 10
STATE_HIGH = np.array([50.0] * 3 + [20.0] * 3 + [1.0] * 3 + [20.0], dtype=np.float32)


def _yaw_of(q_xyzw: np.ndarray) -> np.ndarray:
    x, y, z, w = q_xyzw.T
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def _to_heading(yaw: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rows of world vectors in the heading's frame (turned by -yaw about z)."""
    c, s = np.cos(yaw), np.sin(yaw)
    return np.column_stack([c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1], v[:, 2]])


class NavigateClutterEnv(VectorEnv):
    """`num_envs` vehicles `mav_name`, each through its own seeded course (`clutter`: a
    rotors_sim.clutter.ClutterSpec or a dict of its fields). `depth_camera`: FlightBatch.set_depth_camera's
    keywords over the defaults. `seed` of reset() seeds vehicle i's courses with seed + i. With
    autoreset off, stepping a vehicle that ended before it is reset raises, unless `step_after_end`
    (an evaluation that lets every vehicle fly until the last one ends, scoring each at its end)."""

    metadata = {"autoreset_mode": AutoresetMode.SAME_STEP}

    def __init__(
        self,
        num_envs: int = 16,
        *,
        mav_name: str = "firefly",
        clutter_spec: clutter.ClutterSpec | dict[str, Any] | None = None,
        depth_camera: dict[str, Any] | None = None,
        physics_hz: float = 480.0,
        control_divisor: int = 4,
        episode_s: float = 40.0,
        goal_radius_m: float = 1.0,
        max_speed_m_s: float = 2.0,
        max_climb_m_s: float = 1.0,
        max_yaw_rate_rad_s: float = 0.5,
        sensor_seed: int = 0,
        threads: int = 0,
        autoreset: bool = True,
        step_after_end: bool = False,
    ):
        if int(num_envs) < 1:
            raise SimError(f"num_envs = {num_envs} must be >= 1")
        self.num_envs = int(num_envs)
        self.course = clutter.spec_from(clutter_spec)
        self.autoreset, self.step_after_end = autoreset, step_after_end
        self.metadata = {"autoreset_mode": AutoresetMode.SAME_STEP if autoreset else AutoresetMode.DISABLED}
        step_size = 1.0 / physics_hz
        self.substeps = int(round(1.0 / CAMERA_HZ / step_size))
        if abs(self.substeps * step_size * CAMERA_HZ - 1.0) > 1e-9:
            raise SimError(f"physics_hz = {physics_hz} gives no whole number of steps per camera frame (30 Hz)")
        self.batch = FlightBatch(
            mav_name,
            self.num_envs,
            mode="lee_position",
            step_size=step_size,
            control_divisor=control_divisor,
            threads=threads,
            seeds=[sensor_seed + i for i in range(self.num_envs)],
        )
        self.batch.set_depth_camera(**(depth_camera or {}))
        self.field = clutter.field(self.num_envs, self.batch.collision_radius)
        self.batch.set_obstacles(self.field)
        camera = self.batch.depth_camera
        self.max_range_m = camera["max_range"]
        # Lee's steady state under a constant set point offset e: k_p e = k_v v, so v flies at e = v k_v / k_p
        numbers, _, _ = load_yamls(controller_yamls(mav_name, "lee_position"))
        kp = np.array([numbers[f"position_gain/{a}"] for a in "xyz"])
        kv = np.array([numbers[f"velocity_gain/{a}"] for a in "xyz"])
        self.lead_s = kv / kp
        # and the yaw's: k_R e = k_omega r, so a yaw rate r flies at e = r k_omega / k_R
        self.yaw_lead_s = numbers["angular_rate_gain/z"] / numbers["attitude_gain/z"]
        self.dt = self.substeps * step_size
        self.max_steps = int(round(episode_s / self.dt))
        self.goal_radius_m = goal_radius_m
        self.scale = np.array([max_speed_m_s, max_speed_m_s, max_climb_m_s])
        self.max_yaw_rate_rad_s = max_yaw_rate_rad_s
        depth_shape = (1, camera["height"], camera["width"])
        self.single_observation_space = gym.spaces.Dict(
            {
                "depth": gym.spaces.Box(0.0, 1.0, depth_shape, np.float32),
                "state": gym.spaces.Box(-STATE_HIGH, STATE_HIGH, (STATE_SIZE,), np.float32),
            }
        )
        self.single_action_space = gym.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._rngs = [np.random.default_rng(i) for i in range(self.num_envs)]
        self.starts = np.zeros((self.num_envs, 3))
        self.goals = np.zeros((self.num_envs, 3))
        self.course_seeds = np.zeros(self.num_envs, dtype=np.int64)
        self.steps = np.zeros(self.num_envs, dtype=np.int64)
        self.distance = np.zeros(self.num_envs)
        self.reference = np.zeros((self.num_envs, 3))
        self.yaw_reference = np.zeros(self.num_envs)
        self._ended = np.zeros(self.num_envs, dtype=bool)
        self._obs = {
            "depth": np.ones((self.num_envs, *depth_shape), np.float32),
            "state": np.zeros((self.num_envs, STATE_SIZE), np.float32),
        }

    # --- Gymnasium ---
    def reset(self, *, seed: int | list[int | None] | None = None, options: dict[str, Any] | None = None):
        mask = reset_mask(options, self.num_envs)
        reseed(self._rngs, seed, mask)
        ended = np.flatnonzero(mask)
        self._reset(ended)
        self._ended[ended] = False
        obs = self._observe(ended)
        for key in self._obs:
            self._obs[key][ended] = obs[key]
        return {k: v.copy() for k, v in self._obs.items()}, {"course_seed": self.course_seeds.copy(), "_course_seed": mask.copy()}

    def step(self, actions):
        a = checked_actions(actions, self.action_space.shape)
        if self._ended.any() and not self.step_after_end:
            raise SimError(
                f"environments {np.flatnonzero(self._ended).tolist()} have ended and autoreset is off; "
                "reset them first: reset(options={'reset_mask': mask})"
            )
        o = self.batch.odometry
        p, yaw = o[:, 0:3], _yaw_of(o[:, 3:7])
        v_heading = a[:, 0:3] * self.scale
        rate = a[:, 3] * self.max_yaw_rate_rad_s
        c, s = np.cos(yaw), np.sin(yaw)
        v_W = np.column_stack([c * v_heading[:, 0] - s * v_heading[:, 1], s * v_heading[:, 0] + c * v_heading[:, 1], v_heading[:, 2]])
        self.reference += v_W * self.dt
        behind = self.reference - p
        far = np.linalg.norm(behind, axis=1, keepdims=True)
        self.reference = np.where(far > REFERENCE_LEASH_M, p + behind * (REFERENCE_LEASH_M / np.maximum(far, 1e-9)), self.reference)
        self.yaw_reference = yaw + np.clip(
            np.angle(np.exp(1j * (self.yaw_reference + rate * self.dt - yaw))), -REFERENCE_LEASH_RAD, REFERENCE_LEASH_RAD
        )
        self.batch.commands[:, 0:3] = self.reference + v_W * self.lead_s
        self.batch.commands[:, 3] = self.yaw_reference + rate * self.yaw_lead_s
        self.batch.step(self.substeps)
        self.steps += 1
        p = self.batch.odometry[:, 0:3]
        distance = np.linalg.norm(p - self.goals, axis=1)
        reward = self.distance - distance
        self.distance = distance
        success = distance < self.goal_radius_m
        collided = self.batch.collided | self.batch.in_contact
        left = (p[:, 2] < 0.2) | (p[:, 2] > self.course.height_m) | (p[:, 0] < self.starts[:, 0] - 2.0)
        failed = ~success & (collided | left)
        reward = reward + 10.0 * success - 10.0 * failed
        terminated = success | failed
        truncated = ~terminated & (self.steps >= self.max_steps)
        done = terminated | truncated
        obs = self._observe()
        step_info = {"collided": collided.copy(), "success": success.copy(), "goal_distance": distance.copy()}
        infos = step_infos(step_info)
        if self.autoreset and done.any():
            ended = np.flatnonzero(done)
            final_obs = np.full(self.num_envs, None, dtype=object)
            for i in ended:
                final_obs[i] = {k: v[i].copy() for k, v in obs.items()}
            self._reset(ended)
            fresh = self._observe(ended)
            for key in obs:
                obs[key][ended] = fresh[key]
            autoreset_infos(infos, step_info, done, final_obs)
        elif done.any():
            self._ended |= done
        for key in self._obs:
            self._obs[key][:] = obs[key]
        return obs, reward, terminated, truncated, infos

    def close_extras(self, **kwargs: Any) -> None:
        self.batch = None

    # --- the task ---
    def _reset(self, ended: np.ndarray) -> None:
        positions, yaws = np.empty((len(ended), 3)), np.empty(len(ended))
        for j, i in enumerate(ended):
            seed = int(self._rngs[i].integers(0, 2**31))
            obstacles, start, goal = clutter.generate(self.course, seed)
            self.field.set(int(i), obstacles)
            self.course_seeds[i], self.starts[i], self.goals[i] = seed, start, goal
            positions[j] = start
            yaws[j] = np.arctan2(goal[1] - start[1], goal[0] - start[0])  # facing the goal
        self.batch.reset(ended, positions=positions, yaws=yaws)
        self.batch.commands[ended, 0:3] = positions
        self.batch.commands[ended, 3] = yaws
        self.reference[ended], self.yaw_reference[ended] = positions, yaws
        self.steps[ended] = 0
        self.distance[ended] = np.linalg.norm(positions - self.goals[ended], axis=1)

    def _observe(self, rows: np.ndarray | None = None) -> dict[str, np.ndarray]:
        """The observations of every vehicle, or of `rows` only (their depth images alone rendered)."""
        rows = np.arange(self.num_envs) if rows is None else rows
        depth = self.batch.render_depth(rows)
        # NaN (out of range) as nothing seen; the noise may carry a depth just past the range
        depth = np.clip(np.where(np.isnan(depth), self.max_range_m, depth) / self.max_range_m, 0.0, 1.0)
        o = self.batch.odometry[rows]
        q = o[:, 3:7]
        yaw = _yaw_of(q)
        state = np.empty((len(rows), STATE_SIZE))
        state[:, 0:3] = _to_heading(yaw, self.goals[rows] - o[:, 0:3])
        state[:, 3:6] = _to_heading(yaw, _engine.rotate_rows(q, o[:, 7:10]))
        state[:, 6:9] = rotation_rows(q)[:, 2, :]  # the world's up in the body frame: R^T e_z, R(q)'s third row
        state[:, 9] = o[:, 12]
        np.clip(state, -STATE_HIGH, STATE_HIGH, out=state)
        return {"depth": depth[:, None].astype(np.float32), "state": state.astype(np.float32)}


class FreeDirectionBaseline:
    """A scripted reactive baseline, after the vector field histogram (Borenstein and Koren 1991) on
    the depth image alone: the rows near the horizon give each column's obstacle (the median of
    their depths, over the pixels whose points stand above the ground: the depth noise grows as z^2
    and a minimum over noisy pixels makes phantoms), its bearing and range; a bearing in view is
    free when no such point lies within radius + margin_m of the straight path along it over
    look_ahead_m. Each vehicle turns toward the free bearing nearest the goal's and flies along its
    heading, slower as that path's first point comes closer, holding the goal's height. With no free
    bearing in view it backs off and turns, the way it started to turn (toward the side whose
    columns see farther). Its one memory is that turn; `reset(mask)` forgets it."""

    def __init__(
        self,
        env: NavigateClutterEnv,
        *,
        look_ahead_m: float = 2.0,
        margin_m: float = 0.2,
        speed: float = 0.5,
        back_off: float = 0.1,
    ):
        camera = env.batch.depth_camera
        self.env = env
        self.max_range_m, self.radius_m = env.max_range_m, env.batch.collision_radius
        self.look_ahead_m, self.margin_m, self.speed, self.back_off = look_ahead_m, margin_m, speed, back_off
        w, h = camera["width"], camera["height"]
        fx = w / (2.0 * np.tan(camera["horizontal_fov"] / 2.0))
        fy = h / (2.0 * np.tan(camera["vertical_fov"] / 2.0))
        self.x = (np.arange(w) - (w - 1) / 2.0) / fx
        self.bearing = np.arctan(-self.x)  # left positive
        y = (np.arange(h) - (h - 1) / 2.0) / fy
        self.level = np.abs(y) < 0.25  # within about 14 deg of the horizon
        self.row_y = y[self.level]
        self.camera_xyz = np.asarray(camera["xyz"], dtype=float)
        self.turn = np.zeros(env.num_envs)  # +1 left, -1 right, 0 not turning

    def reset(self, mask: np.ndarray) -> None:
        self.turn[mask] = 0.0

    def __call__(self, obs: dict[str, np.ndarray]) -> np.ndarray:
        odometry = self.env.batch.odometry
        R = rotation_rows(odometry[:, 3:7])
        depth = obs["depth"][:, 0][:, self.level, :] * self.max_range_m  # N x L x W, along the axis [m]
        # a pixel's point in the model frame: camera + d (1, -x, -y); its height: p_z + (R that)_z
        point_M = np.stack(
            [
                self.camera_xyz[0] + depth,
                self.camera_xyz[1] - self.x[None, None, :] * depth,
                self.camera_xyz[2] - self.row_y[None, :, None] * depth,
            ],
            axis=-1,
        )
        z_W = odometry[:, 2, None, None] + np.einsum("nk,nlwk->nlw", R[:, 2, :], point_M)
        depth = np.where((z_W > 0.3) & (depth < 0.999 * self.max_range_m), depth, np.nan)
        with warnings.catch_warnings():  # a column with no point: NaN, which is what it means here
            warnings.simplefilter("ignore", RuntimeWarning)
            along_axis = np.nanmedian(depth, axis=1)  # N x W (NaN: nothing in the column)
        seen = np.isfinite(along_axis)
        n = depth.shape[0]
        rows = np.arange(n)
        nearest = np.where(seen, along_axis, np.inf) * np.sqrt(1.0 + self.x * self.x)[None, :]  # range [m]
        # point j against bearing k: along = r cos(b_j - b_k), across = r |sin(b_j - b_k)|
        diff = self.bearing[None, :, None] - self.bearing[None, None, :]
        with np.errstate(invalid="ignore"):
            along = nearest[:, :, None] * np.cos(diff)
            across = nearest[:, :, None] * np.abs(np.sin(diff))
        in_path = seen[:, :, None] & (along > 0.0) & (across < self.radius_m + self.margin_m)
        clearance = np.where(in_path, along, np.inf).min(axis=1)  # N x W: the path's first point
        free = clearance > self.look_ahead_m
        goal = obs["state"][:, 0:3]
        goal_bearing = np.arctan2(goal[:, 1], goal[:, 0])
        cost = np.where(free, np.abs(self.bearing[None, :] - goal_bearing[:, None]), np.inf)
        best = cost.argmin(axis=1)
        any_free = np.isfinite(cost[rows, best])
        chosen = self.bearing[best]
        # stuck: keep turning the way it turns; a new turn goes to the side whose columns see farther
        starting = ~any_free & (self.turn == 0.0)
        far = np.where(seen, nearest, self.max_range_m)
        room_left, room_right = far[:, : len(self.x) // 2].mean(axis=1), far[:, len(self.x) // 2 :].mean(axis=1)
        self.turn[starting] = np.where(room_left[starting] >= room_right[starting], 1.0, -1.0)
        self.turn[any_free] = 0.0
        room = np.minimum(clearance[rows, best], self.max_range_m)
        go = self.speed * np.clip(room / (2.0 * self.look_ahead_m), 0.3, 1.0)
        action = np.zeros((n, 4))
        # along the heading, which the camera sees; stuck, it backs away from what is ahead
        action[:, 0] = np.where(any_free, go * np.cos(chosen) ** 2, -self.back_off)
        action[:, 2] = np.clip(goal[:, 2], -1.0, 1.0)
        action[:, 3] = np.where(any_free, np.clip(2.0 * chosen, -1.0, 1.0), self.turn)
        return action


OUTCOMES = ("goal", "collision", "left", "time")


def fly_courses(env: NavigateClutterEnv, act, seed: int = 0) -> dict[str, float]:
    """Each vehicle of `env` (autoreset off, step_after_end on) flies one course of reset(seed=seed)
    under act(obs) -> actions, until every one has ended; how many reached the goal, collided, left
    the course or ran out of time, and the mean episode return. The vehicles that ended fly on
    unscored until the last ends."""
    if env.autoreset or not env.step_after_end:
        raise SimError("fly_courses needs NavigateClutterEnv(..., autoreset=False, step_after_end=True)")
    obs, _ = env.reset(seed=seed)
    outcome = np.full(env.num_envs, "", dtype=object)
    returns = np.zeros(env.num_envs)
    while (outcome == "").any():
        obs, reward, terminated, truncated, info = env.step(act(obs))
        returns += np.where(outcome == "", reward, 0.0)
        for i in np.flatnonzero((terminated | truncated) & (outcome == "")):
            outcome[i] = "goal" if info["success"][i] else "collision" if info["collided"][i] else "left" if terminated[i] else "time"
    return {**{k: int((outcome == k).sum()) for k in OUTCOMES}, "mean_return": float(returns.mean())}


def navigate_clutter_vector_env(num_envs: int = 16, **kwargs: Any) -> NavigateClutterEnv:
    """RotorS/NavigateClutter-v0's vector entry point: gym.make_vec("RotorS/NavigateClutter-v0",
    num_envs, vectorization_mode="vector_entry_point")."""
    kwargs.pop("render_mode", None)
    return NavigateClutterEnv(num_envs, **kwargs)
