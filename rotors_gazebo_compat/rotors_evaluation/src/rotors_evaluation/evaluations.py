"""Hovering, waypoint and disturbance evaluations (RotorS' scripts, section 1.6 of the reference):
load -> metrics -> report. Each returns a result dataclass; main() prints RotorS' lines."""

import json
import logging
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from rotors_evaluation import metrics
from rotors_evaluation.bag_data import BagError, FlightBag, FlightData, load_flight
from rotors_evaluation.options import EvalOptions, parse
from rotors_evaluation.plots import plot_flight

POSITION_SCORES = (0.0, 1.5, 3.5, 5.0)  # max 0.2 m
ANGULAR_SCORES = (0.0, 1.0, 2.0, 3.0)  # max 0.2 rad/s
SETTLING_SCORES = (0.0, 1.5, 3.5, 5.0)  # max 10 s


@dataclass
class SegmentResult:
    waypoint: list[float]  # x, y, z, yaw
    start_time: float  # [s]
    settling_time: float | None  # [s] after start; None: not settled / not evaluated
    position_rms: float  # [m]
    angular_velocity_rms: float  # [rad/s]


@dataclass
class EvalResult:
    bag: str
    mav_name: str
    kind: str
    segments: list[SegmentResult] = field(default_factory=list)
    collision_times: list[float] = field(default_factory=list)
    position_rms: float = float("nan")
    angular_velocity_rms: float = float("nan")
    settling_time: float | None = None
    scores: dict = field(default_factory=dict)
    plots: list[str] = field(default_factory=list)
    topics: dict = field(default_factory=dict)  # what each series was read from (old bags use other names)


def _load(opts: EvalOptions, bag: Path) -> FlightData:
    return load_flight(
        bag, opts.mav_name, opts.pose_topic, opts.twist_topic, opts.waypoint_topic, opts.wrench_topic, opts.motor_velocity_topic
    )


def _window_rms(data: FlightData, setpoint: np.ndarray, begin: float, end: float):
    return (
        metrics.rms_error(data.position.window(begin, end), setpoint),
        metrics.rms_error(data.angular_velocity.window(begin, end), np.zeros(3)),
    )


def _require_waypoints(data: FlightData, opts: EvalOptions) -> None:
    if not data.waypoints:
        raise BagError(
            f"no waypoint on '{opts.waypoint_topic}' in bag '{data.path.name}'; the bag has: " f"{', '.join(sorted(data.topics.values()))}"
        )


def evaluate_hovering(data: FlightData, opts: EvalOptions, out=print) -> EvalResult:
    _require_waypoints(data, opts)
    wp = data.waypoints[0]
    out(f"[Waypoint 0]: [{wp.position[0]:.3f}, {wp.position[1]:.3f}, {wp.position[2]:.3f}, {wp.yaw:.3f}] " f"at time {wp.t:.3f} s")
    start = max(wp.t + opts.delay_first_evaluation, opts.begin_time)
    end = min(start + opts.rms_calc_time, opts.end_time)
    out(
        f"Setting the evaluation start time {opts.delay_first_evaluation:.1f} s after the waypoint was published "
        f"(evaluating {start:.2f} s to {end:.2f} s)."
    )
    result = EvalResult(str(data.path), opts.mav_name, "hovering", topics=dict(data.topics))
    pos_rms, ang_rms = _window_rms(data, wp.position, start, end)
    result.segments.append(SegmentResult([*wp.position.tolist(), wp.yaw], wp.t, None, pos_rms, ang_rms))
    result.position_rms, result.angular_velocity_rms = pos_rms, ang_rms
    _report(result, metrics.collisions_after(data.collision_times, start, opts.end_time), out)
    return result


