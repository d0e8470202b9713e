#!/usr/bin/env python3
"""The figure of docs/sensor_realism.md's scored VIO runs: each run's ATE as a share of the path,
by flight and sensor_realism setting, from a CSV (flight, sensor_realism, start_s, ate_rmse_m,
path_m); a run whose error passes 10 % of the path is drawn as diverged at the top.

    python3 scripts/plot_vio_runs.py docs/sensor_realism_openvins_runs.csv docs/sensor_realism_openvins.png
"""

import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

DIVERGED_PERCENT = 10.0


def main(table: str, out: str) -> int:
    with open(table) as f:
        rows = list(csv.DictReader(f))
    groups: dict[tuple[str, str], list[float]] = {}
    for r in rows:
        groups.setdefault((r["flight"], r["sensor_realism"]), []).append(100.0 * float(r["ate_rmse_m"]) / float(r["path_m"]))
    fig, ax = plt.subplots(figsize=(8, 3.8))
    labels = []
    for x, ((flight, realism), shares) in enumerate(sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1] != "false"))):
        shares = np.array(shares)
        kept = shares[shares < DIVERGED_PERCENT]
        color = "tab:red" if realism == "true" else "tab:blue"
        ax.scatter(np.full(len(kept), x), kept, color=color, s=22, zorder=3)
        diverged = int((shares >= DIVERGED_PERCENT).sum())
        if diverged:
            ax.scatter([x], [DIVERGED_PERCENT * 0.8], marker="x", color=color, s=40)
            ax.annotate(f"{diverged} diverged", (x, DIVERGED_PERCENT * 0.8), textcoords="offset points", xytext=(6, -3), fontsize=7)
        median = np.median(shares)
        ax.hlines(min(median, DIVERGED_PERCENT * 0.8), x - 0.25, x + 0.25, color=color, lw=1.5)
        labels.append(f"{flight.replace('warehouse_', '')}\nsensor_realism:={realism}")
    ax.set_yscale("log")
    ax.set_xticks(range(len(labels)), labels, fontsize=8)
    ax.set_ylabel("ATE RMSE [% of the path]")
    ax.set_title("OpenVINS on the warehouse VIO flights, started 0 to 4 s into each bag (bar: median)", fontsize=9)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
