"""Bad input at the autopilot interfaces: each a one-line error naming the cause, and the simulator
keeps running. pymavlink stands in for PX4 (not on these machines) on the autopilot's side of the
socket; socat's pty pair stands in for a Pixhawk's USB serial port.
"""

import socket
import subprocess
import time

import numpy as np
import pytest
from pymavlink import mavutil

import rotors_sim as rs
from support import wait_until
from support.px4 import DT, SteppingWorld, answer, connect, free_port, make_world, next_sensor, start_lockstep


def run_until_sensor(link, n=1):
    for _ in range(n):
        next_sensor(link)
        answer(link, [0.5] * 6, armed=True)


def test_malformed_frames_dropped_with_one_line_link_stays_up(capfd):
    port = free_port()
    world = make_world(port, mavlink_answer_timeout=0.01)  # PX4's plugin's wait: the lost answer costs 10 ms
    stepper, link = start_lockstep(world, port, 40)
    run_until_sensor(link, 5)
    good = link.mav.hil_actuator_controls_encode(0, [0.5] * 16, 129, 1).pack(link.mav)
    corrupt = bytearray(good)
    corrupt[20] ^= 0xFF  # a payload byte: the checksum no longer matches
    link.write(bytes(corrupt))
    link.write(good[:30])  # a truncated frame; the next frame's start resynchronises the parser
    run_until_sensor(link, 34)
    stepper.join()
    err = capfd.readouterr().err
    lines = [line for line in err.splitlines() if "malformed MAVLink frame" in line]
    print(lines[0])
    assert lines and "dropped" in lines[0]
    assert world.time == pytest.approx(42 * DT)  # one answer was lost with the truncated frame: the step went on


def test_skipped_answers_never_end_the_session(capfd):
    """PX4's Gazebo plugin (PX4-SITL_gazebo-classic src/gazebo_mavlink_interface.cpp) waits at most
    10 ms for HIL_ACTUATOR_CONTROLS, only while PX4 is armed, and never closes the link for silence
    (PX4's simulator_mavlink connects once: a closed link needs a PX4 restart). A stand-in that stops
    answering for 50 steps: the world goes on with the last outputs, the link stays up, and the
    answers that come again are applied."""
    port = free_port()
    world = make_world(port, mavlink_answer_timeout=0.01)
    stepper, link = start_lockstep(world, port, 200)
    run_until_sensor(link, 20)
    for _ in range(50):
        next_sensor(link)  # read, never answered
    answers_before = world.autopilot_answers("firefly")
    run_until_sensor(link, 100)
    stepper.join()
    err = capfd.readouterr().err
    late = [line for line in err.splitlines() if "no HIL_ACTUATOR_CONTROLS within" in line]
    print(late[0])
    print(f"answers applied after the silence: {world.autopilot_answers('firefly') - answers_before}; " f"t = {world.time:.3f} s")
    assert late and "the link stays up" in late[0]
    assert "closed the connection" not in err
    assert world.autopilot_answers("firefly") - answers_before >= 95  # the link is still up
    assert world.time == pytest.approx(202 * DT)


def test_a_disarmed_autopilot_is_not_waited_for():
    """PX4's Gazebo plugin waits for answers only while PX4 is armed: a disarmed stand-in that never
    answers again does not slow the world."""
    port = free_port()
    world = make_world(port, mavlink_answer_timeout=30.0)
    stepper = SteppingWorld(world)
    stepper.run(1)
    stepper.join()
    link = connect(port)
    stepper.run(1)
    stepper.join()
    next_sensor(link)
    answer(link, [0.0] * 6, armed=False)
    start = time.monotonic()
    stepper.run(500)
    stepper.join()
    print(f"500 steps without answers in {time.monotonic() - start:.2f} s of wall time")
    assert world.time == pytest.approx(502 * DT) and time.monotonic() - start < 20.0


