"""The command line shared by the evaluation scripts (RotorS' options and defaults, section 1.6)."""
import argparse
from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Sequence


def str2bool(value) -> bool:
    """RotorS' documentation types `--save_plots True`; accept that and the bare flag."""
    if isinstance(value, bool):
        return value
    text = str(value).strip().lower()
    if text in ("true", "1", "yes", "on"):
        return True
    if text in ("false", "0", "no", "off"):
        return False
    raise argparse.ArgumentTypeError(f"'{value}' is not a boolean (use True or False)")


@dataclass
class EvalOptions:
    bagfiles: Sequence[Path]
    mav_name: str
    pose_topic: str
    twist_topic: str
    motor_velocity_topic: str
    waypoint_topic: str
    wrench_topic: str
    save_plots: bool
    prefix: str
    plot: bool
    begin_time: float
    end_time: float
    rms_calc_time: float
    settling_radius: float
    min_settled_time: float
    delay_first_evaluation: float
    disturbance_time: float
    json: Optional[Path]
    plot_dir: Path


def parse(description: str, argv: Optional[Sequence[str]] = None, many_bags: bool = False) -> EvalOptions:
    p = argparse.ArgumentParser(description=description)
    p.add_argument("-b", "--bagfile", required=True, nargs="+" if many_bags else None, type=Path,
                   help="bag file(s) to evaluate")
    p.add_argument("-p", "--pose_topic", default="/ground_truth/pose")
    p.add_argument("-t", "--twist_topic", default="/ground_truth/twist")
    p.add_argument("-s", "--save_plots", nargs="?", const=True, default=False, type=str2bool,
                   help="save the plots as PNG (also: --save_plots True)")
    p.add_argument("--prefix", default="", help="file name prefix of the saved plots")
    p.add_argument("-d", "--plot", nargs="?", const=True, default=True, type=str2bool,
                   help="show the plots when a display exists (default true)")
    p.add_argument("--begin_time", type=float, default=0.0)
    p.add_argument("-e", "--end_time", type=float, default=1000.0)
    p.add_argument("--rms_calc_time", type=float, default=10.0, help="[s] length of the RMS window")
    p.add_argument("--settling_radius", type=float, default=0.1, help="[m]")
    p.add_argument("--min_settled_time", type=float, default=3.0, help="[s]")
    p.add_argument("-m", "--motor_velocity_topic", default="/motor_speed")
    p.add_argument("-w", "--waypoint_topic", default="/command/trajectory")
    p.add_argument("-W", "--wrench_topic", default="/wrench")
    p.add_argument("-D", "--delay_first_evaluation", type=float, default=5.0, help="[s]")
    p.add_argument("--disturbance_time", type=float, default=40.0,
                   help="[s] when the disturbance starts (disturbance_eval; 40 s: mav_with_wind_gust's gust)")
    p.add_argument("-n", "--mav_name", default="")
    p.add_argument("--json", type=Path, help="also write a machine-readable summary here ('-' = stdout)")
    p.add_argument("--plot_dir", type=Path, default=Path("."), help="where saved plots go (default: cwd)")
    a = p.parse_args(argv)
    bags = a.bagfile if many_bags else [a.bagfile]
    return EvalOptions(bags, a.mav_name, a.pose_topic, a.twist_topic, a.motor_velocity_topic, a.waypoint_topic,
                       a.wrench_topic, a.save_plots, a.prefix, a.plot, a.begin_time, a.end_time, a.rms_calc_time,
                       a.settling_radius, a.min_settled_time, a.delay_first_evaluation, a.disturbance_time, a.json,
                       a.plot_dir)
