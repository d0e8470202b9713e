"""rotors_sim, the engine from Python without ROS: the hovering example's offset, many worlds in
one process (different seeds differ, the same seed repeats), sensors and contacts, the controllers
from the vehicle yaml, and bad input as one clear exception with the world still working.
(Bit for bit against a lockstep ROS flight: test_lockstep_determinism.py.)"""

import io
import math

import numpy as np
import pytest

import rotors_sim as rs
from rotors_sim.examples import hovering_example
from rotors_sim.world import message_class


def test_python_hovering_example_hovers_at_ros_offset():
    # the ROS example settles 0.040 m above its set point (the Lee controller's steady state with
    # the yaml's rounded constants); the same libraries from Python give the same offset
    flight = hovering_example(random_seed=1, duration_s=15.0)
    settled = flight.position_W[flight.time_s > 10.0]
    offset = settled.mean(axis=0) - np.array([0.0, 0.0, 1.0])
    print(f"offset after settling: {offset.round(4)} m")
    assert abs(offset[2] - 0.040) < 0.002 and np.all(np.abs(offset[:2]) < 0.005)
    before = flight.position_W[flight.time_s < 4.9]
    assert before[:, 2].max() < 0.2  # on the ground until the waypoint is due at 5 s


def fly(seed: int, world: rs.World | None = None, duration_s: float = 6.0):
    return hovering_example(random_seed=seed, duration_s=duration_s, due_s=1.0, world=world)


def test_batch_of_16_seeded_worlds_flies_16_distinct_repeatable():
    batch = rs.Batch(lambda i: rs.World("basic"), 16)
    for i, world in enumerate(batch.worlds):
        world.spawn_mav("firefly", random_seed=100 + i, odometry_noise_position="0.01 0.01 0.01")
    lees = [rs.LeePositionController.for_mav("firefly") for _ in batch.worlds]
    for lee in lees:
        lee.set_point([0.0, 0.0, 1.0])
    seen = [0] * len(batch)
    imu = [[] for _ in batch.worlds]
    for _ in range(300):  # 3 s: every world steps in one call, on threads
        for i, world in enumerate(batch.worlds):
            odometry = world.odometry("firefly")
            if odometry is not None and odometry.count != seen[i]:
                seen[i] = odometry.count
                world.set_motor_speeds("firefly", lees[i].rotor_speeds(odometry))
        batch.step(1)
        for i, world in enumerate(batch.worlds):
            imu[i].append(world.message("/firefly/imu")[0].linear_acceleration.z)
    final = np.array([w.link_state("firefly")[0] for w in batch.worlds])
    print("positions after 3 s [mm]:", (final * 1000).round(1).tolist())
    assert np.all(np.abs(final[:, 2] - 1.0) < 0.2)  # all of them fly
    assert len({tuple(series) for series in imu}) == 16  # 16 seeds, 16 different IMU streams
    assert len({tuple(p) for p in final}) == 16  # and 16 different flights (the controller sees noisy odometry)
    # a world of the batch flown again alone with its seed: the same flight, bit for bit
    again = rs.World("basic")
    again.spawn_mav("firefly", random_seed=100 + 5, odometry_noise_position="0.01 0.01 0.01")
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0.0, 0.0, 1.0])
    seen_again, imu_again = 0, []
    for _ in range(300):
        odometry = again.odometry("firefly")
        if odometry is not None and odometry.count != seen_again:
            seen_again = odometry.count
            again.set_motor_speeds("firefly", lee.rotor_speeds(odometry))
        again.step()
        imu_again.append(again.message("/firefly/imu")[0].linear_acceleration.z)
    assert imu_again == imu[5]
    assert np.array_equal(again.link_state("firefly")[0], final[5])


WIND_GUST_MODEL = rs.paths.package_path("rotors_description") / "urdf" / "mav_with_wind_gust.gazebo"


