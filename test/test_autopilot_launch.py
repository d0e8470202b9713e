"""The autopilot launch files as a user runs them: mav_px4_sitl.launch (the simulator server with
its --step-size, the iris with the MAVLink interface on TCP 4560 + instance, lockstep) with
pymavlink on PX4's side (PX4 is not on these machines: it stands in for it), and
mav_betaflight_sitl.launch with the real Betaflight firmware started by the launch file and RC on
the vehicle's rc topic (sensor_msgs/Joy), as joy_to_rc or a user's node sends it.
"""

import time

import numpy as np
import pytest
from pymavlink import mavutil

import clients.autopilot_launch
from support import launch, retry_until
from support.px4 import answer

pytestmark = pytest.mark.xdist_group("betaflight_ports")


def test_px4_sitl_launch_listens_on_4560_plus_instance_lockstep(ros):
    instance = 23
    # the launch's real_time_factor 1: PX4 has 4 ms of wall time per step (test_autopilot_faults.py
    # checks the waiting itself in process)
    launch(ros, "rotors_gazebo", "mav_px4_sitl.launch", f"instance:={instance}", "random_seed:=2")
    link = retry_until(
        lambda: mavutil.mavlink_connection(f"tcp:127.0.0.1:{4560 + instance}", source_system=1, autoreconnect=False),
        60,
        f"the simulator listening on TCP {4560 + instance}",
    )
    link.mav.heartbeat_send(2, 12, 0, 0, 0)
    # until the first answer the world does not wait: it may have sent several HIL_SENSOR by then;
    # after it, while PX4 is armed, each HIL_SENSOR waits for its answer at most 10 ms of wall time
    # (PX4's Gazebo plugin); what was sent before is read and dropped
    first = link.recv_match(type="HIL_SENSOR", blocking=True, timeout=30)
    assert first is not None, "no HIL_SENSOR from the launched vehicle"
    answer(link, [0.0] * 4, armed=True, t_us=first.time_usec)
    last = None
    for _ in range(250):  # 1 s of sim time at 4 ms
        m = link.recv_match(type="HIL_SENSOR", blocking=True, timeout=30)
        assert m is not None, "no HIL_SENSOR from the launched vehicle"
        if last is not None:
            assert m.time_usec - last == 4000  # the launch's --step-size 0.004: one HIL_SENSOR a step
        last = m.time_usec
        answer(link, [0.0] * 4, armed=True, t_us=m.time_usec)
    link.close()


def test_betaflight_sitl_launch_runs_firmware_flies_on_rc_topic(ros, tmp_path):
    """The lockstep firmware, started by the launch file, answers and flies on RC from /iris/rc (the
    sticks are held for spans of sim time, the firmware's clock). No retry: the lockstep build has no
    start-up race (docs/autopilots.md)."""
    proc = launch(ros, "rotors_gazebo", "mav_betaflight_sitl.launch", f"betaflight_workdir:={tmp_path / 'bf'}", "random_seed:=3")
    result = ros.run_client(clients.autopilot_launch.betaflight_rc_climb, timeout=300, log_path=str(proc.log_path))
    answered = "Betaflight answers" in proc.log_path.read_text(errors="replace")
    print(f"firmware answered: {answered}; climbed to {result['z_max']:.2f} m on RC from /iris/rc")
    assert answered and result["z_max"] > 1.0


def test_ardupilot_sitl_launch_servo_port_9002_plus_10_instance(ros):
    """A stand-in for ArduPilot's SIM_JSON (ArduPilot is not on these machines), instance 3, with the
    downward rangefinder (enable_rangefinder:=true), whose reading goes out as rng_1."""
    import json
    import socket
    import struct

    launch(ros, "rotors_gazebo", "mav_ardupilot_sitl.launch", "instance:=3", "real_time_factor:=0", "enable_rangefinder:=true")
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.settimeout(0.5)
    deadline, answers = time.monotonic() + 60, []
    frame = 0
    while len(answers) < 200:
        assert time.monotonic() < deadline, f"{len(answers)} answers from UDP 9032"
        sock.sendto(struct.pack("<HHI16H", 18458, 400, frame, *([1000] * 16)), ("127.0.0.1", 9032))
        frame += 1
        try:
            data = sock.recv(4096)
        except OSError:
            continue
        answers.append(json.loads(data.strip().split(b"\n")[-1]))
    steps = np.diff([a["timestamp"] for a in answers[-100:]])
    print(f"{len(answers)} answers; timestamps step by {steps.min():.4f}-{steps.max():.4f} s")
    assert np.allclose(steps, 0.001)  # the launch's --step-size 0.001: one step per frame
    # on the ground the beam (5 cm under the body) is closer than its 0.06 m minimum: REP 117's -inf
    # goes out as 0, which AP_RangeFinder_SITL reads as out of range low
    assert answers[-1]["rng_1"] == 0.0, answers[-1]


def test_mav_px4_sitl_multi_launch_gives_each_vehicle_its_port(ros):
    """Each of the three instances answers on its own port. One link at a time, closed after its first
    HIL_SENSOR: a connected link that nobody reads fills its socket and holds the world in send() (as
    a PX4 stopped in a debugger would), so reading the links one after another while all three are
    open can stall the world before the last one is accepted."""
    launch(ros, "rotors_gazebo", "mav_px4_sitl_multi.launch", "real_time_factor:=0")
    for instance in range(3):
        port = 4560 + instance
        link = retry_until(
            lambda port=port: mavutil.mavlink_connection(f"tcp:127.0.0.1:{port}", source_system=1, autoreconnect=False),
            60,
            f"the simulator listening on TCP {port}",
        )
        m = link.recv_match(type="HIL_SENSOR", blocking=True, timeout=30)
        link.close()
        assert m is not None, f"no HIL_SENSOR on TCP {4560 + instance}"
