"""Runs that begin and end cleanly (lockstep participants, shutdown order, evaluation windows):
Ctrl-C ends the bag with the flight, a late controller holds the clock, a killed controller pauses
the simulation and its restart resumes the flight."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import clients.clean_runs
import clients.sim
from rotors_evaluation.bag_data import FlightBag
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time

EVAL = REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "scripts" / "hovering_eval.py"
STEP_S = 0.01  # basic.world's step = the controller's period in lockstep


def last_times(bag: Path):
    b = FlightBag(bag)
    try:
        last = {}
        for conn, t_ns, _ in b.reader.messages():
            last[conn.topic] = t_ns * 1e-9
        return last
    finally:
        b.close()


def sim_time(ros: RosGraph) -> float:
    return ros.run_client(clients.sim.clock_now, timeout_s=10)["t"]


def test_ctrl_c_ends_bag_with_flight_and_eval_sees_no_collision(ros: RosGraph):
    # as a user would: the hovering example in lockstep, Ctrl-C after 22 s of sim time. Paced at 10x real
    # time: as fast as possible (40-70x over ROS) the flight ran up to 50 s of sim time on past 22 s in the
    # second or so the Ctrl-C takes to land (test client exit, signal, shutdown), beyond the bound below
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "enable_logging:=true", "lockstep:=true", "real_time_factor:=10")
    try:
        wait_sim_time(ros, 22.0)
    finally:
        os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C: every process of the launch gets SIGINT at once
        proc.wait(timeout=60)
    assert "LCP internal error" not in Path(proc.log_path).read_text(errors="replace")  # resting on the ground
    bag = next(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    last = last_times(bag)
    end = max(last.values())
    print(f"bag ends at {end:.3f} s, last motor command at {last['firefly/command/motor_speed']:.3f} s")
    assert end - last["firefly/command/motor_speed"] <= STEP_S + 1e-9, last
    assert 22.0 <= end < 60.0
    res = subprocess.run([sys.executable, str(EVAL), "-b", str(bag), "--mav_name", "firefly"], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    assert "No collisions occurred" in res.stdout, res.stdout
    assert "Position RMS error: 0.040 m" in res.stdout, res.stdout


def fly_determinism_launch(ros: RosGraph, tag: str, controller_delay_s: float) -> Path:
    proc = ros.start(
        [
            "roslaunch",
            "-p",
            str(ros.port),
            str(REPO / "test/launch/lockstep_determinism.launch"),
            f"log_file:={tag}",
            f"controller_delay_s:={controller_delay_s}",
        ],
        f"launch_{tag}",
    )
    try:
        assert ros.wait_for(lambda: "Successfully spawned" in Path(proc.log_path).read_text(), 60)
        # the set point is latched and the simulation unpaused at once: a late controller must hold the clock
        ros.run_client(clients.clean_runs.hover_set_point_then_unpause, timeout=180, until_s=6.0)
        wait_sim_time(ros, 6.0)
        log = Path(proc.log_path).read_text()
        if controller_delay_s > 0:
            assert "holding the clock at t = 0.000 s" in log, log[-3000:]
    finally:
        stop_launch(proc)
    return next(Path(ros.env["ROS_HOME"]).glob(f"{tag}_*.bag"))


def poses(bag: Path, until_s: float):
    b = FlightBag(bag)
    try:
        return [
            (t_ns, bytes(raw))
            for conn, t_ns, raw in b.reader.messages()
            if conn.topic == "firefly/ground_truth/pose" and t_ns <= until_s * 1e9
        ]
    finally:
        b.close()


def test_controller_starting_5_s_late_gives_same_trajectory(ros: RosGraph):
    on_time = poses(fly_determinism_launch(ros, "on_time", 0), 5.5)
    late = poses(fly_determinism_launch(ros, "late", 5), 5.5)
    assert len(on_time) > 500 and len(on_time) == len(late)
    z = [np.frombuffer(p[1][-56:-32], dtype="<f8")[2] for p in on_time]  # it did take off
    assert max(z) > 0.5
    diff = [i for i, (a, b) in enumerate(zip(on_time, late)) if a != b]
    assert not diff, f"{len(diff)} poses differ, first at t = {on_time[diff[0]][0] * 1e-9:.2f} s"


def test_killed_controller_pauses_lockstep_restart_resumes(ros: RosGraph):
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "enable_logging:=true", "lockstep:=true", "real_time_factor:=0")
    restarted = setpoint = None
    try:
        wait_sim_time(ros, 12.0)
        pid = int(ros.run(["pgrep", "-f", f"lee_position_controller_node.*{ros.env['ROS_LOG_DIR']}"]).stdout.split()[0])
        os.kill(pid, signal.SIGKILL)
        time.sleep(4.0)  # a silent participant is pinged after 2 s
        t_paused = sim_time(ros)
        time.sleep(3.0)
        assert sim_time(ros) == t_paused, "the simulation ran on without its controller"
        log = Path(proc.log_path).read_text()
        assert "/firefly/command/motor_speed went away at t = " in log, log[-3000:]
        # the user restarts it (its parameters are still on the server). The hover set point is
        # latched first, so that the new controller has it from its start: the simulation resumes
        # 0.5 s after the controller answers, and a Lee controller without a set point sends zeros
        setpoint = ros.start(
            [
                "rostopic",
                "pub",
                "-l",
                "/firefly/command/pose",
                "geometry_msgs/PoseStamped",
                "{pose: {position: {z: 1.0}, orientation: {w: 1.0}}}",
            ],
            "setpoint",
        )
        assert ros.wait_for(
            lambda: "/rostopic_" in ros.run(["rostopic", "info", "/firefly/command/pose"], check=False, timeout=10).stdout, 30
        ), "the latched set point was not advertised in 30 s"
        restarted = ros.start(
            [
                "rosrun",
                "rotors_control",
                "lee_position_controller_node",
                "__ns:=/firefly",
                "__name:=lee_position_controller_node",
                "odometry:=odometry_sensor1/odometry",
            ],
            "controller_again",
        )
        wait_sim_time(ros, t_paused + 10.0, timeout_s=120)
        assert "/firefly/command/motor_speed is back; resuming at t = " in Path(proc.log_path).read_text()
    finally:
        for p in (restarted, setpoint):
            if p is not None:
                os.killpg(p.pid, signal.SIGINT)
        stop_launch(proc)
    bag = next(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    b = FlightBag(bag)
    try:
        z = [(t * 1e-9, m.pose.position.z) for m, _, t in b.messages("firefly/ground_truth/pose")]
    finally:
        b.close()
    after = [zz for t, zz in z if t_paused + 5.0 < t < t_paused + 10.0]
    assert after and abs(np.mean(after) - 1.04) < 0.02, "the MAV is not hovering again after the restart"
    res = subprocess.run([sys.executable, str(EVAL), "-b", str(bag), "--mav_name", "firefly"], capture_output=True, text=True)
    assert "No collisions occurred" in res.stdout, res.stdout
