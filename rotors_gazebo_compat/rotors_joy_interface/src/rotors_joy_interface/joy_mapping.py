"""sensor_msgs/Joy -> mav_msgs/RollPitchYawrateThrust with RotorS' parameters (reference 1.7):
    roll = axis_roll * max_roll * dir_roll,  pitch = axis_pitch * max_pitch * dir_pitch
    yaw_rate = +max_yaw_rate (yaw-left button held), -max_yaw_rate (yaw-right), else 0
    multirotor: thrust.z = (axis_thrust + 1) max_thrust / 2 * dir_thrust
    fixed wing: thrust.x = max(axis_thrust * dir_thrust, 0)
ROS-free: the node (scripts/rotors_joy_interface) reads the parameters and moves the messages."""

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields


class JoyError(ValueError):
    """A Joy message the mapping cannot use (one line)."""


@dataclass
class JoyMapping:
    # private parameter names of RotorS' node, trailing underscores included
    axis_roll_: int = 0
    axis_pitch_: int = 1
    axis_thrust_: int = 2
    axis_direction_roll: float = -1.0
    axis_direction_pitch: float = 1.0
    axis_direction_thrust: float = 1.0
    max_roll: float = math.radians(10.0)  # [rad]
    max_pitch: float = math.radians(10.0)  # [rad]
    max_yaw_rate: float = math.radians(45.0)  # [rad/s]
    max_thrust: float = 30.0  # [N]
    is_fixed_wing: bool = False
    button_yaw_left_: int = 3
    button_yaw_right_: int = 4
    # read by RotorS and unused there too; accepted so that RotorS launch files load, and named at start
    max_v_xy: float = 1.0
    v_yaw_step: float = 0.05
    button_ctrl_enable_: int = 5
    button_ctrl_mode_: int = 10
    button_takeoff_: int = 7
    button_land_: int = 8

    UNUSED = ("max_v_xy", "v_yaw_step", "button_ctrl_enable_", "button_ctrl_mode_", "button_takeoff_", "button_land_")

    @classmethod
    def from_params(cls, params: dict[str, object]) -> "JoyMapping":
        mapping = cls()
        names = {f.name: f.type for f in fields(cls)}
        for key, value in params.items():
            if key not in names:
                raise JoyError(f"unknown parameter '{key}' (known: {', '.join(sorted(names))})")
            setattr(mapping, key, value)
        mapping.validate()
        return mapping

    def validate(self) -> None:
        for name in ("axis_roll_", "axis_pitch_", "axis_thrust_", "button_yaw_left_", "button_yaw_right_"):
            if not isinstance(getattr(self, name), int) or getattr(self, name) < 0:
                raise JoyError(f"parameter {name} = {getattr(self, name)!r} must be an index >= 0")
        for name in ("max_roll", "max_pitch", "max_yaw_rate", "max_thrust"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
                raise JoyError(f"parameter {name} = {value!r} must be a finite number >= 0")

    def command(self, axes: Sequence[float], buttons: Sequence[int]) -> tuple[float, float, float, tuple[float, float, float]]:
        """(roll [rad], pitch [rad], yaw_rate [rad/s], thrust [N] as (x, y, z)) for one Joy message."""
        for what, index in (("axis_roll_", self.axis_roll_), ("axis_pitch_", self.axis_pitch_), ("axis_thrust_", self.axis_thrust_)):
            if index >= len(axes):
                raise JoyError(f"Joy has {len(axes)} axes; {what} = {index} needs at least {index + 1}")
        for what, index in (("button_yaw_left_", self.button_yaw_left_), ("button_yaw_right_", self.button_yaw_right_)):
            if index >= len(buttons):
                raise JoyError(f"Joy has {len(buttons)} buttons; {what} = {index} needs at least {index + 1}")
        a_roll, a_pitch, a_thrust = axes[self.axis_roll_], axes[self.axis_pitch_], axes[self.axis_thrust_]
        if not all(math.isfinite(a) and -1.0 - 1e-6 <= a <= 1.0 + 1e-6 for a in (a_roll, a_pitch, a_thrust)):
            raise JoyError(f"Joy axes must be finite and in [-1, 1], got roll {a_roll}, pitch {a_pitch}, " f"thrust {a_thrust}")
        roll = a_roll * self.max_roll * self.axis_direction_roll
        pitch = a_pitch * self.max_pitch * self.axis_direction_pitch
        yaw_rate = 0.0
        if buttons[self.button_yaw_left_]:
            yaw_rate = self.max_yaw_rate
        elif buttons[self.button_yaw_right_]:
            yaw_rate = -self.max_yaw_rate
        if self.is_fixed_wing:
            thrust = (max(a_thrust * self.axis_direction_thrust, 0.0), 0.0, 0.0)
        else:
            thrust = (0.0, 0.0, (a_thrust + 1.0) * self.max_thrust / 2.0 * self.axis_direction_thrust)
        return roll, pitch, yaw_rate, thrust
