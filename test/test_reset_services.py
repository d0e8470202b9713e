"""Gazebo's reset services repeat a flight bit for bit over ROS, as World.reset() does from Python
(test_python_module.py): the firefly with a wind gust, GPS, magnetometer, barometer and seeded IMU
and odometry noise, flown by the Lee controller node in lockstep. After /gazebo/reset_simulation
every message of every /firefly topic repeats the first flight's byte for byte; after
/gazebo/reset_world (the time runs on) they repeat with their header stamps aside."""

from pathlib import Path

import clients.reset_services
from support import REPO, RosGraph, send_hover_pose, stop_launch

FLIGHT_S = 3.0
COMPARED_S = 2.5  # each flight stops at FLIGHT_S, give or take the steps a pause call takes to land

# the topics at their RotorS rates (Hz) that must be in both flights: each is compared over at
# least COMPARED_S of its messages
RATES_HZ = {
    "/firefly/imu": 100,
    "/firefly/gps": 5,
    "/firefly/magnetic_field": 100,
    "/firefly/air_pressure": 10,
    "/firefly/ground_speed": 5,
    "/firefly/odometry_sensor1/odometry": 100,
    "/firefly/command/motor_speed": 100,
    "/firefly/wind_speed": 100,
    "/firefly/external_force": 100,
    "/firefly/ground_truth/pose": 100,
    "/firefly/joint_states": 100,
}


def test_reset_simulation_and_world_repeat_flight_bit_for_bit(ros: RosGraph):
    proc = ros.start(["roslaunch", "-p", str(ros.port), str(REPO / "test/launch/reset_repeats.launch")], "launch")
    try:
        ready = ros.wait_for(lambda: "Successfully spawned" in Path(proc.log_path).read_text(), 60)
        assert ready, Path(proc.log_path).read_text()[-2000:]
        r = send_hover_pose(ros, then=clients.reset_services.record_and_reset, flight_s=FLIGHT_S)  # the set point, then the flights
    finally:
        stop_launch(proc)
    for name in ("simulation", "world"):
        compared = r[name]
        print(
            f"reset_{name}: {len(compared)} topics, {sum(n for n, _ in compared.values())} messages compared; "
            f"differing: {({t: f for t, (_, f) in compared.items() if f is not None}) or 'none'}"
        )
        for topic, rate_hz in RATES_HZ.items():
            assert compared.get(topic, [0])[0] >= rate_hz * COMPARED_S, (name, topic, compared.get(topic))
        assert {t: f for t, (_, f) in compared.items() if f is not None} == {}, name
    # the gust pushed the MAV in the first flight; after reset_world (from 3 s on) it is over
    assert r["gust"][0] > 1 and r["gust"][1] == 1
