"""One flight of a sweep, isolated: its own ROS master (on a port verified to be its own), ROS_HOME
and log folder, in lockstep and as fast as possible, stopped at its sim time or its wall-time limit,
then evaluated. run_flight never raises: a flight that fails or hangs comes back as a row with
status 'failed', the reason and the last lines of its log, so the sweep goes on."""

import json
import math
import os
import shutil
import signal
import socket
import subprocess
import threading
import time
import traceback
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import yaml

from rotors_evaluation import watchers
from rotors_evaluation.processes import graph_processes, kill_graph_leftovers, stop_process_group
from rotors_evaluation.ros_master import MasterStartError, start_own_master
from rotors_evaluation.sweep_spec import FORCED_ARGS

LOG_TAIL_LINES = 15
STALL_LIMIT_S = 60.0  # wall seconds without sim time advancing before a flight is called stalled
STOP_GRACE_S = 20.0  # wall seconds roslaunch gets to shut down (and close the bag) after Ctrl-C


class FlightFailedError(Exception):
    pass


def _alive(pid: int) -> bool:
    """The process exists and is not a zombie waiting for its parent."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat[stat.rindex(")") + 2] != "Z"


def _default_signals() -> None:
    """In the child: Ctrl-C and SIGTERM unblocked and back to their defaults (a Ray worker blocks
    SIGINT; the mask is inherited through exec, so roslaunch would never hear Ctrl-C)."""
    os.setsid()
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _log_tail(path: Path, lines: int = LOG_TAIL_LINES) -> str:
    try:
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])
    except OSError:
        return ""


def _flat(params: dict[str, Any], kind: str) -> dict[str, Any]:
    """controller.position_gain.x -> {'position_gain/x': v}: rosparam sets each leaf alone (a
    nested dict would replace the whole position_gain, dropping y and z)."""
    return {k.split(".", 1)[1].replace(".", "/"): v for k, v in params.items() if k.startswith(kind + ".")}


def _arg_text(value: Any) -> str:
    return ("true" if value else "false") if isinstance(value, bool) else str(value)


def _xacro_arg(name: str, value: Any) -> str:
    """name:=value for the xacro command line, quoted when the value holds spaces ("1 0 0")."""
    text = _arg_text(value)
    return f"{name}:='{text}'" if any(c.isspace() for c in text) or not text else f"{name}:={text}"


def launch_arguments(sweep: dict[str, Any], params: dict[str, Any], seed: int, flight_dir: Path) -> dict[str, str]:
    """The forced, fixed and varied launch arguments of this flight (parameter files written)."""
    declared = sweep["launch_args"]
    merged = {**sweep["fixed"], **params}
    args = {k: v for k, v in FORCED_ARGS.items() if k in declared}
    if "real_time_factor" in declared:
        args["real_time_factor"] = _arg_text(sweep["real_time_factor"])
    if "paused" in declared:
        args["paused"] = "true"  # the examples unpause when their nodes are up
    if "random_seed" in declared:
        args["random_seed"] = str(seed)
    if "log_file" in declared:
        args["log_file"] = "flight"
    args.update({k.split(".", 1)[1]: _arg_text(v) for k, v in merged.items() if k.startswith("launch.")})
    xacro = " ".join(_xacro_arg(k.split(".", 1)[1], v) for k, v in merged.items() if k.startswith("model."))
    if xacro:
        args["xacro_args"] = xacro
    for kind, carrier, file_name in (
        ("controller", "extra_controller_params", "controller.yaml"),
        ("estimator", "extra_msf_params", "estimator.yaml"),
    ):
        values = _flat(merged, kind)
        if values:
            (flight_dir / file_name).write_text(yaml.safe_dump(values, default_flow_style=False))
            args[carrier] = str(flight_dir / file_name)
    return args


def write_flight_launch(sweep: dict[str, Any], args: dict[str, str], flight_dir: Path) -> Path:
    """flight.launch: includes the sweep's launch file with this flight's arguments. Written as XML,
    because roslaunch's command line refuses a value that itself holds ':=' (xacro_args)."""
    lines = ["<launch>", f"  <include file={quoteattr(str(sweep['launch_file']))}>"]
    lines += [f"    <arg name={quoteattr(k)} value={quoteattr(v)}/>" for k, v in args.items()]
    lines += ["  </include>", "</launch>"]
    path = flight_dir / "flight.launch"
    path.write_text("\n".join(lines) + "\n")
    return path