def fly_recording_everything(world: rs.World, seconds: float = 3.0) -> dict[str, list[bytes]]:
    """The hovering example's flight with a fresh Lee controller in a Python loop (set point
    (0, 0, 1) due 0.5 s after the start): every message of every topic, serialized, by topic."""
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0.0, 0.0, 1.0], due=world.time + 0.5)
    seen, last_odometry, log = {}, 0, {}
    for _ in range(int(round(seconds / world.step_size))):
        odometry = world.odometry("firefly")
        if odometry is not None and odometry.count != last_odometry:
            last_odometry = odometry.count
            world.set_motor_speeds("firefly", lee.rotor_speeds(odometry))
        world.step()
        for topic, _, count in world.topics():
            got = world.engine.message(topic)  # None after a reset until the topic's first message
            if got is not None and count != seen.get(topic, 0):
                seen[topic] = count
                log.setdefault(topic, []).append(bytes(got[2]))
    return log


def first_differences(a: dict, b: dict, canonical=lambda topic, data: data) -> dict[str, str]:
    """Per topic whose messages differ: where (message count, or the first index that differs)."""
    out = {}
    for topic in sorted(set(a) | set(b)):
        x, y = a.get(topic, []), b.get(topic, [])
        if len(x) != len(y):
            out[topic] = f"{len(x)} against {len(y)} messages"
            continue
        first = next((i for i in range(len(x)) if canonical(topic, x[i]) != canonical(topic, y[i])), None)
        if first is not None:
            out[topic] = f"message {first} of {len(x)}"
    return out


def spawn_windy_firefly(world: rs.World, gust_start_s: float) -> None:
    """The firefly with a 3 N gust and every noisy sensor seeded: IMU, odometry noise, GPS,
    magnetometer (a random initial bias), pressure."""
    world.spawn_mav(
        "firefly",
        model=WIND_GUST_MODEL,
        random_seed=7,
        enable_navigation_sensors=True,
        wind_gust_start=gust_start_s,
        wind_gust_duration=1.0,
        wind_gust_force_mean=3.0,
        odometry_noise_position="0.01 0.01 0.01",
        odometry_noise_attitude="0.02 0.02 0.02",
    )


def test_reset_repeats_flight_bit_for_bit_with_wind_and_nav():
    """World.reset() (Gazebo's reset_simulation, also the server's /gazebo/reset_simulation): every
    message of every topic of a second flight is byte for byte the first one's."""
    world = rs.World("basic")
    spawn_windy_firefly(world, gust_start_s=1.0)  # the gust inside each flight
    first = fly_recording_everything(world)
    world.reset()
    assert world.time == 0.0
    second = fly_recording_everything(world)
    counts = {t: len(m) for t, m in first.items()}
    print(f"{len(first)} topics, {sum(counts.values())} messages; differing after reset: " f"{first_differences(first, second) or 'none'}")
    for topic in (
        "/firefly/imu",
        "/firefly/gps",
        "/firefly/magnetic_field",
        "/firefly/air_pressure",
        "/firefly/odometry_sensor1/odometry",
        "/firefly/ground_speed",
        "/firefly/wind_speed",
        "/firefly/external_force",
    ):
        assert counts.get(topic, 0) > 0, topic
    assert first_differences(first, second) == {}
    # the gust pushed the MAV: the flights are not a trivial hover
    assert first["/firefly/external_force"] != [first["/firefly/external_force"][0]] * counts["/firefly/external_force"]


def test_quick_solver_flight_repeats_whatever_other_worlds_drew_and_after_reset():
    """ODE's quick stepper (the warehouse's solver) reorders constraint rows with ODE's one
    process-wide random generator; each world keeps its own state of it. A flight that starts with
    0.5 s on its legs (ground contacts: rows to reorder) is byte for byte the same in a new world
    after another world drew from the generator, and in the first world after its reset."""
    first_world = rs.World("warehouse")
    first_world.spawn_mav("firefly", random_seed=3)
    first = fly_recording_everything(first_world)
    other = rs.World("warehouse")
    other.spawn_mav("firefly", random_seed=5)
    other.step(777)  # resting on its legs: the quick stepper draws
    second_world = rs.World("warehouse")
    second_world.spawn_mav("firefly", random_seed=3)
    second = fly_recording_everything(second_world)
    first_world.reset()
    third = fly_recording_everything(first_world)
    assert first["/firefly/odometry_sensor1/odometry"][-1] != first["/firefly/odometry_sensor1/odometry"][0]  # it flew
    assert first_differences(first, second) == {}
    assert first_differences(first, third) == {}


