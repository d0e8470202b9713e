#!/usr/bin/env python3
"""A VIO's estimates against the ground truth of the flights they were run on: the path from above
(ground truth and each SE(3)-aligned estimate) and the position error over time, with evo's ATE,
for docs/sensor_realism.md's scored flights.

    python3 scripts/plot_vio_error.py out.png "label=estimate.txt:<export>/mav0" ...

Each estimate is a TUM file (t x y z qx qy qz qw, the IMU's pose in the VIO's world); each export
is export_euroc.py's mav0 folder of the same flight (state_groundtruth_estimate0/data.csv: the
IMU's pose). Prints one line per estimate: poses, path length, ATE RMSE and its share of the path.
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from evo.core import metrics, sync
from evo.tools import file_interface


def scored(estimate: str, mav0: str):
    """(ground truth, aligned estimate, per-pose error [m], ATE statistics) of one run."""
    truth = file_interface.read_euroc_csv_trajectory(f"{mav0}/state_groundtruth_estimate0/data.csv")
    est = file_interface.read_tum_trajectory_file(estimate)
    truth, est = sync.associate_trajectories(truth, est, max_diff=0.002)
    est.align(truth, correct_scale=False)
    ape = metrics.APE(metrics.PoseRelation.translation_part)
    ape.process_data((truth, est))
    return truth, est, ape.error, ape.get_all_statistics()


def main(out: str, runs: list[str]) -> int:
    if not runs:
        print(__doc__, file=sys.stderr)
        return 2
    fig, (top, err) = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw=dict(width_ratios=[1, 1.4]))
    drawn_truth = set()
    for run in runs:
        label, rest = run.split("=", 1)
        estimate, mav0 = rest.split(":", 1)
        truth, est, error, stats = scored(estimate, mav0)
        length = truth.path_length
        share = 100 * stats["rmse"] / length
        print(
            f"{label}: {len(est.timestamps)} poses, path {length:.1f} m, ATE RMSE {stats['rmse']:.3f} m "
            f"({share:.2f} % of the path), max {stats['max']:.3f} m"
        )
        if mav0 not in drawn_truth:
            top.plot(
                truth.positions_xyz[:, 0], truth.positions_xyz[:, 1], color="k", lw=1.0, label="ground truth" if not drawn_truth else None
            )
            drawn_truth.add(mav0)
        top.plot(est.positions_xyz[:, 0], est.positions_xyz[:, 1], lw=0.9, label=label)
        t = est.timestamps - est.timestamps[0]
        err.plot(t, error, lw=0.9, label=f"{label}: ATE {stats['rmse']:.3f} m ({100 * stats['rmse'] / length:.2f} %)")
    top.set_aspect("equal")
    top.set_xlabel("x [m]")
    top.set_ylabel("y [m]")
    top.set_title("from above, estimates aligned in SE(3)", fontsize=9)
    top.legend(fontsize=7)
    err.set_xlabel("t since the VIO's first pose [s]")
    err.set_ylabel("position error [m]")
    err.set_title("position error after alignment (evo APE)", fontsize=9)
    err.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2:]) if len(sys.argv) > 1 else main("", []))
