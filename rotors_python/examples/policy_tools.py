"""The exported hover policies without a learning framework: their forward pass (what rl_policy_node
computes), their score in the batch, and a plot of their flights there.
    python policy_tools.py --plot ../../docs/policy_batch_flights.png"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from rotors_sim.envs import FlightBatchEnv
from rotors_sim.envs.batched import rotation_rows

POLICIES = Path(__file__).resolve().parents[2] / "rotors_control" / "policies"
# the airframe the docs score: 20 % more mass, 15 % weaker motors (mass_scale:=1.2 motor_constant_scale:=0.85)
HEAVY_WEAK = {"mass": ("fixed", 1.2), "motorConstant": ("fixed", 0.85)}


def features(obs: np.ndarray) -> np.ndarray:
    """What the policy sees of rows of RotorS/Hover-v0 observations [e_p, v_W, q (x, y, z, w), omega_B]:
    [e_p, v_W, R(q) row by row, omega_B] (18). The rotation matrix is continuous in the attitude,
    where a quaternion's components jump with its sign (the batch keeps w >= 0, so q_z flips at a
    yaw of 180 deg)."""
    o = np.asarray(obs, dtype=np.float64)
    rotation = rotation_rows(o[:, 6:10]).reshape(len(o), 9)
    return np.hstack([o[:, 0:6], rotation, o[:, 10:13]])


def forward(policy: dict, obs: np.ndarray) -> np.ndarray:
    """The exported policy on rows of observations (what rl_policy_node computes)."""
    h = features(obs)
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


def error_traces(policy: dict, spec: dict | None, seconds: float = 10.0, vehicles: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Times and |p - p_target| of `vehicles` batch flights from the hover starts."""
    envs = FlightBatchEnv("hover", vehicles, action_type="attitude", episode_s=seconds + 1.0, randomization=spec, sensor_seed=100)
    obs, _ = envs.reset(seed=1000)
    errors, ended = [np.linalg.norm(obs[:, 0:3], axis=1)], np.zeros(vehicles, dtype=bool)
    for _ in range(int(round(seconds / envs.dt))):
        obs, _, terminated, _, _ = envs.step(forward(policy, obs.astype(np.float64)))
        ended |= terminated  # a crashed vehicle starts again (autoreset): its trace ends here
        errors.append(np.where(ended, np.nan, np.linalg.norm(obs[:, 0:3], axis=1)))
    return np.arange(len(errors)) * envs.dt, np.array(errors)


def main() -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    parser = argparse.ArgumentParser()
    parser.add_argument("--plot", required=True)
    args = parser.parse_args()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharey=True)
    for ax, (airframe, spec) in zip(axes, (("the xacro's firefly", None), ("+20 % mass, -15 % motor constant", HEAVY_WEAK))):
        for name, color in (("randomized", "tab:blue"), ("nominal", "tab:orange")):
            policy = dict(np.load(POLICIES / f"firefly_hover_{name}.npz"))
            t, e = error_traces(policy, spec)
            ax.plot(t, e, color=color, alpha=0.35, lw=0.8)
            ax.plot(
                [],
                [],
                color=color,
                label=f"policy trained {'on randomised airframes' if name == 'randomized' else 'on the xacro airframe'}",
            )
        ax.set_title(airframe)
        ax.set_xlabel("time [s]")
        ax.set_yscale("log")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("|p - p_target| [m] (16 starts each)")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(args.plot)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