def _fly(sweep: dict[str, Any], flight: dict[str, Any], flight_dir: Path, row: dict[str, Any]) -> Path:
    """Runs the launch until the sweep's sim time; returns the bag."""
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env["ROS_HOME"] = str(flight_dir)
    env["ROS_LOG_DIR"] = str(flight_dir / "log")
    (flight_dir / "log").mkdir(exist_ok=True)
    try:
        master, port = start_own_master(env, flight_dir / "rosmaster.log", preexec_fn=_default_signals)
    except MasterStartError as e:
        raise FlightFailedError(str(e)) from e
    env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    launch = watch = None
    log_path = flight_dir / "roslaunch.log"
    try:
        launch_file = write_flight_launch(sweep, launch_arguments(sweep, flight["params"], flight["seed"], flight_dir), flight_dir)
        with open(log_path, "w") as log:
            launch = subprocess.Popen(
                ["roslaunch", "-p", str(port), str(launch_file)], env=env, stdout=log, stderr=subprocess.STDOUT, preexec_fn=_default_signals
            )
        watch = subprocess.Popen(
            watchers.command("clock"), env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, preexec_fn=_default_signals
        )
        sim = {"t": -1.0}

        def read_clock():
            for line in watch.stdout:
                try:
                    sim["t"] = float(line)
                except ValueError:
                    pass

        threading.Thread(target=read_clock, daemon=True).start()

        target = float(sweep["sim_time_s"])
        inject = sweep.get("inject_failure")
        inject_at = inject["at_sim_s"] if inject and inject["flight"] == flight["index"] else None
        t0 = time.monotonic()
        last_t, last_change = -1.0, t0
        simulator_seen, servers = False, []
        while True:
            time.sleep(0.05)
            now, t = time.monotonic(), sim["t"]
            row["sim_s"] = max(t, 0.0)
            if t >= target:
                break
            if t != last_t:
                last_t, last_change = t, now
            if launch.poll() is not None:
                raise FlightFailedError(f"roslaunch exited with code {launch.returncode} at sim time {max(t, 0):.2f} s")
            # /proc is scanned until the simulator appears; after that only its pids are watched
            servers = [p for p in servers if _alive(p)] if servers else graph_processes(port, "rotors_sim_server")
            simulator_seen = simulator_seen or bool(servers)
            if simulator_seen and not servers:
                raise FlightFailedError(f"the simulator (rotors_sim_server) died at sim time {max(t, 0):.2f} s")
            if inject_at is not None and t >= inject_at:
                for pid in servers:  # the injected fault: the simulator crashes
                    os.kill(pid, signal.SIGKILL)
                inject_at = None
            if now - t0 > float(sweep["wall_limit_s"]):
                raise FlightFailedError(
                    f"wall-time limit {sweep['wall_limit_s']:.0f} s reached at sim time " f"{max(t, 0):.2f} s of {target:.0f} s"
                )
            if now - last_change > STALL_LIMIT_S:
                raise FlightFailedError(f"sim time stalled at {max(t, 0):.2f} s for {STALL_LIMIT_S:.0f} s")
    finally:
        stop_process_group(watch, 5, signal.SIGKILL)
        stop_process_group(launch, STOP_GRACE_S)
        kill_graph_leftovers(port)  # a node roslaunch could not stop (or every node, if roslaunch was killed)
        stop_process_group(master, 10)
    bags = sorted(flight_dir.glob("*.bag"))
    if not bags:
        raise FlightFailedError("no bag was written (enable_logging)")
    return bags[-1]


def _repeatability(bag: Path, mav_name: str, until_s: float) -> dict[str, Any]:
    """unwaited_steps: steps up to sim time until_s (the flight's end) that lockstep did not wait for
    (simulation_status); > 0: not repeatable. The steps the simulator takes while roslaunch stops
    the nodes after the flight do not count: the controller may be gone before the simulator."""
    from rotors_evaluation.bag_data import FlightBag

    b = FlightBag(bag)
    try:
        unwaited = b.unwaited(mav_name, until_s=until_s)
    finally:
        b.close()
    return {"unwaited_steps": unwaited.steps if unwaited else 0, "unwaited_reason": unwaited.reason if unwaited else ""}