def evaluate_waypoints(data: FlightData, opts: EvalOptions, out=print) -> EvalResult:
    _require_waypoints(data, opts)
    result = EvalResult(str(data.path), opts.mav_name, "waypoints", topics=dict(data.topics))
    t_last = float(data.position.t[-1])
    settle_times, pos_list, ang_list = [], [], []
    for i, wp in enumerate(data.waypoints):
        seg_end = data.waypoints[i + 1].t if i + 1 < len(data.waypoints) else t_last
        out(f"[Waypoint {i}]: [{wp.position[0]:.3f}, {wp.position[1]:.3f}, {wp.position[2]:.3f}, {wp.yaw:.3f}] " f"at time {wp.t:.3f} s")
        settle = None
        if i == 0:
            begin = wp.t + opts.delay_first_evaluation
        else:
            segment = data.position.window(wp.t, seg_end)
            settle = metrics.settling_time(segment, wp.position, opts.settling_radius, opts.min_settled_time, wp.t)
            if settle is None:
                out(f"  did not settle within {opts.settling_radius} m before the next waypoint")
            else:
                out(f"  settling time: {settle:.2f} s")
            begin = wp.t + settle if settle is not None else None
        if begin is None:  # RotorS inserts 101 % of the maxima for an unsettled segment
            pos, ang, settle_value = 1.01 * 0.2, 1.01 * 0.2, 1.01 * 10.0
        else:
            pos, ang = _window_rms(data, wp.position, begin, min(begin + opts.rms_calc_time, seg_end))
            settle_value = settle
        result.segments.append(SegmentResult([*wp.position.tolist(), wp.yaw], wp.t, settle, pos, ang))
        pos_list.append(pos)
        ang_list.append(ang)
        if i > 0:
            settle_times.append(settle_value)
    result.position_rms = float(np.nanmean(pos_list))
    result.angular_velocity_rms = float(np.nanmean(ang_list))
    result.settling_time = float(np.mean(settle_times)) if settle_times else None
    start = data.waypoints[0].t + opts.delay_first_evaluation
    _report(result, metrics.collisions_after(data.collision_times, start, opts.end_time), out, averages=True)
    return result


def evaluate_disturbance(data: FlightData, opts: EvalOptions, out=print) -> EvalResult:
    _require_waypoints(data, opts)
    t_d = opts.disturbance_time  # 40 s by default: mav_with_wind_gust's gust
    wp = data.waypoints[-1]
    for _i, w in enumerate(data.waypoints):
        if w.t <= t_d:
            wp = w
    result = EvalResult(str(data.path), opts.mav_name, "disturbance", topics=dict(data.topics))
    out(f"Disturbance at {t_d:.1f} s; set point [{wp.position[0]:.3f}, {wp.position[1]:.3f}, " f"{wp.position[2]:.3f}]")
    after = data.position.window(t_d, float(data.position.t[-1]))
    settle = metrics.settling_time(after, wp.position, opts.settling_radius, opts.min_settled_time, t_d)
    begin = t_d + (settle if settle is not None else 0.0)
    pos, ang = _window_rms(data, wp.position, begin, begin + opts.rms_calc_time)
    result.settling_time = settle if settle is not None else 1.01 * 10.0
    out(f"Settling time after the disturbance: {result.settling_time:.2f} s" + ("" if settle is not None else " (did not settle)"))
    result.segments.append(SegmentResult([*wp.position.tolist(), wp.yaw], t_d, settle, pos, ang))
    result.position_rms, result.angular_velocity_rms = pos, ang
    _report(result, metrics.collisions_after(data.collision_times, data.waypoints[0].t + opts.delay_first_evaluation, opts.end_time), out)
    return result


def _report(result: EvalResult, collisions: np.ndarray, out, averages: bool = False) -> None:
    result.collision_times = [float(t) for t in collisions]
    if collisions.size:
        out(f"Collision at time {collisions[0]:.3f} s!")
        out("One or more collisions occurred - no points are awarded!")
        result.scores = {"position": 0.0, "angular_velocity": 0.0, "settling_time": 0.0}
        return
    out("No collisions occurred - good job!")
    word = "Average position" if averages else "Position"
    out(f"{word} RMS error: {result.position_rms:.3f} m")
    pos_score = metrics.get_score(result.position_rms, 0.2, POSITION_SCORES)
    out(f"Score: {pos_score:.1f} of {POSITION_SCORES[-1]:.1f}")
    word = "Average angular velocity" if averages else "Angular velocity"
    out(f"{word} RMS error: {result.angular_velocity_rms:.3f} rad/s")
    ang_score = metrics.get_score(result.angular_velocity_rms, 0.2, ANGULAR_SCORES)
    out(f"Score: {ang_score:.1f} of {ANGULAR_SCORES[-1]:.1f}")
    result.scores = {"position": pos_score, "angular_velocity": ang_score}
    if result.settling_time is not None:
        settle_score = metrics.get_score(result.settling_time, 10.0, SETTLING_SCORES)
        out(f"Average settling time: {result.settling_time:.2f} s")
        out(f"Score: {settle_score:.1f} of {SETTLING_SCORES[-1]:.1f}")
        result.scores["settling_time"] = settle_score


