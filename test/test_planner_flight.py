"""The book's section 5 in flight: the power plant example with the planner in the loop (every
waypoint of example_waypoints_powerplant.txt reached, no collision, clearance to the plant at least
the vehicle's radius), a goal behind the wall of obstacle_course.world reached with a map built in
flight only, goals the planner cannot fly refused in one line while the MAV keeps hovering, a map
built with the VI-sensor's depth camera against the world's octomap, and reactive avoidance with a 2D
laser (section 5.1)."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import clients.octomap
import clients.planner_flight
from rotors_evaluation.bag_data import load_flight
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time
from support.flights import EVAL, contacts_with, evaluate, fly_logged, ground_truth

RESOURCE = REPO / "rotors_gazebo_compat" / "rotors_gazebo" / "resource"


def smallest_clearance(points: np.ndarray, octree: Path, tmp_path: Path, z_offset_m: float = 0.0) -> float:
    """The smallest distance of the points to an occupied leaf of the .bt (rotors_path_clearance)."""
    points_file = tmp_path / "path.txt"
    np.savetxt(points_file, points)
    res = subprocess.run(
        ["rosrun", "rotors_planning", "rotors_path_clearance", str(octree), str(points_file), "0", "0", str(z_offset_m)],
        capture_output=True,
        text=True,
        check=True,
    )
    print(res.stdout.strip())
    return float(res.stdout.split("smallest clearance ")[1].split()[0])


def reached(position: np.ndarray, goal: np.ndarray, tolerance_m: float) -> np.ndarray:
    return np.linalg.norm(position - goal, axis=1) < tolerance_m


@pytest.mark.long  # about 45 s here: the long tier keeps make test under 25 min (the bad goals below stay quick)
def test_power_plant_planner_reaches_every_waypoint_no_collision(ros: RosGraph, tmp_path: Path):
    # 5 s until the planner starts, then a leg per waypoint, each at least its 110 s wait time; the
    # last (25 m home from (25, 0, 5)) starts at about 335 s and takes about 65 s
    bag, data = fly_logged(ros, "mav_powerplant_with_planner.launch", 450.0, "gui:=false")
    log = (ros.tmp_path / "launch.log").read_text()
    radius = float(re.search(r"\[planner\] radius ([0-9.]+) m", log).group(1))
    file_waypoints = np.loadtxt(RESOURCE / "example_waypoints_powerplant.txt")[:, 1:4]
    p = data.position.values
    t = data.position.t
    first_reach = []
    for goal in file_waypoints:
        hits = np.flatnonzero(reached(p, goal, 0.1))
        assert hits.size, f"waypoint {goal} never reached within 0.1 m (closest {np.linalg.norm(p - goal, axis=1).min():.2f} m)"
        first_reach.append(t[hits[0]])
    print("waypoints first reached at", np.round(first_reach, 1), "s")
    assert np.all(np.diff(first_reach) > 0), "waypoints reached out of order"
    # the clearance of the body centre to the plant's octree (the world holds it 0.25 m lower)
    flying = p[p[:, 2] > 0.5]
    clearance = smallest_clearance(flying, RESOURCE / "power_plant.bt", tmp_path, z_offset_m=0.25)
    print(f"smallest clearance of the body centre to the plant {clearance:.3f} m (radius {radius:.3f} m)")
    # the planner's goals (planner/goal, in the bag) are the waypoints to evaluate
    out = evaluate("waypoints_eval.py", bag, "-w", "/planner/goal")
    assert out.count("[Waypoint ") == len(file_waypoints)
    assert "No collisions occurred - good job!" in out
    assert clearance >= radius


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_goal_behind_wall_reached_with_map_built_in_flight(ros: RosGraph):
    # no prior map: the VLP-16's map grows as the MAV flies; the straight line to the goal crosses
    # the wall at x = 2.0-2.2 (y -3..3, up to 3 m)
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_obstacle_course_into_the_unknown.launch",
        "gui:=false",
        "enable_logging:=true",
        "lockstep:=true",
        "real_time_factor:=2",
    )
    try:
        wait_sim_time(ros, 45.0)
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert "from topic" in log  # the planner's map is the mapping node's
    legs = re.findall(r"\[planner\] leg (\d+) to .*?(\d+) replans so far", log)
    replans = re.findall(r"\[planner\] replan (\d+): the trajectory ahead passes ([0-9.]+) m", log)
    print(f"{len(legs)} plans, {len(replans)} replans:", [line for line in log.splitlines() if "[planner]" in line])
    bag = next(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/planner/goal", "/wrench")
    p = data.position.values
    goal = np.array([4.5, 0.0, 1.0])
    print(f"end at {p[-1].round(3)}, {np.linalg.norm(p[-1] - goal):.3f} m from the goal; largest x {p[:, 0].max():.2f}")
    assert np.linalg.norm(p[-1] - goal) < 0.1
    assert len(replans) >= 1  # the wall was not in the first map
    out = evaluate("waypoints_eval.py", bag, "-w", "/planner/goal")
    assert "No collisions occurred - good job!" in out


def send_goal(ros: RosGraph, x: float, y: float, z: float) -> None:
    ros.run_client(clients.planner_flight.send_goal, x=x, y=y, z=z)


@pytest.mark.long  # the long tier (about 20-25 s): make test under 25 min
def test_unflyable_goals_one_line_each_and_mav_keeps_hovering(ros: RosGraph):
    # the box ends 3.3 m high and 3.3 m to the sides: the wall (3 m high, y -3..3) plus the
    # clearance (0.57 m; over its top edge sqrt(0.3^2 + 0.3^2) = 0.42 m) closes it, so nothing behind
    # the wall can be reached
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_with_planner.launch",
        "world_name:=obstacle_course",
        "gui:=false",
        "map_min:=[-3, -3.3, 0.5]",
        "map_max:=[5, 3.3, 3.3]",
        "planning_time:=0.5",
        "lockstep:=true",
        "real_time_factor:=5",
    )
    try:
        wait_sim_time(ros, 6.0)
        send_goal(ros, 0.0, 1.0, 1.5)
        t = wait_sim_time(ros, 16.0)
        before = ground_truth(ros, "firefly")
        for goal in ((2.1, 0.0, 1.5), (50.0, 0.0, 1.0), (4.0, 0.0, 1.0)):
            send_goal(ros, *goal)
            t = wait_sim_time(ros, t + 2.0)
        wait_sim_time(ros, t + 3.0)
        after = ground_truth(ros, "firefly")
    finally:
        stop_launch(proc)
    refusals = [line for line in Path(proc.log_path).read_text().splitlines() if "refused" in line]
    print("\n".join(refusals))
    assert len(refusals) == 3
    assert "goal (2.10, 0.00, 1.50) refused: goal (2.1, 0, 1.5) is inside or near an obstacle" in refusals[0]
    assert "goal (50.00, 0.00, 1.00) refused: goal (50, 0, 1) is outside the map box" in refusals[1]
    assert "goal (4.00, 0.00, 1.00) refused: no path from" in refusals[2]
    assert all(line.rstrip("\x1b[0m").endswith("; hovering") for line in refusals)
    moved = np.linalg.norm(np.subtract([after[k] for k in "xyz"], [before[k] for k in "xyz"]))
    print(f"hovering at ({before['x']:.2f}, {before['y']:.2f}, {before['z']:.2f}), moved {moved:.4f} m meanwhile")
    assert abs(before["y"] - 1.0) < 0.05 and moved < 0.02


def test_missing_map_file_is_one_line_and_goals_are_refused(ros: RosGraph):
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_with_planner.launch",
        "gui:=false",
        "map_source:=file",
        "map_file:=/nonexistent/map.bt",
        "lockstep:=true",
        "real_time_factor:=5",
    )
    try:
        wait_sim_time(ros, 6.0)
        send_goal(ros, 0.0, 0.0, 1.0)
        wait_sim_time(ros, 8.0)
        alive = "/firefly/planner" in ros.run(["rosnode", "list"]).stdout
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    assert alive
    assert log.count("map file '/nonexistent/map.bt' does not exist or holds no OcTree (~map_file)") == 2
    assert "goal (0.00, 0.00, 1.00) refused: no map (map file '/nonexistent/map.bt'" in log


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_map_from_vi_sensor_depth_camera_matches_power_plant(ros: RosGraph, tmp_path: Path):
    built, truth = tmp_path / "built.bt", tmp_path / "truth.bt"
    proc = launch(
        ros,
        "rotors_gazebo",
        "mav_powerplant_with_planner.launch",
        "gui:=false",
        "mapping:=true",
        f"map_save_path:={built}",
        "lockstep:=true",
        "real_time_factor:=0",
    )
    try:
        wait_sim_time(ros, 120.0, timeout_s=900.0)  # the first leg (5-74 s) and a hover at the waypoint
        # the truth at the map's resolution, ground included, in the box the MAV flew in
        ros.run_client(
            clients.octomap.get_octomap,
            timeout=300,
            origin=[10.0, -10.0, 14.75],
            lengths=[50.0, 50.0, 30.5],
            leaf_size=0.25,
            filename=str(truth),
        )
    finally:
        stop_launch(proc)
    log = Path(proc.log_path).read_text()
    print([line for line in log.splitlines() if "[mapping]" in line][-1])
    out = subprocess.run(
        [
            sys.executable,
            str(EVAL / "mapping_eval.py"),
            "-m",
            str(built),
            "-t",
            str(truth),
            "--save_plots",
            "True",
            "--plot_dir",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
    )
    print(out.stdout, out.stderr)
    assert out.returncode == 0
    # precision: occupied leaves on or next to a truth leaf (the plant's faces lie on cell
    # boundaries, so a hit on a face lands on either side by rounding); recall: seen truth leaves
    # found exactly
    precision = float(re.search(r"Precision: ([0-9.]+)", out.stdout).group(1))
    recall = float(re.search(r"Recall of the seen leaves: ([0-9.]+)", out.stdout).group(1))
    assert precision >= 0.9 and recall >= 0.6
    assert (tmp_path / "mapping.png").is_file()


def box_distance(p: np.ndarray, lo, hi) -> np.ndarray:
    """Distance of points (N, 3) to an axis-aligned box."""
    return np.linalg.norm(np.maximum(0.0, np.maximum(np.asarray(lo) - p, p - np.asarray(hi))), axis=1)


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_reactive_avoidance_steers_around_wall_with_2d_laser(ros: RosGraph):
    proc = launch(
        ros, "rotors_gazebo", "mav_reactive_avoidance.launch", "gui:=false", "enable_logging:=true", "lockstep:=true", "real_time_factor:=2"
    )
    try:
        wait_sim_time(ros, 50.0)
    finally:
        stop_launch(proc)
    bag = next(Path(ros.env["ROS_HOME"]).glob("firefly_*.bag"))
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench")
    p = data.position.values
    goal = np.array([4.5, 0.0, 1.0])
    wall = box_distance(p, (2.0, -3.0, 0.0), (2.2, 3.0, 3.0))
    pillar = np.hypot(p[:, 0] - 4.0, p[:, 1] + 4.0) - 0.3
    ball = np.linalg.norm(p - [4.0, 4.0, 1.0], axis=1) - 0.5
    print(
        f"end at {p[-1].round(3)}, {np.linalg.norm(p[-1, :2] - goal[:2]):.3f} m from the goal in xy; smallest "
        f"clearance: wall {wall.min():.2f} m, pillar {pillar.min():.2f} m, ball {ball.min():.2f} m; "
        f"height {p[p[:, 0] > 0.5, 2].min():.2f}-{p[p[:, 0] > 0.5, 2].max():.2f} m"
    )
    assert np.linalg.norm(p[-1, :2] - goal[:2]) < 0.15
    assert min(wall.min(), pillar.min(), ball.min()) > 0.32  # the firefly's radius
    hits = [t for t in contacts_with(bag, "firefly", "::", 3.0)]  # after take-off: with anything
    assert not hits, f"contacts at {hits[:5]}"