def test_reset_world_repeats_the_flight_with_the_time_running_on():
    """World.reset_world() (Gazebo's reset_world, also the server's /gazebo/reset_world): the time runs
    on, so the messages are compared with their stamps set to 0; the gust, due at 40 s, stays out."""
    import genpy

    world = rs.World("basic")
    spawn_windy_firefly(world, gust_start_s=40.0)
    first = fly_recording_everything(world)
    world.reset_world()
    assert world.time == pytest.approx(3.0)
    second = fly_recording_everything(world)
    types = {topic: kind for topic, kind, _ in world.topics()}

    def unstamped(topic: str, data: bytes) -> bytes:
        msg = message_class(types[topic])().deserialize(data)
        if hasattr(msg, "header"):
            msg.header.stamp = genpy.Time(0)
        buffer = io.BytesIO()
        msg.serialize(buffer)
        return buffer.getvalue()

    print(f"{len(first)} topics; differing after reset_world (stamps aside): " f"{first_differences(first, second, unstamped) or 'none'}")
    assert first_differences(first, second, unstamped) == {}


def test_set_model_state_moves_the_vehicle():
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=3)
    world.set_model_state("firefly", [2.0, -1.0, 3.0], [0, 0, math.sin(0.25), math.cos(0.25)], velocity=[1, 0, 0])
    world.step()
    p, q, v, _ = world.link_state("firefly")
    assert abs(p[0] - 2.01) < 1e-3 and abs(p[2] - 3.0) < 1e-3 and abs(v[0] - 1.0) < 1e-3
    assert abs(2 * math.atan2(q[2], q[3]) - 0.5) < 1e-9


def test_sensors_messages_and_contacts():
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=9, enable_navigation_sensors=True)
    world.step(200)  # 2 s on the ground, motors off
    topics = {t: kind for t, kind, _ in world.topics()}
    for topic, kind in {
        "/firefly/imu": "sensor_msgs/Imu",
        "/firefly/odometry_sensor1/odometry": "nav_msgs/Odometry",
        "/firefly/gps": "sensor_msgs/NavSatFix",
        "/firefly/magnetic_field": "sensor_msgs/MagneticField",
        "/firefly/air_pressure": "sensor_msgs/FluidPressure",
    }.items():
        assert topics.get(topic) == kind, (topic, topics.get(topic))
    imu, count = world.message("/firefly/imu")
    assert count == 200 and abs(imu.linear_acceleration.z - 9.8) < 0.5  # at rest: the specific force is -g
    # the same reading from the vehicle bus, without a message
    reading = world.imu("firefly")
    assert reading.count == 200 and reading.time_s == imu.header.stamp.to_sec()
    assert reading.linear_acceleration.tolist() == [imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z]
    assert reading.angular_velocity.tolist() == [imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z]
    gps, _ = world.message("/firefly/gps")
    assert abs(gps.latitude - 47.3667) < 0.01  # basic.world's spherical coordinates (Zurich)
    contacts = world.contacts()
    assert any("firefly::" in c["collision1"] + c["collision2"] for c in contacts)  # standing on the ground
    assert world.in_contact("firefly")
    world.set_model_state("firefly", [0.0, 0.0, 5.0])
    world.step()
    assert not world.in_contact("firefly")
    assert world.rotor_speeds("firefly").shape == (6,)


