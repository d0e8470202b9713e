"""The controller libraries of rotors_control as Python objects, with their parameters read from the
same yaml files the ROS nodes load (resource/lee_controller_<mav>.yaml and resource/<mav>.yaml),
by the same loaders and under the same policy (missing: an error naming the parameter; unknown: a warning)."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from rotors_sim import _engine
from rotors_sim._engine import SimError
from rotors_sim.paths import resource
from rotors_sim.world import Odometry


def _values(who: str, value: Any, n: int, meaning: str) -> np.ndarray:
    """`value` as n floats, or SimError naming the argument, what it got and what it takes."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SimError(f"{who}: {value!r} is not numbers; give {n} values ({meaning})") from None
    if a.shape != (n,):
        raise SimError(f"{who}: {a.size} values in shape {a.shape}; give {n} ({meaning})")
    return a


def flatten(tree: dict, prefix: str = "") -> tuple[dict[str, float], list[str]]:
    """{"a": {"b": 1}} -> ({"a/b": 1.0}, []); values that are not numbers go to the second list
    (the reader then says "must be a number" if a loader asks for them)."""
    numbers: dict[str, float] = {}
    others: list[str] = []
    for key, value in tree.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            n, o = flatten(value, name + "/")
            numbers.update(n)
            others += o
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            numbers[name] = float(value)
        else:
            others.append(name)
    return numbers, others


def load_yamls(paths: Sequence[str | Path]) -> tuple[dict[str, float], list[str], str]:
    merged: dict[str, Any] = {}
    for path in paths:
        path = Path(path)
        if not path.exists():
            raise SimError(f"parameter file '{path}' does not exist")
        try:
            content = yaml.safe_load(path.read_text()) or {}
        except yaml.YAMLError as e:
            raise SimError(f"parameter file '{path}' is not valid yaml: {e}".splitlines()[0]) from None
        if not isinstance(content, dict):
            raise SimError(f"parameter file '{path}' must hold a mapping of parameters")
        merged.update(content)
    numbers, others = flatten(merged)
    return numbers, others, " + ".join(Path(p).name for p in paths)


def _report(controller: Any, source: str) -> None:
    if controller.unknown_keys:
        warnings.warn(f"{source}: unknown parameter(s), not used: {', '.join(controller.unknown_keys)} (a typo?)", stacklevel=3)


def _answer(controller: Any, odometry: Odometry) -> np.ndarray:
    return controller.answer(odometry.position_W, odometry.orientation, odometry.velocity_B, odometry.angular_velocity_B, odometry.time_s)


class _YamlController:
    """A controller library object built from yaml files through the shared loaders."""

    _engine_class: Any = None

    def __init__(self, *yaml_paths: str | Path):
        numbers, others, source = load_yamls(yaml_paths)
        self._c = self._engine_class(numbers, others, source)
        _report(self._c, source)

    def rotor_speeds(self, odometry: Odometry) -> np.ndarray:
        """Rotor speeds [rad/s] answering an odometry message (zeros until the first command, as the node)."""
        return _answer(self._c, odometry)

    @property
    def engine(self) -> Any:
        """The C++ controller (for World.attach_controller)."""
        return self._c

    @property
    def vehicle(self) -> dict:
        """The vehicle parameters as the controller read them (mass, inertia, rotors)."""
        return self._c.vehicle


class LeePositionController(_YamlController):
    """Lee's SE(3) position controller (rotors_control library), as lee_position_controller_node runs it."""

    _engine_class = _engine.LeePositionController

    @classmethod
    def for_mav(cls, mav_name: str) -> LeePositionController:
        """With resource/lee_controller_<mav>.yaml and resource/<mav>.yaml, as the hovering example."""
        return cls(resource(f"lee_controller_{mav_name}.yaml"), resource(f"{mav_name}.yaml"))

    def set_point(
        self,
        position: Sequence[float],
        yaw: float = 0.0,
        velocity: Sequence[float] = (0, 0, 0),
        acceleration: Sequence[float] = (0, 0, 0),
        yaw_rate: float = 0.0,
        due: float | None = None,
    ) -> None:
        """A reference point; with `due` [s of sim time] it is released with the first odometry stamped
        at or after it (as the ROS node releases a stamped trajectory), else with the next odometry."""
        self._c.set_trajectory_point(
            _values("set_point: position", position, 3, "x, y, z [m]; the yaw is its own argument"),
            _values("set_point: velocity", velocity, 3, "vx, vy, vz [m/s]"),
            _values("set_point: acceleration", acceleration, 3, "ax, ay, az [m/s^2]"),
            float(yaw),
            float(yaw_rate),
            -1e300 if due is None else float(due),
        )


class AttitudeLevelController(_YamlController):
    """The attitude-level controllers (roll-pitch-yawrate-thrust, attitude-thrust, rate-thrust)."""

    _engine_class = _engine.AttitudeLevelController

    @classmethod
    def for_mav(cls, mav_name: str) -> AttitudeLevelController:
        """With resource/roll_pitch_yawrate_thrust_controller_<mav>.yaml and resource/<mav>.yaml."""
        return cls(resource(f"roll_pitch_yawrate_thrust_controller_{mav_name}.yaml"), resource(f"{mav_name}.yaml"))

    def set_roll_pitch_yawrate_thrust(self, roll: float, pitch: float, yaw_rate: float, thrust_N: float) -> None:
        self._c.set_roll_pitch_yawrate_thrust(float(roll), float(pitch), float(yaw_rate), float(thrust_N))

    def set_attitude_thrust(self, orientation_xyzw: Sequence[float], thrust_N: float) -> None:
        self._c.set_attitude_thrust(_values("set_attitude_thrust: orientation", orientation_xyzw, 4, "x, y, z, w"), float(thrust_N))

    def set_rate_thrust(self, angular_velocity_B: Sequence[float], thrust_N: float) -> None:
        self._c.set_rate_thrust(
            _values("set_rate_thrust: angular velocity", angular_velocity_B, 3, "p, q, r [rad/s] in the body frame"), float(thrust_N)
        )
