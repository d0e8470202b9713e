"""The command line shared by the evaluation scripts (RotorS' options and defaults, section 1.6)."""

import argparse
from collections.abc import Sequence
from dataclasses import dataclass, fields, replace
from pathlib import Path


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
    """Every option of the evaluation scripts, with RotorS' defaults: the one source of truth for the
    command line (parse) and for the sweeps (TUNABLE, with_overrides)."""

    bagfiles: Sequence[Path] = ()
    mav_name: str = ""
    pose_topic: str = "/ground_truth/pose"
    twist_topic: str = "/ground_truth/twist"
    motor_velocity_topic: str = "/motor_speed"
    waypoint_topic: str = "/command/trajectory"
    wrench_topic: str = "/wrench"
    save_plots: bool = False
    prefix: str = ""
    plot: bool = True
    begin_time: float = 0.0  # [s]
    end_time: float = 1000.0  # [s]
    rms_calc_time: float = 10.0  # [s] length of the RMS window
    settling_radius: float = 0.1  # [m]
    min_settled_time: float = 3.0  # [s]
    delay_first_evaluation: float = 5.0  # [s]
    disturbance_time: float = 40.0  # [s] when the disturbance starts (mav_with_wind_gust's gust)
    json: Path | None = None
    plot_dir: Path = Path(".")


# the numeric options a sweep may set in its eval_options
TUNABLE = tuple(f.name for f in fields(EvalOptions) if f.type in (float, "float"))


def with_overrides(bag: Path, mav_name: str, **overrides: float) -> EvalOptions:
    """The defaults for one bag with some numeric options changed (a sweep's eval_options);
    ValueError naming an option that is not in TUNABLE."""
    unknown = sorted(set(overrides) - set(TUNABLE))
    if unknown:
        raise ValueError(f"unknown evaluation option(s) {', '.join(unknown)} (known: {', '.join(TUNABLE)})")
    return replace(EvalOptions(), bagfiles=[bag], mav_name=mav_name, **{k: float(v) for k, v in overrides.items()})


def parse(description: str, argv: Sequence[str] | None = None, many_bags: bool = False) -> EvalOptions:
    p = argparse.ArgumentParser(description=description)
    p.add_argument("-b", "--bagfile", required=True, nargs="+" if many_bags else None, type=Path, help="bag file(s) to evaluate")
    p.add_argument("-p", "--pose_topic", default=EvalOptions.pose_topic)
    p.add_argument("-t", "--twist_topic", default=EvalOptions.twist_topic)
    p.add_argument(
        "-s", "--save_plots", nargs="?", const=True, default=False, type=str2bool, help="save the plots as PNG (also: --save_plots True)"
    )
    p.add_argument("--prefix", default="", help="file name prefix of the saved plots")
    p.add_argument(
        "-d", "--plot", nargs="?", const=True, default=True, type=str2bool, help="show the plots when a display exists (default true)"
    )
    p.add_argument("--begin_time", type=float, default=EvalOptions.begin_time)
    p.add_argument("-e", "--end_time", type=float, default=EvalOptions.end_time)
    p.add_argument("--rms_calc_time", type=float, default=EvalOptions.rms_calc_time, help="[s] length of the RMS window")
    p.add_argument("--settling_radius", type=float, default=EvalOptions.settling_radius, help="[m]")
    p.add_argument("--min_settled_time", type=float, default=EvalOptions.min_settled_time, help="[s]")
    p.add_argument("-m", "--motor_velocity_topic", default=EvalOptions.motor_velocity_topic)
    p.add_argument("-w", "--waypoint_topic", default=EvalOptions.waypoint_topic)
    p.add_argument("-W", "--wrench_topic", default=EvalOptions.wrench_topic)
    p.add_argument("-D", "--delay_first_evaluation", type=float, default=EvalOptions.delay_first_evaluation, help="[s]")
    p.add_argument(
        "--disturbance_time",
        type=float,
        default=EvalOptions.disturbance_time,
        help="[s] when the disturbance starts (disturbance_eval; 40 s: mav_with_wind_gust's gust)",
    )
    p.add_argument("-n", "--mav_name", default="")
    p.add_argument("--json", type=Path, help="also write a machine-readable summary here ('-' = stdout)")
    p.add_argument("--plot_dir", type=Path, default=Path("."), help="where saved plots go (default: cwd)")
    a = p.parse_args(argv)
    bags = a.bagfile if many_bags else [a.bagfile]
    return EvalOptions(
        bags,
        a.mav_name,
        a.pose_topic,
        a.twist_topic,
        a.motor_velocity_topic,
        a.waypoint_topic,
        a.wrench_topic,
        a.save_plots,
        a.prefix,
        a.plot,
        a.begin_time,
        a.end_time,
        a.rms_calc_time,
        a.settling_radius,
        a.min_settled_time,
        a.delay_first_evaluation,
        a.disturbance_time,
        a.json,
        a.plot_dir,
    )
