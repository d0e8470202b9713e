#!/usr/bin/env python3
"""The picture of RotorS/NavigateClutter-v0 in docs/batched_flight.md: four seeded courses seen from
above with the paths the scripted free-direction baseline flies through them, and one vehicle's
depth image (the batch's D435 at 64 x 48) on the way.
    python navigate_plot.py [--out navigate_clutter.png]"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402

from rotors_sim import clutter  # noqa: E402
from rotors_sim.envs.navigate import FreeDirectionBaseline, NavigateClutterEnv  # noqa: E402


def draw_course(ax, rows: np.ndarray) -> None:
    for kind, x, y, _, hx, hy, _, yaw in rows:
        if kind == clutter.CYLINDER:
            ax.add_patch(Circle((x, y), hx, color="0.45"))
        else:
            c, s = np.cos(yaw), np.sin(yaw)
            corners = np.array([[hx, hy], [-hx, hy], [-hx, -hy], [hx, -hy]]) @ np.array([[c, s], [-s, c]]) + [x, y]
            ax.add_patch(Polygon(corners, color="0.45"))


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", default="navigate_clutter.png")
    args = parser.parse_args()
    env = NavigateClutterEnv(4, autoreset=False, step_after_end=True)
    baseline = FreeDirectionBaseline(env)
    obs, _ = env.reset(seed=3)
    paths = [[] for _ in range(4)]
    ended = np.zeros(4, dtype=bool)
    snapshot = None
    for step in range(1200):
        obs, _, terminated, truncated, info = env.step(baseline(obs))
        for i in np.flatnonzero(~ended):
            paths[i].append(env.batch.truth()[i, 0:2].copy())
        if step == 150:
            snapshot = (obs["depth"][0, 0] * env.max_range_m, env.batch.truth()[0].copy())
        ended |= terminated | truncated
        if ended.all():
            break
    fig = plt.figure(figsize=(11, 6.2))
    for i in range(4):
        ax = fig.add_subplot(3, 2, 1 + i + (i // 2) * 0)
        draw_course(ax, env.field.get(i))
        path = np.array(paths[i])
        ax.plot(path[:, 0], path[:, 1], color="tab:blue", lw=1.5)
        ax.plot(*env.starts[i, 0:2], "o", color="tab:green")
        ax.plot(*env.goals[i, 0:2], "*", color="tab:red", ms=10)
        ax.set_xlim(-0.5, 20.5)
        ax.set_ylim(-4.3, 4.3)
        ax.set_aspect("equal")
        ax.set_title(f"course seed {env.course_seeds[i]}", fontsize=8)
        ax.tick_params(labelsize=7)
    depth, pose = snapshot
    ax = fig.add_subplot(3, 2, 5)
    im = ax.imshow(depth, cmap="viridis_r", vmin=0, vmax=env.max_range_m)
    ax.set_title(f"vehicle 0's depth image at t = 5.0 s (x = {pose[0]:.1f} m), 64 x 48 [m]", fontsize=8)
    ax.axis("off")
    fig.colorbar(im, ax=ax, fraction=0.03)
    fig.suptitle("RotorS/NavigateClutter-v0: the free-direction baseline's paths (blue) from start (green) to goal (red)", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
