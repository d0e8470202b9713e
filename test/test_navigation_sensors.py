"""RotorS' GPS, magnetometer and barometer on the firefly (enable_navigation_sensors:=true): rates in
sim time, NavSatFix against the ground-truth position mapped to WGS84 by the textbook formulas
(within 1 cm), pressure against the standard atmosphere, the magnetic field in the body frame."""

import math
from pathlib import Path

import numpy as np
import pytest

import clients.navigation_sensors
from support import RosGraph, rate_from_stamps, stop_launch, wait_sim_time

A, F = 6378137.0, 1 / 298.257223563  # WGS84
E2 = F * (2 - F)
LAT0, LON0, H0 = 47.3667, 8.55, 500.0  # the basic world's spherical_coordinates


def ecef(lat_deg, lon_deg, h):
    phi, lam = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1 - E2 * math.sin(phi) ** 2)
    return np.array([(n + h) * math.cos(phi) * math.cos(lam), (n + h) * math.cos(phi) * math.sin(lam), (n * (1 - E2) + h) * math.sin(phi)])


def enu(lat_deg, lon_deg, h):
    """East, north, up of a WGS84 point from the world origin."""
    phi, lam = math.radians(LAT0), math.radians(LON0)
    east = [-math.sin(lam), math.cos(lam), 0]
    north = [-math.sin(phi) * math.cos(lam), -math.sin(phi) * math.sin(lam), math.cos(phi)]
    up = [math.cos(phi) * math.cos(lam), math.cos(phi) * math.sin(lam), math.sin(phi)]
    return np.array([east, north, up]) @ (ecef(lat_deg, lon_deg, h) - ecef(LAT0, LON0, H0))


def isa_pressure(h):
    h_gp = 6356766.0 * h / (6356766.0 + h)
    return 101325.0 * ((288.15 - 0.0065 * h_gp) / 288.15) ** (9.80665 * 28.9644 / (8314.32 * 0.0065))


def test_gps_magnetometer_barometer_on_the_firefly(ros: RosGraph, tmp_path: Path):
    # roslaunch's command line refuses values holding ':=', so the xacro arguments go in an include
    flight = tmp_path / "flight.launch"
    flight.write_text("""<launch><include file="$(find rotors_gazebo)/launch/mav_hovering_example.launch">
      <arg name="gui" value="false"/><arg name="lockstep" value="true"/><arg name="real_time_factor" value="2"/>
      <arg name="enable_navigation_sensors" value="true"/><arg name="random_seed" value="5"/>
      <arg name="xacro_args" value="gps_hor_pos_std_dev:=0 gps_ver_pos_std_dev:=0"/>
    </include></launch>""")
    proc = ros.start(["roslaunch", "-p", str(ros.port), str(flight)], "launch")
    try:
        wait_sim_time(ros, 8.0)
        got = ros.run_client(clients.navigation_sensors.fly_and_log, timeout=300)
    finally:
        stop_launch(proc)
    odom = np.array(got["odom"])
    t_odom = odom[:, 0]

    def truth_at(t):
        """The ground truth of that step (None if the client missed it)."""
        i = int(np.argmin(np.abs(t_odom - t)))
        return odom[i] if abs(t_odom[i] - t) < 1e-6 else None

    missed = {k: sum(truth_at(m[0]) is None for m in got[k]) for k in ("gps", "speed", "mag", "baro")}
    print(f"samples without a received ground truth of the same step: {missed}")
    assert all(missed[k] <= 0.1 * len(got[k]) for k in missed), missed
    for k in missed:
        got[k] = [m for m in got[k] if truth_at(m[0]) is not None]

    # rates in sim time
    for key, rate in (("gps", 5.0), ("speed", 5.0), ("mag", 100.0), ("baro", 100.0)):
        stamps = np.array([m[0] for m in got[key]])
        measured = rate_from_stamps(stamps)  # a sample set aside above does not count
        print(f"{key}: {len(stamps)} messages, {measured:.2f} Hz in sim time")
        assert abs(measured - rate) < 0.02 * rate, (key, measured)
    # GPS: the noise-free fix is the ground-truth position on WGS84
    errors, max_speed = [], 0.0
    for stamp, lat, lon, alt, status, service, frame in got["gps"]:
        assert (status, service, frame) == (0, 1, "firefly/gps_link")
        truth = truth_at(stamp)
        errors.append(np.linalg.norm(enu(lat, lon, alt) - truth[1:4]))
        q = truth[4:8]
        v_w = rotate(q, truth[8:11])
        max_speed = max(max_speed, np.linalg.norm(v_w))
    print(
        f"GPS against ground truth on WGS84: largest error {max(errors) * 1000:.2f} mm over {len(errors)} fixes "
        f"(up to {max_speed:.2f} m/s)"
    )
    assert max(errors) < 0.01
    # ground speed: world-frame velocity with sigma 0.1 m/s
    residuals = []
    for stamp, vx, vy, vz in got["speed"]:
        truth = truth_at(stamp)
        residuals.append(np.array([vx, vy, vz]) - rotate(truth[4:8], truth[8:11]))
    sigma = np.std(residuals, axis=0)
    print(f"ground speed noise sigma {sigma} (declared 0.1 m/s)")
    assert np.all((sigma > 0.05) & (sigma < 0.16))
    # barometer (no noise by default): the standard atmosphere at 500 m + z
    worst = max(abs(p - isa_pressure(500.0 + truth_at(t)[3])) for t, p in got["baro"])
    assert worst < 1e-6, worst
    # magnetometer: the ENU reference field rotated into the body, within the turn-on bias (uniform in
    # +-4e-7 T an axis) and 6 sigma of the white noise (8e-8 T): the largest of ~2,400 samples passes
    # 6 sigma with probability 1 - 5e-6
    m_w = np.array([8.15e-7, 2.1493e-5, -4.2795e-5])
    worst = max(np.max(np.abs(np.array(b) - rotate(truth_at(t)[4:8], m_w, inverse=True))) for t, *b in got["mag"])
    print(f"magnetometer: largest difference from R^T m_W {worst:.3g} T (bias within 4e-7, sigma 8e-8)")
    assert worst < 4e-7 + 6 * 8e-8