def test_a_depth_camera_and_a_lidar_read_as_numpy_arrays():
    world = rs.World("basic")
    model = rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo"
    world.spawn_mav("firefly", model=model, random_seed=2, enable_vi_depth=True, enable_lidar="vlp16")
    world.step(20)
    scan = world.laser_scan("firefly", "velodyne")
    ranges = scan["ranges_m"]
    assert ranges.shape == (16, 1800) and scan["scan_count"] >= 1 and not ranges.flags.owndata
    # the lowest beam (-15 deg) meets the ground: range * sin(15 deg) is the lidar's height
    heights = ranges[0][np.isfinite(ranges[0])] * math.sin(math.radians(15.0))
    p_W = world.link_state("firefly")[0]
    print(f"lidar height from its lowest beam: {np.median(heights):.3f} m (base link at {p_W[2]:.3f} m)")
    assert len(heights) > 1000 and abs(np.median(heights) - (p_W[2] + 0.15)) < 0.03  # lidar_xyz 0 0 0.15
    depth = world.camera_depth("firefly", "firefly/vi_sensor_camera_depth")
    image = world.camera_image("firefly", "firefly/vi_sensor_camera_depth")
    left = world.camera_image("firefly", "firefly_vi_sensor_stereo_camera", 0)
    right = world.camera_image("firefly", "firefly_vi_sensor_stereo_camera", 1)
    assert depth.dtype == np.float32 and depth.ndim == 2 and image.shape[:2] == depth.shape
    assert left.shape == right.shape == (480, 752, 1) and not left.flags.owndata  # views of the engine's buffers
    assert np.isfinite(depth).mean() > 0.3  # the ground ahead
    with pytest.raises(rs.SimError, match="camera index 2 out of range"):
        world.camera_image("firefly", "firefly_vi_sensor_stereo_camera", 2)


def test_controllers_read_vehicle_yaml_name_missing_param(tmp_path):
    lee = rs.LeePositionController.for_mav("firefly")
    assert len(lee.vehicle["rotors"]) == 6 and abs(lee.vehicle["mass_kg"] - 1.56779) < 1e-9
    attitude = rs.AttitudeLevelController.for_mav("hummingbird")
    assert len(attitude.vehicle["rotors"]) == 4
    broken = tmp_path / "firefly_no_mass.yaml"
    text = (rs.paths.resource("firefly.yaml")).read_text().replace("mass: 1.56779", "")
    broken.write_text(text)
    with pytest.raises(rs.SimError, match="missing parameter mass"):
        rs.LeePositionController(rs.paths.resource("lee_controller_firefly.yaml"), broken)
    with pytest.warns(UserWarning, match="unknown parameter.*positon_gain"):
        typo = tmp_path / "typo.yaml"
        typo.write_text("positon_gain: {x: 1, y: 1, z: 1}\n")
        rs.LeePositionController(rs.paths.resource("lee_controller_firefly.yaml"), rs.paths.resource("firefly.yaml"), typo)


BOX = """<?xml version="1.0"?><sdf version="1.6"><model name="b"><static>true</static><link name="l">
  <collision name="c"><geometry><box><size>{}</size></box></geometry></collision></link></model></sdf>"""
SPHERE = """<?xml version="1.0"?><sdf version="1.6"><model name="s"><link name="l">
  <collision name="c"><geometry><sphere><radius>{}</radius></sphere></geometry></collision></link></model></sdf>"""


