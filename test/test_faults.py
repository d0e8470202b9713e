"""Faults survived, end to end on the book's hovering example (firefly, set point (0, 0, 1), which the
hover holds 4 cm high because of the deliberate mass and gravity mismatch):

- the controller killed with SIGKILL mid-flight without lockstep: the controller interface holds the
  last command for commandTimeout (2 s of sim time), so a controller back within that finds the MAV
  at its set point; after it the motors stop (one line says so), the MAV falls, and the bag's
  evaluation reports the collision (in lockstep the simulation pauses until the controller is back:
  test_clean_runs.py);
- the simulator killed with SIGKILL: the controller node neither exits nor spins a core, and the bag
  written so far is readable after `rosbag reindex`;
- reset_world and reset_simulation mid-flight: the MAV goes back to its spawn pose (and the clock to 0)
  and flies back to its set point;
- the physics paused for 10 s of wall time and resumed: the clock and the MAV stand still meanwhile
  and the hover goes on where it was.
(Deleting and re-spawning a MAV, also with another rotor count: test_respawn.py.)"""

import json
import subprocess
from pathlib import Path

import pytest

import clients.faults
from support import RosGraph, launch, stop_launch, wait_sim_time


@pytest.mark.long  # the long tier (about 40 s): make test under 25 min
def test_controller_killed_no_lockstep_recovers_or_reports_fall(ros: RosGraph, tmp_path: Path):
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_hovering_example.launch",
        "real_time_factor:=1",
        "enable_logging:=true",
        f"log_file:={tmp_path / 'faults'}",
    )
    try:
        wait_sim_time(ros, 12.0)
        r = ros.run_client(clients.faults.controller_killed_without_lockstep, timeout=240)
    finally:
        stop_launch(proc)
    bag = next(tmp_path.glob("faults*.bag"))  # the bag plugin appends the date
    evaluation = subprocess.run(
        ["rosrun", "rotors_evaluation", "hovering_eval.py", "-b", str(bag), "--mav_name", "firefly", "--plot", "False"],
        capture_output=True,
        text=True,
        env=ros.env,
    )
    print(
        f"controller back after {r['gap']:.2f} s: largest offset {r['worst_after_short_outage'] * 1000:.0f} mm, "
        f"{r['error_after'] * 1000:.1f} mm after 8 s; gone for good at {r['t_killed_for_good']:.1f} s: "
        f"lowest z {r['lowest']:.2f} m"
    )
    print(evaluation.stdout[-600:])
    assert r["gap"] < 2.0 and r["worst_after_short_outage"] < 0.1
    assert r["error_after"] < 0.02
    assert r["lowest"] < 0.15  # it fell
    collisions = [line for line in evaluation.stdout.splitlines() if line.startswith("Collision at time")]
    assert evaluation.returncode == 0 and collisions, evaluation.stdout + evaluation.stderr
    t_collision = float(collisions[0].split()[3])
    assert t_collision > r["t_killed_for_good"], collisions


