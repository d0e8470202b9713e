"""A learnt policy flies the ROS simulator: mav_policy_example.launch (rl_policy_node with the
shipped policies, trained on the batched flight engine by rotors_python/examples/train_policy.py,
and the roll-pitch-yawrate-thrust controller) hovers the firefly at the hovering example's set point,
scored by RotorS' hovering_eval.py, on the xacro's airframe and on one with 20 % more mass and 15 %
weaker motors than the controllers are told of; beside the Lee position controller on both."""

import json
import subprocess
from pathlib import Path

import pytest

from support import RosGraph, launch, stop_launch, wait_sim_time

AIRFRAMES = {"xacro": (), "heavy_weak": ("mass_scale:=1.2", "motor_constant_scale:=0.85")}


def fly_and_score(
    ros: RosGraph, tmp_path: Path, launch_file: str, name: str, *args: str, until_s: float = 21.0, evaluation: str = "hovering_eval.py"
) -> dict:
    """Flies until_s of sim time in lockstep, as fast as possible; `evaluation`'s JSON result."""
    proc = launch(
        ros,
        "rotors_gazebo",
        launch_file,
        "enable_logging:=true",
        f"log_file:={tmp_path / name}",
        "lockstep:=true",
        "real_time_factor:=0",
        "random_seed:=1",
        *args,
    )
    try:
        wait_sim_time(ros, until_s)
    finally:
        stop_launch(proc)
    bag = next(tmp_path.glob(f"{name}*.bag"))  # the bag plugin appends the date
    out = subprocess.run(
        ["rosrun", "rotors_evaluation", evaluation, "-b", str(bag), "--mav_name", "firefly", "--plot", "False", "--json", "-"],
        capture_output=True,
        text=True,
        env=ros.env,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    return json.loads(out.stdout[out.stdout.index("{") :])


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_shipped_policy_hovers_both_airframes_scored_by_hovering_eval(ros: RosGraph, tmp_path: Path):
    scores = {}
    for airframe, args in AIRFRAMES.items():
        for policy in ("randomized", "nominal"):
            scores[(policy, airframe)] = fly_and_score(
                ros, tmp_path, "mav_policy_example.launch", f"{policy}_{airframe}", f"policy:={policy}", *args
            )
        scores[("lee", airframe)] = fly_and_score(ros, tmp_path, "mav_hovering_example.launch", f"lee_{airframe}", *args)
    labels = {"randomized": "policy, randomised training", "nominal": "policy, nominal training", "lee": "Lee position controller"}

    def cell(r: dict) -> str:
        return f"{r['position_rms']:.3f}" + (" (on the ground)" if r["collision_times"] else "")

    print("hovering_eval position RMS [m]     xacro firefly   +20 % mass, -15 % motor constant")
    for controller, label in labels.items():
        print(f"{label:<34} {cell(scores[(controller, 'xacro')]):>8}   {cell(scores[(controller, 'heavy_weak')]):>8}")
    for airframe in AIRFRAMES:
        for policy in ("randomized", "nominal"):
            assert not scores[(policy, airframe)]["collision_times"], scores[(policy, airframe)]
        assert scores[("randomized", airframe)]["position_rms"] <= 0.10, scores
    # Lee's law has no integrator: on the ground, 0.92 m under the set point, it commands
    # k_p e_z + m_c g = 6 N/m 0.92 m + 1.56779 kg 9.81 m/s^2 = 20.9 N through its own motor constant;
    # the motors make 0.85 of it, 17.8 N, under the 18.2 N weight of 1.2 x 1.54503 kg at g = 9.8:
    # it stays on the ground, as hovering_eval's collision says
    assert scores[("lee", "heavy_weak")]["collision_times"] and not scores[("lee", "xacro")]["collision_times"]


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_shipped_policy_flies_a_waypoint_file_scored_by_waypoints_eval(ros: RosGraph, tmp_path: Path):
    """RotorS' waypoint publisher sends the file at 30 s of sim time; each point is 1 m or more from
    the one before, farther than the policy's training offsets (0.5 m per axis): the node flies
    towards it through the point 0.5 m ahead."""
    waypoints = tmp_path / "waypoints.txt"
    waypoints.write_text("8 1 0 1 0\n8 1 1.5 2 0\n8 0 0 1 0\n")  # wait_time x y z yaw_deg
    r = fly_and_score(
        ros,
        tmp_path,
        "mav_policy_example.launch",
        "waypoints",
        f"waypoint_file:={waypoints}",
        "mass_scale:=1.2",
        "motor_constant_scale:=0.85",
        until_s=55.0,
        evaluation="waypoints_eval.py",
    )
    settle = [segment["settling_time"] for segment in r["segments"][1:]]
    print(
        f"waypoints_eval, the randomised policy on the heavier, weaker firefly: settling times {settle} s, "
        f"mean position RMS {r['position_rms']:.3f} m"
    )
    assert len(r["segments"]) == 3 and all(t is not None for t in settle), r
    assert r["position_rms"] < 0.05, r
