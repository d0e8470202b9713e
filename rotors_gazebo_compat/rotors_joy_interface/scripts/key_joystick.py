#!/usr/bin/env python3
"""key_joystick.py: fly with the keyboard in a plain terminal (no uinput, no X, no joy_node).
Publishes sensor_msgs/Joy on `joy` at ~rate (20 Hz) for rotors_joy_interface. Keys: arrows roll
and pitch, W/S thrust, A/D yaw, R arm, M mode, Space centres, Q or Ctrl-C quits (see
keyboard.KeyJoystick)."""

import os
import select
import sys
import termios
import time
import tty

import rospy
from sensor_msgs.msg import Joy

from rotors_joy_interface.keyboard import KeyJoystick, decode_keys

HELP = (
    "keys: arrows roll/pitch, W/S thrust up/down (from the bottom: Betaflight's iris hovers near 32 presses of W, "
    "1,800 us, its thrust-to-weight being 1.55), A/D yaw left/right, R arm (the controller-enable button), "
    "M mode (angle), Space level, Q quit"
)


def main() -> int:
    rospy.init_node("key_joystick")
    if not os.isatty(sys.stdin.fileno()):
        rospy.logfatal(
            "[key_joystick] stdin is not a terminal: run it in one (rosrun rotors_joy_interface "
            "key_joystick.py __ns:=<mav>), or launch mav_with_keyboard.launch from a terminal"
        )
        return 1
    rate_hz = float(rospy.get_param("~rate", 20.0))
    pub = rospy.Publisher("joy", Joy, queue_size=10)
    stick = KeyJoystick()
    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    pending = ""
    sys.stderr.write(f"[key_joystick] {HELP}\r\n")
    try:
        tty.setcbreak(fd)
        while not rospy.is_shutdown():
            ready, _, _ = select.select([fd], [], [], 1.0 / rate_hz)
            now = time.monotonic()  # wall clock: key repeat is wall time, whatever the sim's pace
            if ready:
                data = os.read(fd, 64).decode("utf-8", "replace")
                if not data:
                    break
                keys, pending = decode_keys(pending + data)
                if "q" in keys or "\x03" in keys:
                    break
                stick.press_all(keys, now)
            axes, buttons = stick.state(now)
            msg = Joy(axes=axes, buttons=buttons)
            msg.header.stamp = rospy.Time.now()
            pub.publish(msg)
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
    return 0


if __name__ == "__main__":
    sys.exit(main())