EVALUATORS = {"hovering": evaluate_hovering, "waypoints": evaluate_waypoints, "disturbance": evaluate_disturbance}


def report_flight_end(data: FlightData, out=print) -> None:
    """One line when the bag goes on after the simulation stopped for good (the tail is ignored), one
    when lockstep did not wait for every step (the flight is not repeatable)."""
    end = data.flight_end
    if end is not None and end.dropped_s > 0.0:
        out(f"Evaluating until {end.t:.3f} s: {end.reason} (simulation_status); the last {end.dropped_s:.3f} s " f"of the bag are left out")
    if data.unwaited is not None:
        out(
            f"Not repeatable: {data.unwaited.steps} steps were not waited for in lockstep, the first because "
            f"{data.unwaited.reason} (simulation_status)"
        )


def run(kind: str, description: str, argv: Sequence[str] | None = None) -> int:
    """Entry point of hovering_eval.py, waypoint(s)_eval.py and disturbance_eval.py."""
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s: %(message)s")
    opts = parse(description, argv)
    prog = Path(sys.argv[0]).name if argv is None else f"{kind}_eval.py"
    try:
        data = _load(opts, opts.bagfiles[0])
        report_flight_end(data)
        result = EVALUATORS[kind](data, opts)
    except BagError as e:
        print(f"{prog}: {e}", file=sys.stderr)
        return 1
    setpoints = (
        [np.asarray(s.waypoint[:3]) for s in result.segments] if kind != "disturbance" else [np.asarray(result.segments[0].waypoint[:3])]
    )
    starts = [s.start_time for s in result.segments] if kind != "disturbance" else [0.0]
    marks = [None if s.settling_time is None else s.start_time + s.settling_time for s in result.segments]
    if opts.save_plots or opts.plot:
        saved = plot_flight(data, setpoints, starts, marks, opts.plot_dir, opts.prefix, opts.save_plots, opts.plot)
        result.plots = [str(p) for p in saved]
        if saved:
            print("Plots saved: " + ", ".join(result.plots))
    if opts.json:
        text = json.dumps(asdict(result), indent=2, allow_nan=True)
        if str(opts.json) == "-":
            print(text)
        else:
            opts.json.write_text(text + "\n")
    return 0


def _has_topic(path: Path, mav_name: str, topic: str) -> bool:
    bag = FlightBag(path)
    try:
        return bag.resolve(mav_name, topic) is not None
    finally:
        bag.close()


def compare(argv: Sequence[str] | None = None) -> int:
    """Tabulates the hovering metrics of several bags (controllers or estimators side by side); for
    bags holding an estimator's output (msf_core/odometry) also its error against ground truth over
    the same window."""
    from rotors_evaluation.estimator import evaluate_estimator

    opts = parse("Compare the hovering performance of several flights.", argv, many_bags=True)
    rows = []
    for bag in opts.bagfiles:
        try:
            data = _load(opts, bag)
            r = evaluate_hovering(data, opts, out=lambda *_: None)
            estimator = "-"
            if _has_topic(bag, opts.mav_name, "/msf_core/odometry"):
                start = max(data.waypoints[0].t + opts.delay_first_evaluation, opts.begin_time)
                est = evaluate_estimator(bag, opts.mav_name, begin=start, end=min(start + opts.rms_calc_time, opts.end_time))
                estimator = f"{est.position_rms:.3f}"
            rows.append((bag.name, f"{r.position_rms:.3f}", f"{r.angular_velocity_rms:.3f}", str(len(r.collision_times)), estimator))
        except BagError as e:
            rows.append((bag.name, "error", str(e), "", ""))
    header = ("bag", "position RMS [m]", "angular velocity RMS [rad/s]", "collisions", "estimator position RMS [m]")
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(header)]
    line = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()
    print(line(header))
    print(line(["-" * w for w in widths]))
    for r in rows:
        print(line(r))
    return 1 if any(r[1] == "error" for r in rows) else 0
