#!/usr/bin/env python3
"""The book's hovering example from Python (rotors_sim, no ROS): the firefly takes off to (0, 0, 1)
when the waypoint is due at 5 s and hovers 0.040 m above it, as the ROS example does. Saves a plot.
    python hover_plot.py [out.png]"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rotors_sim.examples import hovering_example  # noqa: E402


def main() -> int:
    out = sys.argv[1] if len(sys.argv) > 1 else "python_hover.png"
    flight = hovering_example(random_seed=42, duration_s=15.0)
    t, p = flight.time_s, flight.position_W
    speeds = np.array([s for _, s in flight.commands])
    t_cmd = np.array([t for t, _ in flight.commands])
    offset = p[t > 10.0].mean(axis=0) - np.array([0.0, 0.0, 1.0])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for i, axis in enumerate("xyz"):
        ax1.plot(t, p[:, i], label=f"{axis} (ground truth)")
    ax1.axhline(1.0, color="grey", ls="--", lw=0.8, label="set point z = 1 m")
    ax1.axvline(5.0, color="grey", ls=":", lw=0.8)
    ax1.set_ylabel("position [m]")
    ax1.set_title(f"firefly hovering example from Python (rotors_sim, no ROS): z offset {offset[2]:.3f} m")
    ax1.legend(loc="center right", fontsize=8)
    ax2.plot(t_cmd, speeds, lw=0.8)
    ax2.set_ylabel("rotor speed command [rad/s]")
    ax2.set_xlabel("sim time [s] (waypoint due at 5 s)")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"{out}: offset after settling {offset.round(4)} m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
