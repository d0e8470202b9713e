#!/usr/bin/env python3
"""The figure of docs/sensor_realism.md's VIO flights: the warehouse flight from above (the camera's
heading every 2 s of the medium flight) and the speed and yaw rate of the three difficulties.

    python3 scripts/plot_vio_flights.py docs/sensor_realism_vio_flights.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from rotors_gazebo.flight_paths import EUROC_SHAPES, mean_speed, mean_yaw_rate_deg_s, read_trajectory_file
from rotors_sim.paths import package_path


def main(out: str) -> int:
    folder = package_path("rotors_gazebo") / "resource" / "vio_flights"
    flights = {d: read_trajectory_file(folder / f"warehouse_{d}.csv") for d in EUROC_SHAPES}
    fig, (top, speed, rate) = plt.subplots(1, 3, figsize=(13, 3.8), gridspec_kw=dict(width_ratios=[1.2, 1, 1]))
    m = flights["medium"]
    top.plot(m.p_W[:, 0], m.p_W[:, 1], color="tab:blue", lw=1)
    every = int(round(2.0 / (m.t_s[1] - m.t_s[0])))
    heading = np.column_stack([np.cos(m.yaw[::every]), np.sin(m.yaw[::every])])
    top.quiver(m.p_W[::every, 0], m.p_W[::every, 1], heading[:, 0], heading[:, 1], scale=12, width=0.005, color="tab:orange")
    top.plot(*m.p_W[0, :2], "ko")
    top.set_aspect("equal")
    top.set_xlabel("x [m]")
    top.set_ylabel("y [m]")
    top.set_title("warehouse flight from above; camera heading every 2 s (medium)", fontsize=9)
    for d, f in flights.items():
        sequence, shape = EUROC_SHAPES[d]
        speed_label = f"{d}: mean {mean_speed(f):.2f} m/s (EuRoC {sequence} {shape.mean_speed_m_s})"
        rate_label = f"{d}: mean |r| {mean_yaw_rate_deg_s(f):.1f} deg/s ({shape.mean_angular_rate_deg_s})"
        speed.plot(f.t_s, np.linalg.norm(f.v_W, axis=1), lw=0.9, label=speed_label)
        rate.plot(f.t_s, np.degrees(f.yaw_rate), lw=0.7, label=rate_label)
    speed.set_xlabel("t [s]")
    speed.set_ylabel("speed [m/s]")
    rate.set_xlabel("t [s]")
    rate.set_ylabel("yaw rate [deg/s]")
    speed.legend(fontsize=7, loc="upper right")
    rate.legend(fontsize=7, loc="upper right")
    speed.set_ylim(0, 2.2)
    rate.set_ylim(-80, 120)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "sensor_realism_vio_flights.png"))