def test_simulator_killed_leaves_nodes_idle_bag_recoverable(ros: RosGraph, tmp_path: Path):
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_hovering_example.launch",
        "lockstep:=true",
        "real_time_factor:=0",
        "enable_logging:=true",
        f"log_file:={tmp_path / 'killed'}",
    )
    try:
        wait_sim_time(ros, 20.0)
        r = ros.run_client(clients.faults.simulator_killed, timeout=240)
    finally:
        stop_launch(proc)
    print(f"simulator killed: controller alive {r['lee_alive']}, CPU {r['lee_cpu_s_in_5_s']:.3f} s in 5 s")
    assert r["lee_alive"] and r["lee_cpu_s_in_5_s"] < 0.25
    bag = next(tmp_path.glob("killed*.bag"))
    evaluate = [
        "rosrun",
        "rotors_evaluation",
        "hovering_eval.py",
        "-b",
        str(bag),
        "--mav_name",
        "firefly",
        "--plot",
        "False",
        "--json",
        "-",
    ]
    before = subprocess.run(evaluate, capture_output=True, text=True, env=ros.env)
    if before.returncode != 0:  # an unindexed bag: the one line names the fix
        assert f"rosbag reindex {bag}" in before.stderr, before.stderr
        reindex = subprocess.run(["rosbag", "reindex", str(bag)], capture_output=True, text=True, env=ros.env)
        assert reindex.returncode == 0, reindex.stdout + reindex.stderr
    after = subprocess.run(evaluate, capture_output=True, text=True, env=ros.env)
    assert after.returncode == 0, after.stderr
    summary = json.loads(after.stdout[after.stdout.index("{") :])
    print(f"bag after the kill ({'readable' if before.returncode == 0 else 'reindexed'}): " f"position RMS {summary['position_rms']:.3f} m")
    assert summary["position_rms"] < 0.06


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_reset_world_and_reset_simulation_mid_flight(ros: RosGraph):
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "lockstep:=true", "real_time_factor:=1")
    try:
        wait_sim_time(ros, 12.0)
        r = ros.run_client(clients.faults.reset_world_and_simulation, timeout=240)
    finally:
        stop_launch(proc)
    print(
        f"reset_world: z {r['z_after_reset_world']:.2f} m, back within {r['error_8_s_after_reset_world'] * 1000:.1f} "
        f"mm after 8 s; reset_simulation: clock {r['clock_after_reset_simulation']:.2f} s, z "
        f"{r['z_after_reset_simulation']:.2f} m, back within {r['error_8_s_after_reset_simulation'] * 1000:.1f} mm"
    )
    assert r["z_after_reset_world"] < 0.3 and r["z_after_reset_simulation"] < 0.3
    assert r["clock_after_reset_simulation"] < 1.0
    assert r["error_8_s_after_reset_world"] < 0.01 and r["error_8_s_after_reset_simulation"] < 0.01


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_reset_simulation_while_lockstep_waits_for_the_controller(ros: RosGraph):
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "lockstep:=true", "real_time_factor:=0")
    try:
        wait_sim_time(ros, 1.0)
        r = ros.run_client(clients.faults.reset_simulation_repeatedly, timeout=300, count=30)
    finally:
        stop_launch(proc)
    went_on = [t for t in r["reached"] if t >= 0.5]
    print(f"30 resets of a lockstep flight: the clock went on after {len(went_on)} of them")
    assert len(went_on) == 30


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_pause_for_10_s_and_resume(ros: RosGraph):
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "real_time_factor:=1")
    try:
        wait_sim_time(ros, 12.0)
        r = ros.run_client(clients.faults.pause_and_resume, timeout=240)
    finally:
        stop_launch(proc)
    print(
        f"paused 10 s: clock advanced {r['clock_advanced_while_paused']:.3f} s, MAV moved "
        f"{r['moved_while_paused'] * 1000:.2f} mm; largest offset in 5 s after resuming "
        f"{r['worst_after_resume'] * 1000:.1f} mm"
    )
    assert r["clock_advanced_while_paused"] == 0.0 and r["moved_while_paused"] == 0.0
    assert r["worst_after_resume"] < 0.01


@pytest.mark.long  # the long tier (about 20-25 s): make test under 25 min
def test_controller_stopped_in_debugger_never_freezes_simulator(ros: RosGraph):
    # lockstep: SIGSTOP the controller (a debugger's breakpoint). Its node still accepts connections
    # but answers nothing; the simulator pings it from a worker thread with a deadline, so services
    # keep answering at once, the participant is declared gone, and SIGCONT resumes the flight
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example.launch", "lockstep:=true", "real_time_factor:=1")
    try:
        wait_sim_time(ros, 8.0)
        r = ros.run_client(clients.faults.controller_stopped_as_in_a_debugger, timeout=240)
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    print(r)
    assert r["slowest_service_call_s"] < 0.5  # the simulation thread never waited on the stopped node
    assert r["clock_while_stopped"] < 0.05  # lockstep held the clock meanwhile
    assert "lockstep: /firefly/command/motor_speed went away" in log and "(ping failed)" in log
    assert "/firefly/command/motor_speed is back" in log
    assert r["resumed_to"] >= 2.0