@pytest.mark.parametrize(
    "bad, match",
    [
        (lambda w: w.spawn_mav("fireflyy"), "unknown vehicle mav_name 'fireflyy'"),
        (lambda w: w.set_motor_speeds("firefly", [500.0] * 4), "has 4 angular_velocities, the vehicle has 6 motors"),
        (lambda w: w.set_motor_speeds("firefly", [float("nan")] * 6), r"angular_velocities\[0\] = nan"),
        (lambda w: w.set_motor_speeds("nobody", [1.0] * 6), "no vehicle with motor models in namespace 'nobody'"),
        (lambda w: w.link_state("nobody"), "no model 'nobody' in the world"),
        (lambda w: w.message("/firefly/imuu"), "no plugin publishes '/firefly/imuu'"),
        (
            lambda w: w.imu("firefly", "imuu"),
            r"no IMU publishes '/firefly/imuu' in vehicle 'firefly' \(its IMUs: /firefly/ground_truth/imu, /firefly/imu\)",
        ),
        (lambda w: w.odometry("firefly", "odom"), "no odometry sensor publishes '/firefly/odom'"),
        (lambda w: w.set_model_state("firefly", [0, 0, float("inf")]), "position must be finite"),
        (lambda w: w.step(-1), "must be >= 0"),
        (lambda w: w.laser_scan("firefly", "imu"), "has no sensor 'imu'"),
        (lambda w: rs.World("nowhere"), "unknown world 'nowhere'"),
        (lambda w: w.spawn("<robot name='x'><link name='a'></robot>", "x"), "model 'x': the description does not parse"),
        (lambda w: w.spawn(BOX.format("1 0 1"), "b"), r"box <size> y 0\.000000 must be finite and > 0"),
        (lambda w: w.spawn(BOX.format("1 nan 1"), "b"), r"does not parse: Error reading element <size>"),  # sdformat
        (lambda w: w.spawn(SPHERE.format("-0.5"), "s"), r"sphere <radius> -0\.500000 must be finite and > 0"),
    ],
)
def test_bad_input_is_one_exception_and_world_keeps_working(bad, match):
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=4)
    world.set_motor_speeds("firefly", [100.0] * 6)
    world.step(10)
    with pytest.raises(rs.SimError, match=match):
        bad(world)
    t = world.time
    world.step(10)
    assert abs(world.time - t - 0.1) < 1e-9 and world.odometry("firefly").count >= 20
    assert world.rotor_speeds("firefly")[0] > 50.0  # the last valid command stays in force


@pytest.mark.parametrize(
    "call, match",
    [
        (
            lambda c: c.set_point([0.3, 0.2, 1.0, 0.5]),
            r"set_point: position: 4 values in shape \(4,\); give 3 \(x, y, z \[m\]; the yaw is its own argument\)",
        ),
        (lambda c: c.set_point([0, 0, 1], velocity=[1, 2]), r"set_point: velocity: 2 values in shape \(2,\); give 3"),
        (lambda c: c.set_point("up"), "set_point: position: 'up' is not numbers; give 3 values"),
    ],
)
def test_a_set_point_of_the_wrong_length_is_one_error_and_the_last_stays(call, match):
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=4)
    lee = rs.LeePositionController.for_mav("firefly")
    world.attach_controller("firefly", lee)
    lee.set_point([0.0, 0.0, 1.0])
    world.step(300)
    with pytest.raises(rs.SimError, match=match):
        call(lee)
    world.step(300)
    assert world.odometry("firefly").position_W[2] > 0.5  # still climbing to the last valid set point


def test_engine_controller_flies_python_loop_flight_bit_for_bit():
    loop = hovering_example(random_seed=5, duration_s=8.0)
    attached = hovering_example(random_seed=5, duration_s=8.0, attached=True)
    assert np.array_equal(loop.position_W, attached.position_W)
    assert abs(attached.position_W[-1][2] - 1.04) < 0.03


def test_listen_keeps_only_the_topics_asked_for():
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=1)
    world.listen(["/firefly/odometry_sensor1/odometry"])
    world.step(5)
    counts = {topic: count for topic, _, count in world.topics()}
    assert counts["/firefly/odometry_sensor1/odometry"] == 5 and counts["/firefly/imu"] == 0
    assert world.imu("firefly").count == 5  # the vehicle bus carries every reading all the same
    world.listen()
    world.step(5)
    assert world.message("/firefly/imu")[1] == 5


