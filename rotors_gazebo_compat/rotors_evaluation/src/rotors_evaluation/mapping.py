"""mapping_eval.py: a map built in flight (rotors_mapping_node's .bt) against the world's ground
truth (world/get_octomap's .bt at the same resolution): precision and recall of occupied leaves, the
volume the sensors observed, and a top view of the cells (true and false positives, missed)."""

import argparse
import logging
import os
import shutil
import subprocess
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotors_evaluation.options import str2bool

LABELS = (
    "occupied, on a truth leaf",
    "occupied, no truth leaf within one cell",
    "truth seen, missed",
    "truth not seen",
    "occupied, next to a truth leaf",
)
COLOURS = ("tab:green", "tab:red", "tab:orange", "0.85", "tab:blue")


@dataclass
class MappingResult:
    figures: dict[str, float]
    plot: Path | None = None


def bt_resolution(path: Path) -> float:
    """The `res` line of a .bt header; ValueError naming the file if it is no OctoMap."""
    with open(path, "rb") as f:
        for _ in range(8):
            line = f.readline().decode("ascii", "replace").strip()
            if line.startswith("res "):
                return float(line.split()[1])
    raise ValueError(f"'{path}' is no binary OctoMap (.bt): no 'res' line in its header")


def truth_from_service(built: Path, out: Path, center: Sequence[float], lengths: Sequence[float]) -> Path:
    """Asks the running simulator's world/get_octomap for the truth at the built map's resolution."""
    import rospy  # only with a simulator running
    from geometry_msgs.msg import Point
    from rotors_comm.srv import Octomap

    rospy.wait_for_service("/world/get_octomap", timeout=30)
    rospy.ServiceProxy("/world/get_octomap", Octomap)(
        bounding_box_origin=Point(*center),
        bounding_box_lengths=Point(*lengths),
        leaf_size=bt_resolution(built),
        publish_octomap=False,
        filename=str(out.resolve()),
    )
    return out


def compare(built: Path, truth: Path, cells_csv: Path | None) -> dict[str, float]:
    tool = shutil.which("rotors_map_compare") or "rotors_map_compare"
    cmd = [tool, str(built), str(truth)] + ([str(cells_csv)] if cells_csv else [])
    if not shutil.which("rotors_map_compare"):
        cmd = ["rosrun", "rotors_planning", "rotors_map_compare"] + cmd[1:]
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:  # its own line is the last (OctoMap may print one before it)
        lines = res.stderr.strip().splitlines()
        raise ValueError(lines[-1] if lines else f"rotors_map_compare failed ({res.returncode})")
    return {k: float(v) for k, v in (line.split() for line in res.stdout.splitlines())}


def plot_cells(cells_csv: Path, out: Path, show: bool, z_range: Sequence[float]) -> Path:
    import matplotlib

    if not os.environ.get("DISPLAY"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cells = np.loadtxt(cells_csv, delimiter=",", skiprows=1, ndmin=2)
    cells = cells[(cells[:, 2] >= z_range[0]) & (cells[:, 2] <= z_range[1])]
    fig, ax = plt.subplots(figsize=(7, 7))
    for label in (3, 2, 0, 4, 1):  # truth not seen at the back, false positives on top
        c = cells[cells[:, 3] == label]
        ax.scatter(c[:, 0], c[:, 1], s=1, color=COLOURS[label], label=f"{LABELS[label]} ({len(c)})")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal")
    ax.set_title(f"map built in flight vs the world's octomap, top view of z {z_range[0]:g}-{z_range[1]:g} m")
    ax.legend(loc="upper right", markerscale=8, fontsize=8)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    if show:
        plt.show()
    return out


def parse(argv: Sequence[str] | None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("-m", "--map", type=Path, required=True, help="the built map (.bt), e.g. rotors_mapping_node's save_path")
    p.add_argument("-t", "--truth", type=Path, help="the ground truth (.bt) at the same resolution")
    p.add_argument(
        "--from_service",
        type=float,
        nargs=6,
        metavar=("CX", "CY", "CZ", "LX", "LY", "LZ"),
        help="ask the running simulator's world/get_octomap for the truth in this box instead [m]",
    )
    p.add_argument("-s", "--save_plots", nargs="?", const=True, default=False, type=str2bool)
    p.add_argument("-d", "--plot", nargs="?", const=True, default=False, type=str2bool, help="show the plot")
    p.add_argument("--plot_dir", type=Path, default=Path("."))
    p.add_argument(
        "--z_range",
        type=float,
        nargs=2,
        default=(1.0, 100.0),
        metavar=("MIN", "MAX"),
        help="[m] the height band the plot shows (default 1-100 m: without the ground)",
    )
    a = p.parse_args(argv)
    if (a.truth is None) == (a.from_service is None):
        p.error("give the truth as --truth FILE.bt or --from_service CX CY CZ LX LY LZ")
    return a


def main(argv: Sequence[str] | None = None) -> int:
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    a = parse(argv)
    for path, what in ((a.map, "map"), (a.truth, "truth")):
        if path is not None and not path.is_file():
            print(f"mapping_eval: the {what} file '{path}' does not exist")
            return 1
    try:
        truth = a.truth or truth_from_service(a.map, a.plot_dir / "truth.bt", a.from_service[:3], a.from_service[3:])
        cells = a.plot_dir / "mapping_cells.csv" if (a.save_plots or a.plot) else None
        if cells:
            a.plot_dir.mkdir(parents=True, exist_ok=True)
        f = compare(a.map, truth, cells)
    except (OSError, ValueError) as e:
        print(f"mapping_eval: {e}")
        return 1
    print(
        f"Resolution: {f['resolution']:.3f} m; built map: {int(f['built_occupied'])} occupied and "
        f"{int(f['built_free'])} free leaves: {f['known_volume_m3']:.0f} m^3 observed, "
        f"{f['known_volume_m3'] / max(f['truth_box_m3'], 1e-9):.1%} of the truth's box ({f['truth_box_m3']:.0f} m^3)"
    )
    print(f"Ground truth: {int(f['truth_occupied'])} occupied leaves, {int(f['seen_truth'])} of them seen")
    # a hit on a face that lies on a cell boundary lands in either cell by rounding: "within one
    # cell" counts an occupied leaf that touches a truth leaf as on the surface
    print(f"Precision: {f['precision_within_one']:.3f} of the occupied leaves on or next to a truth leaf " f"({f['precision']:.3f} on one)")
    print(f"Recall of the seen leaves: {f['recall']:.3f} found exactly ({f['recall_within_one']:.3f} within one cell)")
    if cells:
        out = plot_cells(cells, a.plot_dir / "mapping.png", a.plot, a.z_range)
        if a.save_plots:
            print(f"Plot saved: {out}")
    return 0
