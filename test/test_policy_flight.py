"""A learnt policy flies the ROS simulator: mav_policy_example.launch (rl_policy_node with the
shipped policies, trained on the batched flight engine by rotors_python/examples/train_policy.py,
and the roll-pitch-yawrate-thrust controller) hovers the firefly at the hovering example's set point,
scored by RotorS' hovering_eval.py, on the xacro's airframe and on one with 20 % more mass and 15 %
weaker motors than the controllers are told of; beside the Lee position controller on both."""

import json
import subprocess
from pathlib import Path

import pytest

from conftest import RosGraph, launch, stop_launch, wait_sim_time

AIRFRAMES = {"xacro": (), "heavy_weak": ("mass_scale:=1.2", "motor_constant_scale:=0.85")}


def fly_and_score(ros: RosGraph, tmp_path: Path, launch_file: str, name: str, *args: str) -> float:
    """Flies 21 s of sim time in lockstep, as fast as possible, and returns hovering_eval's position RMS."""
    proc = launch(
        ros, "rotors_gazebo", launch_file, "enable_logging:=true", f"log_file:={tmp_path / name}", "lockstep:=true",
        "real_time_factor:=0", "random_seed:=1", *args,
    )
    try:
        wait_sim_time(ros, 21.0)
    finally:
        stop_launch(proc)
    bag = next(tmp_path.glob(f"{name}*.bag"))  # the bag plugin appends the date
    evaluation = subprocess.run(
        ["rosrun", "rotors_evaluation", "hovering_eval.py", "-b", str(bag), "--mav_name", "firefly", "--plot", "False", "--json", "-"],
        capture_output=True, text=True, env=ros.env,
    )
    assert evaluation.returncode == 0, evaluation.stdout + evaluation.stderr
    result = json.loads(evaluation.stdout[evaluation.stdout.index("{") :])
    assert not [line for line in evaluation.stdout.splitlines() if line.startswith("Collision at time")], evaluation.stdout
    return result["position_rms"]


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_shipped_policy_hovers_both_airframes_scored_by_hovering_eval(ros: RosGraph, tmp_path: Path):
    rms = {}
    for airframe, args in AIRFRAMES.items():
        for policy in ("randomized", "nominal"):
            rms[(policy, airframe)] = fly_and_score(
                ros, tmp_path, "mav_policy_example.launch", f"{policy}_{airframe}", f"policy:={policy}", *args
            )
        rms[("lee", airframe)] = fly_and_score(ros, tmp_path, "mav_hovering_example.launch", f"lee_{airframe}", *args)
    print("hovering_eval position RMS [m]     xacro firefly   +20 % mass, -15 % motor constant")
    for controller in ("randomized", "nominal", "lee"):
        label = {"randomized": "policy, randomised training", "nominal": "policy, nominal training", "lee": "Lee position controller"}
        print(f"{label[controller]:<34} {rms[(controller, 'xacro')]:>8.3f}   {rms[(controller, 'heavy_weak')]:>8.3f}")
    assert rms[("randomized", "xacro")] <= 0.10 and rms[("randomized", "heavy_weak")] <= 0.10, rms
