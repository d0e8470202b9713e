"""Worlds with structure, flown end to end: a MAV sent through the obstacle course's wall stops at the
wall, the contact is recorded and hovering_eval.py counts it; the power plant example crashes where
the book says it must (the straight line between its waypoints is in collision, seed section 3);
no run prints ODE's 'LCP internal error'."""

import importlib.util
from pathlib import Path

import numpy as np

import clients.octomap
from rotors_evaluation.metrics import rms_error
from support import REPO, RosGraph, launch, stop_launch
from support.flights import contacts_with, evaluate, fly_logged

WALL_FACE_X_M = 2.0  # obstacle_course.world: the wall spans x = 2.0 .. 2.2


def test_mav_sent_through_wall_stops_and_eval_counts_collision(ros: RosGraph):
    # the hovering example's private parameters: the waypoint (4, 0, 1) lies behind the wall
    ros.run(["rosparam", "set", "/firefly/hovering_example/x", "4.0"])
    bag, data = fly_logged(ros, "mav_hovering_example.launch", 20.0, "world_name:=obstacle_course")
    assert np.allclose(data.waypoints[0].position, [4.0, 0.0, 1.0])
    x = data.position.values[:, 0]
    print(f"largest x {x.max():.3f} m; the wall's face at {WALL_FACE_X_M} m")
    assert x.max() < WALL_FACE_X_M  # the body centre never reaches the wall: it did not pass through
    hits = contacts_with(bag, "firefly", "wall::link::collision", data.waypoints[0].t)
    assert hits, "no contact with the wall recorded"
    out = evaluate("hovering_eval.py", bag)
    assert "One or more collisions occurred - no points are awarded!" in out
    first = float(out.split("Collision at time ")[1].split(" s!")[0])
    assert any(abs(first - t) < 1e-3 for t in hits)  # the evaluation counts a recorded contact


def test_power_plant_example_collides_as_book_says_and_counted(ros: RosGraph):
    # seed section 3: "the straight line solution is in collision, and the MAV is going to crash into
    # the wall without a planner"
    bag, data = fly_logged(ros, "mav_powerplant_with_waypoint_publisher.launch", 45.0, "gui:=false")
    wp = data.waypoints[0]
    assert np.allclose(wp.position, [2.0, -27.0, 15.0]) and 30.0 <= wp.t < 31.0
    # before the waypoint the MAV rests on the ground: its only contacts are the ground's
    hits = contacts_with(bag, "firefly", "powerplant::link::collision", wp.t + 0.5)
    assert hits, "the flight to (2, -27, 15) did not touch the plant"
    print(f"first contact with the plant at {hits[0]:.3f} s")
    assert "One or more collisions occurred - no points are awarded!" in evaluate("waypoints_eval.py", bag)


def test_get_octomap_of_power_plant_agrees_with_rotors_octree(ros: RosGraph, tmp_path: Path):
    world = REPO / "rotors_gazebo_compat" / "rotors_gazebo" / "worlds" / "powerplant.world"
    reference = REPO / "rotors_gazebo_compat" / "rotors_gazebo" / "resource" / "power_plant.bt"
    proc = launch(ros, "gazebo_ros", "empty_world.launch", f"world_name:={world}", "paused:=true", "gui:=false", name="world")
    out = tmp_path / "powerplant_from_service.bt"
    try:
        # power_plant.bt spans x -15..35, y -35..15, z 0..50; the world holds it 0.25 m lower
        result = ros.run_client(
            clients.octomap.get_octomap,
            timeout=300,
            origin=[10.0, -10.0, 24.75],
            lengths=[50.0, 50.0, 50.0],
            leaf_size=0.25,
            filename=str(out),
        )
    finally:
        stop_launch(proc)
    assert result["resolution"] == 0.25 and result["bytes"] > 0
    assert result["latitude"] == 47.3667
    res = ros.run(["rosrun", "rotors_core", "rotors_octomap_compare", str(out), str(reference), "0", "0", "0.25"])
    print(res.stdout)
    iou = float(res.stdout.split("intersection over union ")[1].split()[0])
    assert iou >= 0.9999, res.stdout  # measured: 1.0000 (2228.828 m^3 occupied in both)


def test_mav_sent_into_heightmap_hillside_stops_on_its_surface(ros: RosGraph):
    # the terrain the heightmap image was made from (the model's own generator script)
    spec = importlib.util.spec_from_file_location("make_hills", REPO / "rotors_gazebo_compat/rotors_gazebo/models/hills/make_hills.py")
    make_hills = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_hills)
    height_m = make_hills.height_m

    # (20, 0, 3): 3 m above the valley floor but 2.1 m under the hillside at x = 20 (h = 5.15 m)
    for axis, value in (("x", 20.0), ("y", 0.0), ("z", 3.0)):
        ros.run(["rosparam", "set", f"/firefly/hovering_example/{axis}", str(value)])
    bag, data = fly_logged(ros, "mav_hovering_example.launch", 16.0, "world_name:=hills")
    p = data.position.values
    clearance = p[:, 2] - height_m(p[:, 0], p[:, 1])
    print(f"farthest x {p[:, 0].max():.2f} m; least height of the body centre over the terrain {clearance.min():.3f} m")
    assert clearance.min() > 0.03  # never inside the hill (the body's half height is 0.08 m)
    # it ends pressed against the hillside, short of the set point: on the surface, where the
    # terrain is higher than the set point
    end = p[-1]
    print(f"end at {end.round(2)}, terrain there {height_m(end[0], end[1]):.2f} m")
    assert end[0] < 19.0 and clearance[-1] < 0.3 and height_m(end[0], end[1]) > 3.0
    assert contacts_with(bag, "firefly", "hills::link::collision", data.waypoints[0].t + 1.0)


def test_the_waypoint_world_floor_carries_the_hovering_example(ros: RosGraph):
    # RotorS' waypoint world: the occupancy grid at (5, 0, 0) with its own floor, no ground plane
    bag, data = fly_logged(ros, "mav_hovering_example.launch", 21.0, "world_name:=waypoint")
    wp = data.waypoints[0]
    z = data.position.values[:, 2]
    assert 0.0 < z[data.position.t < wp.t].min() < 0.2  # resting on the floor (top at z = 0) before take-off
    rms = rms_error(data.position.window(wp.t + 5, wp.t + 15), wp.position)
    assert abs(rms - 0.040) <= 0.005, rms  # as in the basic world (book section 3.6)
