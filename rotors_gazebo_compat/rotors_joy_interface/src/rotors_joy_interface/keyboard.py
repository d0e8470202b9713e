"""A keyboard joystick for a plain terminal (RotorS' key_joystick.py needed uinput and joy_node):
keys become the axes and buttons of a sensor_msgs/Joy that rotors_joy_interface maps with its
default parameters.

    Left / Right arrows   roll axis (0)        +-0.2 per press, springs back when released
    Up / Down arrows      pitch axis (1)       +-0.2 per press, springs back when released
    W / S                 thrust axis (2)      +-0.05 per press, stays (starts at -1: no thrust)
    A / D                 yaw-left / yaw-right buttons (3 / 4), held while the key repeats
    Space                 centres roll and pitch
    R / M                 buttons 5 / 10 (RotorS' ctrl_enable / ctrl_mode; joy_to_rc: arm / angle mode toggles)

A terminal sends no key-up events: an axis or button counts as released `hold_s` after its last
key press (the terminal's auto-repeat keeps a held key pressed), then roll and pitch spring back to
0 at `spring_back_per_s`. Joy convention: left and up are positive (as joy_node reports a stick).
ROS-free; scripts/key_joystick.py reads the terminal and publishes."""

from collections.abc import Iterable
from dataclasses import dataclass, field

ROLL, PITCH, THRUST, YAW = 0, 1, 2, 3
BUTTON_YAW_LEFT, BUTTON_YAW_RIGHT = 3, 4
BUTTON_CTRL_ENABLE, BUTTON_CTRL_MODE = 5, 10
N_AXES, N_BUTTONS = 4, 12

# escape sequences of the arrow keys (xterm and the Linux console; SS3 form from application mode)
ARROWS = {
    "\x1b[A": "up",
    "\x1b[B": "down",
    "\x1b[C": "right",
    "\x1b[D": "left",
    "\x1bOA": "up",
    "\x1bOB": "down",
    "\x1bOC": "right",
    "\x1bOD": "left",
}


def decode_keys(text: str) -> tuple[list[str], str]:
    """Key names in `text` ('up', 'w', ' ', ...), and an incomplete escape sequence left over."""
    keys, i = [], 0
    while i < len(text):
        if text[i] == "\x1b":
            seq = text[i : i + 3]
            if len(seq) < 3 and seq in ("\x1b", "\x1b[", "\x1bO"):
                return keys, text[i:]
            keys.append(ARROWS.get(seq, "escape"))
            i += 3 if seq in ARROWS else 1
        else:
            keys.append(text[i].lower())
            i += 1
    return keys, ""


@dataclass
class KeyJoystick:
    roll_pitch_step: float = 0.2
    thrust_step: float = 0.05
    hold_s: float = 0.5
    spring_back_per_s: float = 2.0
    axes: list[float] = field(default_factory=lambda: [0.0, 0.0, -1.0, 0.0])
    _last_press: dict = field(default_factory=dict)  # axis / button -> time of its last key [s]
    _last_update: float | None = None

    def press(self, key: str, t: float) -> bool:
        """Applies one key at time t [s]; False for a key that does nothing."""

        def step(axis: int, delta: float, limit: float = 1.0) -> None:
            self.axes[axis] = max(-limit, min(limit, self.axes[axis] + delta))
            self._last_press[("axis", axis)] = t

        if key == "left":
            step(ROLL, self.roll_pitch_step)
        elif key == "right":
            step(ROLL, -self.roll_pitch_step)
        elif key == "up":
            step(PITCH, self.roll_pitch_step)
        elif key == "down":
            step(PITCH, -self.roll_pitch_step)
        elif key == "w":
            step(THRUST, self.thrust_step)
        elif key == "s":
            step(THRUST, -self.thrust_step)
        elif key == "a":
            self._last_press[("button", BUTTON_YAW_LEFT)] = t
        elif key == "d":
            self._last_press[("button", BUTTON_YAW_RIGHT)] = t
        elif key == "r":
            self._last_press[("button", BUTTON_CTRL_ENABLE)] = t
        elif key == "m":
            self._last_press[("button", BUTTON_CTRL_MODE)] = t
        elif key == " ":
            self.axes[ROLL] = self.axes[PITCH] = 0.0
        else:
            return False
        return True

    def state(self, t: float) -> tuple[list[float], list[int]]:
        """Axes and buttons at time t [s] (after releasing what was not pressed for hold_s)."""
        dt = 0.0 if self._last_update is None else max(t - self._last_update, 0.0)
        self._last_update = t
        for axis in (ROLL, PITCH):
            last = self._last_press.get(("axis", axis))
            if last is None or t - last > self.hold_s:
                v = self.axes[axis]
                decay = self.spring_back_per_s * dt
                self.axes[axis] = 0.0 if abs(v) <= decay else v - decay * (1 if v > 0 else -1)
        buttons = [0] * N_BUTTONS
        for b in (BUTTON_YAW_LEFT, BUTTON_YAW_RIGHT, BUTTON_CTRL_ENABLE, BUTTON_CTRL_MODE):
            last = self._last_press.get(("button", b))
            buttons[b] = int(last is not None and t - last <= self.hold_s)
        return list(self.axes), buttons

    def press_all(self, keys: Iterable[str], t: float) -> list[str]:
        """Applies keys; returns those that do nothing."""
        return [k for k in keys if not self.press(k, t)]