def test_message_from_other_system_id_ignored_with_one_line(capfd):
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 20)
    run_until_sensor(link, 5)
    next_sensor(link)  # the world waits for this one's answer: every earlier answer is applied
    answers = world.autopilot_answers("firefly")
    other = mavutil.mavlink.MAVLink(None, srcSystem=7, srcComponent=1)
    link.write(other.hil_actuator_controls_encode(0, [1.0] * 16, 129, 1).pack(other))  # not an answer
    answer(link, [0.5] * 6, armed=True)
    run_until_sensor(link, 14)
    stepper.join()
    assert world.autopilot_answers("firefly") == answers + 15  # system 7's message was not applied
    err = capfd.readouterr().err
    line = next(line for line in err.splitlines() if "system id 7" in line)
    print(line)
    assert "system id 1" in line and "ignored" in line


def test_nan_outputs_keep_last_valid_and_out_of_range_clamped(capfd):
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 300)
    run_until_sensor(link, 150)  # 0.5 everywhere: the rotors settle at 419 rad/s
    for _ in range(75):
        next_sensor(link)
        answer(link, [float("nan")] + [0.9] * 5, armed=True)  # refused whole
    settled = np.abs(world.rotor_speeds("firefly"))
    for _ in range(75):
        next_sensor(link)
        answer(link, [3.0] * 6, armed=True)  # clamped to 1
    stepper.join()
    clamped = np.abs(world.rotor_speeds("firefly"))
    err = capfd.readouterr().err
    print(next(line for line in err.splitlines() if "nan" in line.lower()))
    print(next(line for line in err.splitlines() if "outside -1..1" in line))
    np.testing.assert_allclose(settled, 0.5 * 838, rtol=2e-3)
    np.testing.assert_allclose(clamped, 838, rtol=2e-3)
    assert world.time == pytest.approx(302 * DT)  # every answer counted: lockstep went on


def test_autopilot_disconnect_disarms_motors_and_can_reconnect(capfd):
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 400)
    run_until_sensor(link, 100)
    link.close()  # PX4 killed mid-flight
    stepper.join()  # the world runs on without it
    assert np.abs(world.rotor_speeds("firefly")).max() < 1.0  # disarmed values: stopped
    err = capfd.readouterr().err
    print(next(line for line in err.splitlines() if "closed the connection" in line))
    # PX4 restarted: it connects again (the kernel takes the connection before the interface does),
    # the next step accepts it and sends HIL_SENSOR, and lockstep resumes with the first answer
    link = connect(port)
    stepper.run(1)
    stepper.join()
    next_sensor(link)
    answer(link, [0.5] * 6, armed=True)
    stepper.run(200)
    run_until_sensor(link, 10)
    next_sensor(link)
    held = world.time
    time.sleep(0.3)
    assert world.time == held  # lockstep again: waiting for the next answer
    link.close()
    stepper.join()


def test_a_port_in_use_is_refused_at_spawn_with_one_line():
    with socket.socket() as taken:
        taken.bind(("0.0.0.0", 0))
        taken.listen(1)
        port = taken.getsockname()[1]
        world = rs.World("basic", step_size=DT)
        with pytest.raises(rs.SimError) as e:
            world.spawn_mav("firefly", enable_mavlink_interface=True, mavlink_tcp_port=port)
    print(e.value)
    assert f":{port}" in str(e.value) and "in use" in str(e.value)
    world.spawn_mav("firefly", namespace="other")  # the world still works
    world.step(10)


def test_missing_serial_device_is_one_line_and_world_runs_on(capfd):
    world = rs.World("basic", step_size=DT)
    world.spawn_mav("firefly", enable_mavlink_interface=True, mavlink_serial_enabled=True, mavlink_serial_device="/dev/ttyACM_not_there")
    world.step(100)
    assert world.time == pytest.approx(100 * DT)
    line = next(line for line in capfd.readouterr().err.splitlines() if "ttyACM_not_there" in line)
    print(line)
    assert "No such file" in line and "retrying" in line


