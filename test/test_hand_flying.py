"""Hand flying: rotors_joy_interface's mapping (RotorS' axes, scales and parameters), the terminal
keyboard joystick and the gamepad scaling, and a flight: mav_with_keyboard.launch run in a
pseudo-terminal, driven by scripted key presses, climbs, rolls and yaws as commanded."""

import json
import math
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from rotors_joy_interface.gamepad import GamepadLayout, normalise
from rotors_joy_interface.joy_mapping import JoyError, JoyMapping
from rotors_joy_interface.keyboard import BUTTON_YAW_RIGHT, KeyJoystick, decode_keys
from support import RosGraph, stop_launch


def test_joy_mapping_is_rotors():
    m = JoyMapping()
    buttons = [0] * 12
    # full left stick, full forward, thrust axis at 0: roll = 1 * 10 deg * -1, pitch = 10 deg, T = 15 N
    roll, pitch, yaw_rate, thrust = m.command([1.0, 1.0, 0.0], buttons)
    assert roll == pytest.approx(-math.radians(10)) and pitch == pytest.approx(math.radians(10))
    assert yaw_rate == 0.0 and thrust == (0.0, 0.0, 15.0)
    buttons[3] = 1
    assert m.command([0, 0, -1.0], buttons)[2:] == (pytest.approx(math.radians(45)), (0.0, 0.0, 0.0))
    buttons[3], buttons[4] = 0, 1
    assert m.command([0, 0, 1.0], buttons)[2:] == (pytest.approx(-math.radians(45)), (0.0, 0.0, 30.0))
    wing = JoyMapping.from_params({"is_fixed_wing": True, "axis_thrust_": 3})
    assert wing.command([0, 0, 0, -0.5], [0] * 12)[3] == (0.0, 0.0, 0.0)
    assert wing.command([0, 0, 0, 0.5], [0] * 12)[3] == (0.5, 0.0, 0.0)
    with pytest.raises(JoyError, match="Joy has 2 axes; axis_thrust_ = 2 needs at least 3"):
        m.command([0.0, 0.0], [0] * 12)
    with pytest.raises(JoyError, match="must be finite and in"):
        m.command([float("nan"), 0.0, 0.0], [0] * 12)
    with pytest.raises(JoyError, match="unknown parameter 'max_rol'"):
        JoyMapping.from_params({"max_rol": 0.2})


def test_keyboard_joystick_and_gamepad_scaling():
    keys, rest = decode_keys("w\x1b[Cd\x1b[")
    assert keys == ["w", "right", "d"] and rest == "\x1b["
    keys, rest = decode_keys(rest + "A")
    assert keys == ["up"] and rest == ""
    stick = KeyJoystick()
    assert stick.press_all(["w"] * 22 + ["right", "right", "d", "x"], 0.0) == ["x"]
    axes, buttons = stick.state(0.1)
    assert axes[2] == pytest.approx(0.1) and axes[0] == pytest.approx(-0.4) and buttons[BUTTON_YAW_RIGHT] == 1
    axes, buttons = stick.state(0.7)  # released 0.5 s after the last press: roll springs back at 2/s
    assert buttons[BUTTON_YAW_RIGHT] == 0 and axes[0] == pytest.approx(0.0) and axes[2] == pytest.approx(0.1)
    assert normalise(0, 0, 255) == 1.0 and normalise(255, 0, 255) == -1.0 and normalise(127.5, 0, 255) == 0.0
    pad = GamepadLayout({0: (-32768, 32767), 1: (-32768, 32767)}, [0x130, 0x131])
    pad.on_abs(0, -32768)  # stick full left
    pad.on_key(0x131, 1)
    assert pad.axes == [1.0, 0.0] and pad.buttons == [0, 1]  # no event on axis 1 yet


RECORDER = textwrap.dedent("""
    import json, math, sys, time, rospy
    from nav_msgs.msg import Odometry
    from mav_msgs.msg import RollPitchYawrateThrust
    rospy.init_node('recorder', anonymous=True)
    odom, cmd = [], []
    def on_odom(m):
        q = m.pose.pose.orientation
        odom.append([time.monotonic(), m.pose.pose.position.y, m.pose.pose.position.z,
                     math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))])
    rospy.Subscriber('/firefly/ground_truth/odometry', Odometry, on_odom)
    rospy.Subscriber('/firefly/command/roll_pitch_yawrate_thrust', RollPitchYawrateThrust,
                     lambda m: cmd.append([time.monotonic(), m.roll, m.pitch, m.yaw_rate, m.thrust.z]))
    print('READY', flush=True)
    time.sleep(float(sys.argv[1]))
    print('RESULT=' + json.dumps({'odom': odom, 'cmd': cmd}), flush=True)
""")


