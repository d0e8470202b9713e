"""Gamepads through evdev (python3-evdev; Debian has no joy driver): an EV_ABS value to a Joy
axis in [-1, 1] as joy_node reports it (joy_node negates every axis, so a stick's left and up are
+1), EV_KEY buttons to 0/1, axes and buttons in the order of their event codes."""


def normalise(value: int, minimum: int, maximum: int, flip: bool = True) -> float:
    """A raw axis value into [-1, 1] (centre 0), negated as joy_node does unless flip is False."""
    if maximum <= minimum:
        raise ValueError(f"axis range [{minimum}, {maximum}] is empty")
    x = 2.0 * (value - minimum) / (maximum - minimum) - 1.0
    x = max(-1.0, min(1.0, x))
    return -x if flip else x


class GamepadLayout:
    """The axes and buttons of one device, in the order Joy lists them."""

    def __init__(self, abs_infos: dict[int, tuple[int, int]], keys: list[int]):
        self.axis_codes = sorted(abs_infos)
        self.ranges = abs_infos
        self.button_codes = sorted(keys)
        self.axes = [0.0] * len(self.axis_codes)
        self.buttons = [0] * len(self.button_codes)

    def on_abs(self, code: int, value: int) -> None:
        if code in self.ranges:
            lo, hi = self.ranges[code]
            self.axes[self.axis_codes.index(code)] = normalise(value, lo, hi)

    def on_key(self, code: int, value: int) -> None:
        if code in self.button_codes:
            self.buttons[self.button_codes.index(code)] = 1 if value else 0