def test_hitl_over_serial_pty_exchanges_sensor_and_controls(tmp_path):
    a, b = tmp_path / "sim", tmp_path / "fc"
    socat = subprocess.Popen(["socat", f"pty,raw,echo=0,link={a}", f"pty,raw,echo=0,link={b}"])
    try:
        wait_until(lambda: a.exists() and b.exists(), 5, f"socat's two ptys {a} and {b}")
        world = rs.World("basic", step_size=DT)
        world.spawn_mav(
            "firefly", enable_mavlink_interface=True, mavlink_serial_enabled=True, mavlink_serial_device=str(a), mavlink_baud_rate=921600
        )
        fc = mavutil.mavlink_connection(str(b), baud=921600, source_system=1)
        sensors = 0
        for _ in range(50):
            world.step(1)  # HITL runs on the autopilot's clock: no lockstep, the world does not wait
            while (m := fc.recv_match(type="HIL_SENSOR", blocking=False)) is not None:
                sensors += 1
                answer(fc, [0.6] * 6, armed=True, t_us=m.time_usec)
            time.sleep(0.002)
        world.step(200)
        print(f"{sensors} HIL_SENSOR over the pty, {world.autopilot_answers('firefly')} answers applied")
        assert sensors >= 40 and world.autopilot_answers("firefly") >= 30
        assert np.abs(world.rotor_speeds("firefly")).min() > 0.5 * 838
    finally:
        socat.terminate()
        socat.wait()


def test_a_new_heartbeat_system_id_is_followed(capfd):
    """PX4 restarted with another MAV_SYS_ID on the same link: its heartbeat says so, and its answers
    are taken from then on (as PX4's Gazebo plugin answers whatever system is on the link)."""
    port = free_port()
    world = make_world(port)
    stepper, link = start_lockstep(world, port, 40)
    run_until_sensor(link, 10)
    next_sensor(link)  # the world waits for this one's answer: every earlier answer is applied
    before = world.autopilot_answers("firefly")
    other = mavutil.mavlink.MAVLink(None, srcSystem=7, srcComponent=1)
    link.write(other.heartbeat_encode(2, 12, 0, 0, 0).pack(other))
    for i in range(20):
        if i > 0:
            next_sensor(link)
        link.write(other.hil_actuator_controls_encode(0, [0.5] * 16, 129, 1).pack(other))
    next_sensor(link)  # waiting again: the 20 answers of system 7 are in
    captured = capfd.readouterr()
    print(next(line for line in (captured.out + captured.err).splitlines() if "system id 7" in line))
    assert world.autopilot_answers("firefly") - before == 20
    link.write(other.hil_actuator_controls_encode(0, [0.5] * 16, 129, 1).pack(other))
    while stepper.thread.is_alive():  # system 7 answers the remaining steps
        if link.recv_match(type="HIL_SENSOR", blocking=True, timeout=1.0) is not None:
            link.write(other.hil_actuator_controls_encode(0, [0.5] * 16, 129, 1).pack(other))
    stepper.join()


def test_a_lockstep_rate_other_than_the_firmwares_is_refused_with_one_line():
    """The lockstep Betaflight firmware runs its loops at a compiled-in 500 Hz state rate
    (SIMULATOR_LOCKSTEP_HZ in betaflight_lockstep.patch): another lockstep_rate is one line at spawn."""
    world = rs.World("basic", step_size=1.0 / 400)
    with pytest.raises(rs.SimError) as e:
        world.spawn_mav("iris", enable_betaflight_interface=True, betaflight_lockstep_rate=400)
    print(e.value)
    assert "lockstep_rate 400" in str(e.value) and "built for 500 Hz" in str(e.value) and "\n" not in str(e.value)
    world.spawn_mav("firefly", namespace="other")  # the world still works
    world.step(10)
