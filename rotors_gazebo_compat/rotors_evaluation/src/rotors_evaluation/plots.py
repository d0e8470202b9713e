"""Plots of a flight (book figures 11 and 12): position, position error and angular velocity."""

import os
from collections.abc import Sequence
from pathlib import Path

import matplotlib

if not os.environ.get("DISPLAY"):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rotors_evaluation.bag_data import FlightData  # noqa: E402


def _finish(fig, name: str, out_dir: Path, prefix: str, save: bool, saved: list[Path]) -> None:
    fig.tight_layout()
    if save:
        out_dir.mkdir(parents=True, exist_ok=True)
        path = out_dir / f"{prefix}{name}.png"
        fig.savefig(path, dpi=100)
        saved.append(path)


def plot_flight(
    data: FlightData,
    setpoints: Sequence[np.ndarray],
    segment_starts: Sequence[float],
    settle_marks: Sequence[float | None],
    out_dir: Path,
    prefix: str,
    save: bool,
    show: bool,
) -> list[Path]:
    """Returns the saved files. setpoints[i] holds from segment_starts[i]; settle_marks[i] is the
    absolute settling time of segment i (None: not settled)."""
    saved: list[Path] = []
    t, p = data.position.t, data.position.values
    seg = np.searchsorted(np.asarray(segment_starts), t, side="right") - 1
    ref = np.array([setpoints[max(i, 0)] for i in seg]) if len(setpoints) else np.zeros_like(p)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for k, label in enumerate("xyz"):
        ax.plot(t, p[:, k], label=label)
        if len(setpoints):
            ax.plot(t, ref[:, k], "--", linewidth=0.8, color=f"C{k}")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("position [m]")
    ax.set_title("Position (dashed: set point)")
    ax.legend()
    ax.grid(True)
    _finish(fig, "position", out_dir, prefix, save, saved)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, np.linalg.norm(p - ref, axis=1), label="|p - p_sp|")
    for s in settle_marks:
        if s is not None:
            ax.axvline(s, color="g", linestyle=":", label="settled")
    ax.set_ylim(0.0, 1.0)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("position error [m]")
    ax.set_title("Position error")
    ax.grid(True)
    ax.legend()
    _finish(fig, "position_error", out_dir, prefix, save, saved)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    w = data.angular_velocity
    for k, label in enumerate(("p (x)", "q (y)", "r (z)")):
        ax.plot(w.t, w.values[:, k], label=label)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("angular velocity [rad/s]")
    ax.set_title("Angular velocity")
    ax.legend()
    ax.grid(True)
    _finish(fig, "angular_velocities", out_dir, prefix, save, saved)

    if show and os.environ.get("DISPLAY"):
        plt.show()
    plt.close("all")
    return saved