def keyboard_flight(ros: RosGraph, tmp_path: Path, launch_args: list, ready, ready_s: float, recorder: str, record_s: float, fly) -> tuple:
    """Runs `roslaunch rotors_gazebo <launch_args>` with a pseudo-terminal as its stdin (the keyboard
    joystick reads it), waits up to ready_s for `ready(launch log)`, starts `recorder` for record_s seconds and
    calls fly(keys), keys(key, count, period) typing a key count times and returning when it
    started. Returns (the launch log, odometry rows, command rows, what fly returned)."""
    master, slave = os.openpty()
    launch_log = open(tmp_path / "launch.log", "w")
    proc = subprocess.Popen(
        ["roslaunch", "-p", str(ros.port), "rotors_gazebo", *launch_args],
        env=ros.env,
        stdin=slave,
        stdout=launch_log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    proc.log_path = tmp_path / "launch.log"
    rec_proc = None
    try:
        assert ros.wait_for(lambda: ready(proc.log_path.read_text()), ready_s), proc.log_path.read_text()[-3000:]
        rec_proc = subprocess.Popen([sys.executable, "-c", recorder, str(record_s)], env=ros.env, stdout=subprocess.PIPE, text=True)
        assert rec_proc.stdout.readline().strip() == "READY"

        def keys(key: str, count: int, period: float = 0.05) -> float:
            t = time.monotonic()
            for _ in range(count):
                os.write(master, key.encode())
                time.sleep(period)
            return t

        marks = fly(keys)
        out, _ = rec_proc.communicate(timeout=30)
    finally:
        if rec_proc is not None and rec_proc.poll() is None:
            rec_proc.kill()
        stop_launch(proc)
        os.close(master)
        os.close(slave)
    rec = json.loads(next(line for line in out.splitlines() if line.startswith("RESULT="))[len("RESULT=") :])
    return proc.log_path.read_text(), np.array(rec["odom"]), np.array(rec["cmd"]), marks


def at(series, t):
    """The row of `series` (time in column 0) nearest to t."""
    return series[np.argmin(np.abs(series[:, 0] - t))]


def test_keyboard_flight_climbs_rolls_and_yaws(ros: RosGraph, tmp_path: Path):
    def ready(log: str) -> bool:
        return "rotors_joy_interface" in ros.run(["rosnode", "list"], check=False).stdout and "Successfully spawned" in log

    def fly(keys) -> tuple:
        time.sleep(1.0)
        t_climb = keys("w", 22)  # thrust axis -1 + 22 * 0.05 = 0.1: 16.5 N
        time.sleep(2.5)
        keys("s", 2)  # 15 N, about the weight
        time.sleep(0.5)
        t_roll = keys("\x1b[C", 30)  # right arrow held 1.5 s: roll +10 deg
        time.sleep(1.5)
        t_yaw = keys("d", 30)  # D held 1.5 s: yaw rate -45 deg/s
        return t_climb, t_roll, t_yaw

    log, odom, cmd, (t_climb, t_roll, t_yaw) = keyboard_flight(
        ros, tmp_path, ["mav_with_keyboard.launch", "gui:=false"], ready, 60, RECORDER, 14, fly
    )
    assert "keys: arrows roll/pitch" in log and "R arm" in log and "M mode" in log and "32 presses of W" in log, log[-3000:]

    assert cmd[:, 4].max() == pytest.approx(16.5, abs=1e-5)  # W x 22
    assert cmd[:, 1].max() == pytest.approx(math.radians(10), abs=1e-6)  # right arrow: roll right
    assert cmd[:, 3].min() == pytest.approx(-math.radians(45), abs=1e-6)  # D: yaw right
    climbed = at(odom, t_roll)[2] - at(odom, t_climb)[2]
    moved = at(odom, t_yaw)[1] - at(odom, t_roll)[1]
    yawed = at(odom, t_yaw + 3.0)[3] - at(odom, t_yaw)[3]
    print(
        f"keyboard flight: climbed {climbed:.2f} m, rolled right and moved {moved:.2f} m in y, "
        f"yawed {math.degrees(yawed):.1f} deg in 3 s"
    )
    assert climbed > 1.0
    assert moved < -0.5
    assert yawed < -math.radians(20)  # with RotorS' RPYT gains the yaw rate builds up over about 2 s


WING_RECORDER = (
    RECORDER.replace("/firefly/", "/techpod/")
    .replace("m.yaw_rate, m.thrust.z", "m.yaw_rate, m.thrust.x")
    .replace(
        "math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))]",
        "math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2)), "
        "math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x ** 2 + q.y ** 2)), m.pose.pose.position.x]",
    )
)


def plot_wing_flight(odom, cmd, t_climb: float, t_bank: float, out: Path) -> None:
    """Track, height and bank of the keyboard flight, with the stick commands (README picture)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t0 = odom[0, 0]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax1.plot(odom[:, 5], odom[:, 1], color="tab:blue")
    ax1.set_xlabel("x [m]")
    ax1.set_ylabel("y [m]")
    ax1.set_title("techpod flown by keyboard: track (right turn)")
    ax1.axis("equal")
    ax2.plot(odom[:, 0] - t0, odom[:, 2], label="height [m]")
    ax2.set_xlabel("wall time [s] (real time)")
    ax3 = ax2.twinx()
    ax3.plot(odom[:, 0] - t0, np.degrees(odom[:, 4]), color="tab:red", label="bank [deg]")
    ax3.plot(cmd[:, 0] - t0, 100 * cmd[:, 4], color="tab:green", ls="--", label="throttle [%]")
    ax3.plot(cmd[:, 0] - t0, 100 * cmd[:, 1], color="tab:purple", ls=":", label="roll stick [%]")
    low, high = ax2.get_ylim()
    for k, (t, what) in enumerate(((t_climb, "W, down arrow: climb"), (t_bank, "right arrow x 3: bank"))):
        ax2.axvline(t - t0, color="grey", lw=0.8)
        ax2.text(t - t0 + 0.1, low + (0.30 - 0.08 * k) * (high - low), what, fontsize=8)
    ax2.set_ylabel("height [m]")
    ax3.set_ylabel("bank [deg], throttle and roll stick [%]")
    lines = ax2.get_legend_handles_labels()[0] + ax3.get_legend_handles_labels()[0]
    ax2.legend(lines, [ln.get_label() for ln in lines], fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"plot: {out}")


@pytest.mark.long  # the long tier (about 20-25 s): make test under 25 min
def test_keyboard_fixed_wing_flight_climbs_banks_and_turns(ros: RosGraph, tmp_path: Path):
    # fixed_wing_with_joy.launch joystick:=keyboard in a pseudo-terminal: the launcher sets the techpod
    # flying at 15 m/s; W x 30 opens the throttle to 0.5 (thrust axis -1 + 30 * 0.05, about the
    # trim); then W x 6 (0.8) and a tap of the down arrow (elevator trailing edge up for 0.5 s): it
    # climbs; three taps of the right arrow deflect the ailerons (roll axis 0.6 -> +-0.21 rad) and
    # spring back: it banks right and turns right. Ground truth and stick commands are recorded.
    def fly(keys) -> tuple:
        keys("w", 30, 0.02)  # throttle 0.5
        time.sleep(2.0)
        t_climb = keys("w", 6, 0.02)  # throttle 0.8
        keys("\x1b[B", 1)  # down arrow: pitch up
        time.sleep(4.0)
        t_bank = keys("\x1b[C", 3, 0.2)  # right arrow three times: ailerons 0.6 of full, then back
        time.sleep(6.0)
        return t_climb, t_bank

    _, odom, cmd, (t_climb, t_bank) = keyboard_flight(
        ros,
        tmp_path,
        ["fixed_wing_with_joy.launch", "gui:=false", "joystick:=keyboard", "world_name:=basic", "real_time_factor:=1"],
        lambda log: "launched at 15.0 m/s" in log,
        90,
        WING_RECORDER,
        15,
        fly,
    )
    plot_wing_flight(odom, cmd, t_climb, t_bank, tmp_path / "fixed_wing_keyboard.png")
    assert cmd[:, 4].max() == pytest.approx(0.8, abs=1e-6)  # throttle from W x 36
    assert cmd[:, 1].max() == pytest.approx(0.6, abs=1e-6)  # the right arrow's roll command
    climbed = at(odom, t_bank)[2] - at(odom, t_climb)[2]
    after = odom[odom[:, 0] > t_bank]
    bank = np.degrees(after[:, 4]).max()
    turned = np.degrees(at(odom, t_bank + 6.0)[3] - at(odom, t_bank)[3])
    print(
        f"fixed-wing keyboard flight: climbed {climbed:.1f} m in 4 s, banked up to {bank:.1f} deg right, " f"turned {turned:.1f} deg in 6 s"
    )
    assert climbed > 2.0
    assert bank > 10.0  # roll about +x (FLU) is right wing down
    assert turned < -20.0  # a right turn: the heading decreases
