"""Hand flying: Joy -> RollPitchYawrateThrust, a terminal keyboard joystick, evdev gamepads."""