def _evaluate(sweep: dict[str, Any], bag: Path, flight_dir: Path) -> dict[str, Any]:
    from rotors_evaluation.bag_data import load_flight
    from rotors_evaluation.evaluations import EVALUATORS
    from rotors_evaluation.options import with_overrides

    opts = with_overrides(bag, sweep["mav_name"], **{"end_time": sweep["sim_time_s"], **sweep["eval_options"]})
    metrics: dict[str, Any] = {}
    data = None
    for kind in sweep["evaluations"]:
        if kind == "estimator":
            from rotors_evaluation.estimator import evaluate_estimator

            r = evaluate_estimator(bag, sweep["mav_name"], begin=opts.begin_time or None, end=opts.end_time)
            metrics.update(
                {
                    "estimator_position_rms_m": r.position_rms,
                    "estimator_velocity_rms_mps": r.velocity_rms,
                    "estimator_max_position_error_m": r.max_position_error,
                }
            )
            continue
        if data is None:
            data = load_flight(
                bag, opts.mav_name, opts.pose_topic, opts.twist_topic, opts.waypoint_topic, opts.wrench_topic, opts.motor_velocity_topic
            )
        r = EVALUATORS[kind](data, opts, out=lambda *_: None)
        if not math.isfinite(r.position_rms):
            # the set point node is not in lockstep: starved of CPU, it can wake up sim seconds late
            first = data.waypoints[0].t if data.waypoints else float("nan")
            raise FlightFailedError(
                f"{kind} evaluation window is empty: the first set point came at {first:.2f} s sim "
                f"time (the waypoint node fell behind the simulator; lower real_time_factor)"
            )
        metrics[f"{kind}_position_rms_m"] = r.position_rms
        metrics[f"{kind}_angular_velocity_rms_radps"] = r.angular_velocity_rms
        metrics[f"{kind}_collisions"] = len(r.collision_times)
        if kind != "hovering":
            metrics[f"{kind}_settling_time_s"] = r.settling_time
    return metrics


def _ray_node() -> str:
    """The Ray node this flight runs on (empty outside Ray)."""
    try:
        import ray

        return ray.get_runtime_context().get_node_id() if ray.is_initialized() else ""
    except ImportError:
        return ""


def failed_row(flight: dict[str, Any], reason: str = "", host: str = "", node: str = "") -> dict[str, Any]:
    """A flight's row before it flew (or when its worker died): status 'failed' with `reason`."""
    return {
        "id": flight["id"],
        "index": flight["index"],
        "repetition": flight["repetition"],
        "seed": flight["seed"],
        **flight["params"],
        "status": "failed",
        "reason": reason,
        "sim_s": 0.0,
        "wall_s": 0.0,
        "unwaited_steps": 0,
        "host": host,
        "node": node,
        "bag": "",
        "log_tail": "",
    }


def run_flight(sweep: dict[str, Any], flight: dict[str, Any], out_dir: str) -> dict[str, Any]:
    """Flies and evaluates one flight; always returns its row: status 'ok', 'not repeatable' (lockstep
    did not wait for every step, so the same seed may fly differently; the metrics are kept) or 'failed'."""
    flight_dir = Path(out_dir) / "flights" / flight["id"]
    shutil.rmtree(flight_dir, ignore_errors=True)
    flight_dir.mkdir(parents=True)
    row = failed_row(flight, host=socket.gethostname(), node=_ray_node())
    (flight_dir / "flight.json").write_text(json.dumps(flight, indent=1) + "\n")
    t0 = time.monotonic()
    try:
        bag = _fly(sweep, flight, flight_dir, row)
        row.update(_evaluate(sweep, bag, flight_dir))
        repeatability = _repeatability(bag, sweep["mav_name"], float(sweep["sim_time_s"]))
        row["unwaited_steps"] = repeatability["unwaited_steps"]
        row["status"] = "ok" if row["unwaited_steps"] == 0 else "not repeatable"
        if row["unwaited_steps"]:
            row["reason"] = f"{row['unwaited_steps']} steps not waited for: {repeatability['unwaited_reason']}"
        if sweep["keep_bags"]:
            row["bag"] = str(bag)
        else:
            bag.unlink()
    except FlightFailedError as e:
        row["reason"] = str(e)
    except Exception as e:  # an evaluation or set-up error: recorded, the sweep goes on
        row["reason"] = f"{type(e).__name__}: {e}".splitlines()[0]
        (flight_dir / "error.txt").write_text(traceback.format_exc())
    row["wall_s"] = round(time.monotonic() - t0, 3)
    if row["status"] == "failed":
        row["log_tail"] = _log_tail(flight_dir / "roslaunch.log")
    shutil.rmtree(flight_dir / "log", ignore_errors=True)  # rosout copies; roslaunch.log keeps the output
    (flight_dir / "result.json").write_text(json.dumps(row, indent=1, default=str) + "\n")
    return row
