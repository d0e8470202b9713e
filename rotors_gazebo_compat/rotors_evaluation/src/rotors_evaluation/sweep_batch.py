"""Sweeps on the batched flight engine (`engine: batch` in a sweep file): the flights that share a
vehicle (launch.mav_name and the model.* xacro arguments) fly together in one rotors_sim.FlightBatch,
without ROS, as the launch file's example flies them (spawned at (0, 0, 0.1), Lee's controller with
the vehicle's yaml and the flight's controller.* values, the hovering example's set point (0, 0, 1)
due at 5 s of sim time), sampled every 10 ms as the bag's ground truth, and scored by the same
evaluations as a world flight. Ray runs each group as one task. What needs ROS, rendering or the
estimator (estimator.* parameters, the estimator evaluation, other launch files) is refused when the
sweep file is read."""

from __future__ import annotations

import socket
import time
from pathlib import Path
from typing import Any

import numpy as np

# launch file -> the model file spawn_mav gets (None: the default, mav_generic_odometry_sensor.gazebo)
LAUNCH_MODELS = {"mav_hovering_example.launch": None, "mav_with_wind_gust.launch": "mav_with_wind_gust.gazebo"}
EVALUATIONS = ("hovering", "disturbance")
LAUNCH_PARAMS = ("launch.mav_name", "launch.world_name")
SET_POINT, DUE_S, SPAWN = (0.0, 0.0, 1.0, 0.0), 5.0, (0.0, 0.0, 0.1)
SAMPLE_S = 0.01


def unsupported(launch_file: Path, evaluations: list[str], names: list[str]) -> str:
    """Why the batch cannot fly this sweep ("" when it can)."""
    if launch_file.name not in LAUNCH_MODELS:
        return f"engine batch flies {', '.join(LAUNCH_MODELS)}; '{launch_file.name}' needs the world " "(engine: world)"
    bad = [e for e in evaluations if e not in EVALUATIONS]
    if bad:
        return f"engine batch evaluates {', '.join(EVALUATIONS)}; '{bad[0]}' needs the world (engine: world)"
    for name in names:
        kind = name.split(".", 1)[0]
        if kind == "estimator" or (kind == "launch" and name not in LAUNCH_PARAMS):
            return f"engine batch takes model.*, controller.* and {', '.join(LAUNCH_PARAMS)}; '{name}' needs the " "world (engine: world)"
    return ""


def _group_key(params: dict[str, Any], sweep: dict[str, Any]) -> tuple:
    merged = {**sweep["fixed"], **params}
    return tuple(sorted((k, str(v)) for k, v in merged.items() if not k.startswith("controller.")))


def fly_group(sweep: dict[str, Any], flights: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Flies one group of flights (the same vehicle) in one batch; returns a row per flight."""
    from dataclasses import replace

    import rotors_sim as rs
    from rotors_evaluation.bag_data import FlightData, Series, WaypointSample
    from rotors_evaluation.evaluations import EVALUATORS
    from rotors_evaluation.options import EvalOptions

    t0 = time.monotonic()
    merged = {**sweep["fixed"], **flights[0]["params"]}
    mav = str(merged.get("launch.mav_name", sweep["mav_name"]))
    world = str(merged.get("launch.world_name", "basic"))
    xacro_args = {k.split(".", 1)[1]: v for k, v in merged.items() if k.startswith("model.")}
    model_file = LAUNCH_MODELS[Path(sweep["launch_file"]).name]
    if model_file:
        from rotors_sim.paths import package_path

        xacro_args["model"] = package_path("rotors_description") / "urdf" / model_file
    overrides = [
        {k.split(".", 1)[1]: v for k, v in {**sweep["fixed"], **f["params"]}.items() if k.startswith("controller.")} for f in flights
    ]
    rows = [
        {
            "id": f["id"],
            "index": f["index"],
            "repetition": f["repetition"],
            "seed": f["seed"],
            **f["params"],
            "status": "failed",
            "reason": "",
            "sim_s": 0.0,
            "wall_s": 0.0,
            "unwaited_steps": 0,
            "host": socket.gethostname(),
            "node": "",
            "bag": "",
            "log_tail": "",
            "engine": "batch",
        }
        for f in flights
    ]
    try:
        batch = rs.FlightBatch(
            mav,
            len(flights),
            step_size=None,
            control_divisor=1,
            world=world,
            threads=1,
            seeds=[int(f["seed"]) for f in flights],
            controller_overrides=overrides,
            positions=[SPAWN] * len(flights),
            **xacro_args,
        )
    except Exception as e:  # a bad model or controller value: every flight of the group says why
        for row in rows:
            row["reason"] = f"{type(e).__name__}: {e}".splitlines()[0]
        return rows
    dt = batch.step_size
    per_sample = max(1, round(SAMPLE_S / dt))
    batch.commands[:] = np.nan  # no set point yet: rotors stopped, as before the hovering example's
    samples = int(round(float(sweep["sim_time_s"]) / (per_sample * dt)))
    t = np.zeros(samples)
    position = np.zeros((samples, len(flights), 3))
    angular_velocity = np.zeros((samples, len(flights), 3))
    contact = np.zeros((samples, len(flights)), dtype=bool)
    for k in range(samples):
        if np.isnan(batch.commands[0, 0]) and batch.time[0] + 1e-9 >= DUE_S:
            batch.commands[:] = SET_POINT
        batch.step(per_sample)
        truth = batch.truth()
        t[k] = batch.time[0]
        position[k] = truth[:, 0:3]
        angular_velocity[k] = truth[:, 10:13]
        contact[k] = batch.in_contact
    wall = time.monotonic() - t0
    opts = replace(
        EvalOptions(), mav_name=mav, end_time=float(sweep["sim_time_s"]), **{k: float(v) for k, v in sweep["eval_options"].items()}
    )
    for i, row in enumerate(rows):
        # a contact that begins after the take-off is a collision (the bag's contact topic, as the world counts)
        airborne = t > DUE_S + 1.0
        begins = np.flatnonzero(contact[1:, i] & ~contact[:-1, i]) + 1
        data = FlightData(
            Path(f"batch:{row['id']}"),
            Series(t, position[:, i]),
            Series(t, angular_velocity[:, i]),
            [WaypointSample(DUE_S, np.array(SET_POINT[:3]), SET_POINT[3])],
            t[begins[airborne[begins]]],
        )
        try:
            for kind in sweep["evaluations"]:
                r = EVALUATORS[kind](data, opts, out=lambda *_: None)
                row[f"{kind}_position_rms_m"] = r.position_rms
                row[f"{kind}_angular_velocity_rms_radps"] = r.angular_velocity_rms
                row[f"{kind}_collisions"] = len(r.collision_times)
                if kind != "hovering":
                    row[f"{kind}_settling_time_s"] = r.settling_time
            row["status"] = "ok"
        except Exception as e:
            row["reason"] = f"{type(e).__name__}: {e}".splitlines()[0]
        row["sim_s"] = float(t[-1]) if samples else 0.0
        row["wall_s"] = round(wall / len(flights), 4)  # the group's wall time, shared out
    return rows


def groups(sweep: dict[str, Any], flights: list[dict[str, Any]]) -> list[list[dict[str, Any]]]:
    """The flights by vehicle: each list flies in one batch."""
    by_key: dict[tuple, list[dict[str, Any]]] = {}
    for f in flights:
        by_key.setdefault(_group_key(f["params"], sweep), []).append(f)
    return list(by_key.values())