def test_sdf_model_spawns_from_text_and_falls_as_a_body():
    sdf = """<?xml version="1.0"?><sdf version="1.6"><model name="crate"><link name="body">
      <inertial><mass>2.0</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
      <collision name="c"><geometry><box><size>0.4 0.4 0.4</size></box></geometry></collision>
      </link></model></sdf>"""
    world = rs.World("basic")
    assert world.spawn(sdf, "crate", xyz=(0.0, 0.0, 10.0)) == "crate"
    n, dt, g = 50, world.step_size, 9.8
    world.step(n)  # free fall from rest, ODE's semi-implicit Euler: z_n = z_0 - g dt^2 n (n + 1) / 2
    z = world.link_state("crate")[0][2]
    assert abs(z - (10.0 - g * dt**2 * n * (n + 1) / 2)) < 1e-9
    assert abs(z - (10.0 - g * (n * dt) ** 2 / 2)) < g * dt * n * dt  # the continuous fall, within one step's error


def test_set_model_state_moves_static_model_and_its_collision():
    """A static 1 m table moved from x 5 to the origin: its pose follows, and a crate dropped on the
    origin comes to rest on its top (z 1.2) instead of the ground; reset puts the table back."""
    table = """<?xml version="1.0"?><sdf version="1.6"><model name="table"><static>true</static><link name="top">
      <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
      <visual name="v"><geometry><box><size>1 1 1</size></box></geometry></visual></link></model></sdf>"""
    crate = """<?xml version="1.0"?><sdf version="1.6"><model name="crate"><link name="body">
      <inertial><mass>2.0</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
      <collision name="c"><geometry><box><size>0.4 0.4 0.4</size></box></geometry></collision>
      </link></model></sdf>"""
    world = rs.World("basic")
    world.spawn(table, "table", xyz=(5.0, 0.0, 0.5))
    world.set_model_state("table", [0.0, 0.0, 0.5], [0.0, 0.0, math.sin(0.3), math.cos(0.3)])
    position, orientation = world.link_state("table")[:2]
    assert np.allclose(position, [0.0, 0.0, 0.5]) and np.allclose(orientation, [0.0, 0.0, math.sin(0.3), math.cos(0.3)])
    world.spawn(crate, "crate", xyz=(0.0, 0.0, 2.0))
    world.step(int(2.0 / world.step_size))
    assert abs(world.link_state("crate")[0][2] - 1.2) < 0.01  # on the table's top, not on the ground (0.2)
    world.reset()
    assert np.allclose(world.link_state("table")[0], [5.0, 0.0, 0.5])


def test_world_given_twice_to_step_all_or_batch_is_one_error():
    """step_all steps each world on a thread: a world given twice would be stepped by two threads at
    once. It is refused, naming the two positions, and nothing is stepped."""
    world = rs.World("basic")
    other = rs.World("basic")
    with pytest.raises(rs.SimError, match=r"worlds\[0\] and worlds\[2\] are the same world"):
        rs.step_all([world.engine, other.engine, world.engine], 10)
    assert world.time == 0.0 and other.time == 0.0
    batch = rs.Batch(lambda i: world, 2)
    with pytest.raises(rs.SimError, match="are the same world"):
        batch.step(1)
    rs.step_all([world.engine, other.engine], 10)
    assert world.time == pytest.approx(0.1) and other.time == pytest.approx(0.1)


def test_camera_messages_are_kept_only_when_named():
    """A camera's image_raw and camera_info are listed with their types from the start, but kept
    (and the image built) only once World.listen names them; listen() with no topics keeps every
    other topic again, not them."""
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=3, model=rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo")
    image = "/firefly/vi_sensor/left/image_raw"
    world.step(20)
    kinds = {t: kind for t, kind, _ in world.topics()}
    assert kinds[image] == "sensor_msgs/Image" and kinds["/firefly/vi_sensor/left/camera_info"] == "sensor_msgs/CameraInfo"
    assert world.message(image) is None and world.message("/firefly/imu") is not None
    world.listen([image, "/firefly/imu"])
    world.step(10)
    msg, count = world.message(image)
    assert (msg.width, msg.height, msg.encoding, count) == (752, 480, "mono8", 3)  # 30 Hz: 3 frames in 0.1 s
    world.listen()
    world.step(10)
    assert world.message(image)[1] == 3 and world.message("/firefly/odometry_sensor1/odometry") is not None