def rotate(q_xyzw, v, inverse=False):
    x, y, z, w = q_xyzw
    r = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )
    return (r.T if inverse else r) @ np.asarray(v)


def test_the_world_magnetic_model_field_at_the_worlds_origin():
    """With PX4's autopilot profile the magnetometer's reference field is the World Magnetic Model's at
    the world's <spherical_coordinates> (as PX4's Gazebo magnetometer), checked against pygeomag's WMM
    at Canberra, where RotorS' fixed Zurich field would be far off (another hemisphere)."""
    import datetime

    import numpy as np
    from pygeomag import GeoMag

    import rotors_sim as rs

    lat, lon, elevation = -35.363261, 149.165230, 584.0
    world = rs.World(
        sdf=f"""<?xml version="1.0"?><sdf version="1.6"><world name="canberra">
      <physics type="ode"><max_step_size>0.004</max_step_size><real_time_factor>0</real_time_factor></physics>
      <spherical_coordinates><surface_model>EARTH_WGS84</surface_model><latitude_deg>{lat}</latitude_deg>
      <longitude_deg>{lon}</longitude_deg><elevation>{elevation}</elevation><heading_deg>0</heading_deg>
      </spherical_coordinates>
      <include><uri>model://ground_plane</uri></include></world></sdf>"""
    )
    world.spawn_mav("iris", random_seed=3, enable_navigation_sensors=True, autopilot_profile="px4")
    readings = []
    for _ in range(400):
        world.step(1)
        m = world.message("/iris/magnetic_field")[0].magnetic_field
        readings.append([m.x, m.y, m.z])
    mean_B = np.mean(readings[100:], axis=0)  # FLU body, facing east and level: x east, y north, z up
    now = datetime.datetime.now(datetime.UTC)
    year = now.year + (now.timetuple().tm_yday - 1) / 365.25
    wmm = GeoMag().calculate(glat=lat, glon=lon, alt=elevation / 1000, time=year)
    expected_B = np.array([wmm.y, wmm.x, -wmm.z]) * 1e-9
    print(f"magnetometer at Canberra {mean_B * 1e9} nT, WMM {expected_B * 1e9} nT")
    # the profile's noise (4e-7 T per sample) averages out; RotorS' initial bias is within 4e-7 T per axis
    np.testing.assert_allclose(mean_B, expected_B, atol=5e-7)


def test_px4_profile_publishes_barometer_at_50_hz_and_magnetometer_at_100_hz():
    """PX4's iris has its barometer at 50 Hz and its magnetometer at 100 Hz (<pubRate> in
    iris.sdf.jinja); with autopilot_profile px4 so do ours, on PX4's 250 Hz steps: each sample at the
    first step at or after its time (the magnetometer's 8 and 12 ms apart in turn). RotorS' profile
    keeps every step; a negative pubRate is one line."""
    import rotors_sim as rs

    counts = {}
    for profile in ("px4", "rotors"):
        world = rs.World("basic", step_size=0.004)
        world.spawn_mav("iris", random_seed=3, enable_navigation_sensors=True, autopilot_profile=profile)
        stamps = {"air_pressure": [], "magnetic_field": []}
        for _ in range(500):  # 2 s
            world.step(1)
            for topic, seen in stamps.items():
                msg, _ = world.message(f"/iris/{topic}")
                t = msg.header.stamp.to_sec()
                if not seen or seen[-1] != t:
                    seen.append(t)
        counts[profile] = {topic: len(seen) for topic, seen in stamps.items()}
        if profile == "px4":
            for topic, period in (("air_pressure", 0.02), ("magnetic_field", 0.01)):
                t = np.array(stamps[topic])
                due = t[0] + period * np.arange(len(t))  # sample k due at t_0 + k / rate
                assert np.all(t >= due - 1e-9) and np.all(t - due < 0.004 - 1e-9), topic
    print(f"messages in 2 s at 250 Hz steps: {counts}")
    assert counts["px4"] == {"air_pressure": 100, "magnetic_field": 200}
    assert counts["rotors"] == {"air_pressure": 500, "magnetic_field": 500}
    from rotors_sim.world import run_xacro

    model = rs.paths.package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo"
    args = dict(mav_name="iris", namespace="iris", enable_navigation_sensors=True, autopilot_profile="px4")
    urdf = run_xacro(model, args).replace("<pubRate>50</pubRate>", "<pubRate>-5</pubRate>")
    with pytest.raises(rs.SimError, match=r"pubRate = -5.0+ Hz must be >= 0"):
        rs.World("basic").spawn(urdf, "iris")
