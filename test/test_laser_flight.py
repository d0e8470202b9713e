"""End to end: lasers on a flying MAV (mav_hovering_example_with_lidar.launch, lockstep, as fast as
possible). A VLP-16 in the power plant: the cloud's layout is velodyne_pointcloud's, it comes at
10 Hz of sim time, and its points, put in the world with the ground-truth pose, lie on the plant's
OctoMap cells or on the tarmac around it. The downward rangefinder over the basic world reads the height of the sensor; the
Hokuyo publishes REP 117 LaserScans."""

import math
from pathlib import Path

import numpy as np
import pytest

import clients.laser_flight
from support import REPO, RosGraph, launch, stop_launch, wait_sim_time

PLANT = REPO / "rotors_gazebo_compat" / "rotors_gazebo" / "resource" / "power_plant.bt"
LIDAR_ABOVE_BASE_M = 0.15  # lidar_xyz's default
# powerplant.world: the octree spans x -15..35, y -35..15; around it the tarmac visual lies at z 0.01
PLANT_X_M, PLANT_Y_M, TARMAC_Z_M = (-15.0, 35.0), (-35.0, 15.0), 0.01


def test_vlp16_cloud_in_the_power_plant_lies_on_the_plant(ros: RosGraph, tmp_path: Path):
    points_file = tmp_path / "points.txt"
    proc = launch(ros, "rotors_gazebo", "mav_hovering_example_with_lidar.launch", "lockstep:=true", "real_time_factor:=0")
    try:
        wait_sim_time(ros, 1.0)
        result = ros.run_client(
            clients.laser_flight.vlp16_clouds, timeout=200, lidar_above_base_m=LIDAR_ABOVE_BASE_M, points_file=str(points_file)
        )
    finally:
        stop_launch(proc)
    # velodyne_pointcloud's PointXYZIRT: x y z float32, intensity float32 at 16, ring uint16 at 20, time at 24
    assert result["fields"] == [
        ["x", 0, 7, 1],
        ["y", 4, 7, 1],
        ["z", 8, 7, 1],
        ["intensity", 16, 7, 1],
        ["ring", 20, 4, 1],
        ["time", 24, 7, 1],
    ]
    assert result["point_step"] == 32 and result["frame"] == "firefly/velodyne_link"
    assert math.isclose(result["period"], 0.1, abs_tol=1e-6), result["period"]
    assert result["rings"] == list(range(16))
    lo, hi = result["time_span"]
    assert lo >= 0.0 and 0.09 < hi < 0.1  # each column's time within the 100 ms sweep
    # points on the tarmac beyond the octree's footprint have no cell to lie on: they lie on the tarmac
    points = np.loadtxt(points_file)
    assert len(points) > 5 * 10000
    beyond = (points[:, 0] < PLANT_X_M[0]) | (points[:, 0] > PLANT_X_M[1]) | (points[:, 1] < PLANT_Y_M[0]) | (points[:, 1] > PLANT_Y_M[1])
    on_tarmac = beyond & (np.abs(points[:, 2] - TARMAC_Z_M) < 0.03)
    print(f"{int(on_tarmac.sum())} points on the tarmac beyond the plant; {int((beyond & ~on_tarmac).sum())} " "elsewhere beyond it")
    assert not np.any(beyond & ~on_tarmac)
    np.savetxt(points_file, points[~beyond], fmt="%.5f")
    # the plant is spawned 0.25 m lower than its .bt (powerplant.world): move the points up by that
    out = ros.run(["rosrun", "rotors_core", "rotors_octomap_distance", str(PLANT), str(points_file), "0", "0", "0.25"])
    print(
        f"VLP-16 in the power plant, {result['points_per_cloud']} points per sweep; distance of 5 sweeps' points "
        f"to the nearest occupied OctoMap cell: {out.stdout.strip()}"
    )
    figures = dict(kv.rsplit(" ", 1) if kv.startswith("without") else kv.split(" ", 1) for kv in out.stdout.strip().split(", "))
    assert float(figures["p99"].split()[0]) < 0.03  # sensor noise 8 mm
    assert int(figures["without an occupied cell within 1.0 m"]) == 0


def test_rangefinder_reads_height_and_hokuyo_publishes_scans(ros: RosGraph):
    results = {}
    for lidar in ("rangefinder", "hokuyo"):
        proc = launch(
            ros,
            "rotors_gazebo",
            "mav_hovering_example_with_lidar.launch",
            "lockstep:=true",
            "real_time_factor:=0",
            "world_name:=basic",
            f"enable_lidar:={lidar}",
            name=lidar,
        )
        try:
            wait_sim_time(ros, 8.0)  # hovering at 1 m since 5 s
            results[lidar] = ros.run_client(clients.laser_flight.rangefinder_or_hokuyo)
        finally:
            stop_launch(proc)
    rf = results["rangefinder"]
    mean = sum(rf["ranges"]) / len(rf["ranges"])
    # the beam starts 5 cm below the base link and looks straight down at the ground (z = 0)
    print(f"rangefinder at base z = {rf['z']:.3f} m: mean range {mean:.4f} m over 20 readings (sigma 0.01 m)")
    assert abs(mean - (rf["z"] - 0.05)) < 0.01
    assert rf["limits"] == pytest.approx([0.06, 25.0, 1]) and math.isclose(rf["period"], 0.05, abs_tol=1e-6)
    hk = results["hokuyo"]
    angle_min, angle_max, increment, n, range_min, range_max, frame = hk["scan"]
    assert n == 1081 and math.isclose(angle_min, -0.75 * math.pi, rel_tol=1e-6)
    assert math.isclose(angle_min + (n - 1) * increment, angle_max, abs_tol=1e-5)
    assert (range_min, range_max) == pytest.approx((0.1, 30.0)) and frame == "firefly/hokuyo_link"
    assert math.isclose(hk["period"], 0.025, abs_tol=1e-6)
    # level at 1 m over an empty plane: no beam of a horizontal scan returns (REP 117: +inf)
    assert hk["finite"] == 0
