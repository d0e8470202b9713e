"""RotorS on ROS 2 (the ros2 tier: make test-ros2): the ROS 2 front end (rotors_gazebo_compat/
rotors_ros2/rotors_ros2_sim.py) in a network namespace with only the loopback interface, and a client written with
rclpy (PyPI's Jazzy wheels) that finds it with ROS 2's own graph queries, receives odometry and IMU at
their rates, stamped on sim time and framed as on ROS 1, flies the hovering example's set point and
resets the simulation."""

import json
import subprocess

import pytest

from support import REPO

pytestmark = pytest.mark.ros2


def on_loopback_graph(script: str, timeout_s: float) -> subprocess.CompletedProcess:
    """`script` (bash) in a network namespace of its own with only the loopback interface up
    (unshare --net), in scripts/ros2_env.bash's environment: nothing of the graph reaches the
    machine's network, whatever the DDS settings."""
    probe = subprocess.run(["unshare", "--net", "true"], capture_output=True, text=True)
    assert probe.returncode == 0, f"unshare --net is not permitted here: {probe.stderr.strip()}"
    body = f"set -e; ip link set lo up; source {REPO}/scripts/ros2_env.bash; {script}"
    return subprocess.run(["unshare", "--net", "bash", "-c", body], capture_output=True, text=True, timeout=timeout_s)


def simulator_and_client(tmp_path, sim_args: str, client: str, timeout_s: float) -> dict:
    """rotors_ros2_sim.py `sim_args` and the rclpy client command `client` on a loopback graph; the
    client's RESULT=<json>. The simulator gets 10 s to stop after SIGINT, then SIGKILL, within
    `timeout_s`."""
    sim_log = tmp_path / "sim.log"
    res = on_loopback_graph(
        f"python {REPO}/rotors_gazebo_compat/rotors_ros2/rotors_ros2_sim.py {sim_args} > {sim_log} 2>&1 & sim=$!; "
        f"status=0; {client} || status=$?; "
        "kill -INT $sim; for _ in $(seq 100); do kill -0 $sim 2>/dev/null || break; sleep 0.1; done; "
        "kill -KILL $sim 2>/dev/null || true; exit $status",
        timeout_s=timeout_s,
    )
    lines = [line for line in res.stdout.splitlines() if line.startswith("RESULT=")]
    assert lines, f"the rclpy client failed ({res.returncode}):\n{res.stdout[-3000:]}\n{res.stderr[-3000:]}\n{sim_log.read_text()[-3000:]}"
    return json.loads(lines[0][len("RESULT=") :])


def test_an_rclpy_client_flies_the_hovering_example_on_ros2(tmp_path):
    assert (REPO / "build" / "ros2-venv" / "bin" / "python").exists(), "no build/ros2-venv: run make ros2-setup"
    # the client's waits share a budget of 240 s, the simulator's stop 10 s: both within the 300 s
    r = simulator_and_client(tmp_path, "--mav firefly --seed 3", f"python {REPO}/test/ros2_clients/hover_client.py 240", 300)
    print(json.dumps(r, indent=1))
    assert "gazebo" in r["nodes"]
    assert r["topics"]["/firefly/odometry_sensor1/odometry"] == ["nav_msgs/msg/Odometry"]
    assert r["topics"]["/firefly/imu"] == ["sensor_msgs/msg/Imu"]
    assert r["topics"]["/clock"] == ["rosgraph_msgs/msg/Clock"]
    assert {"/reset_simulation", "/reset_world", "/pause_physics", "/unpause_physics", "/spawn_entity", "/delete_entity"} <= set(
        r["services"]
    )
    # basic.world steps at 100 Hz and the hovering example's odometry and IMU publish every step
    assert r["odometry_hz"] == pytest.approx(100.0, rel=1e-6) and r["imu_hz"] == pytest.approx(100.0, rel=1e-6)
    assert r["odometry_gaps"] == 0 and r["imu_gaps"] == 0  # none lost on the way
    assert r["odometry_frames"] == ["world", "firefly/odometry_sensor1"] and r["imu_frame"] == "firefly/imu_link"
    assert abs(r["imu_z_at_rest"] - 9.8) < 0.5  # on the ground: the specific force is -g
    assert abs(r["sim_time_now_minus_clock"]) < 0.1  # the client's clock follows /clock (use_sim_time)
    # hovering at (0, 0, 1) 0.040 m high, as on ROS 1 (test_python_hovering_example_hovers_at_ros_offset)
    assert abs(r["z_offset_last_2_s"] - 0.040) < 0.005, r
    assert r["clock_after_reset"] < 1.0 and r["z_after_reset"] < 0.2


def test_the_hovering_example_on_ros2_records_a_ros2_bag_that_hovering_eval_scores_as_on_ros1(tmp_path):
    """mav_hovering_example.py (the launch file's arguments) with enable_logging:=true flies the
    firefly on the loopback graph and records a ROS 2 bag (MCAP) of what the ROS 1 bag plugin
    records for the evaluation; RotorS' hovering_eval.py scores it 0.040 m, as the ROS 1 demo."""
    assert (REPO / "build" / "ros2-venv" / "bin" / "python").exists(), "no build/ros2-venv: run make ros2-setup"
    res = on_loopback_graph(
        f"export ROS_HOME={tmp_path}; python {REPO}/rotors_gazebo_compat/rotors_ros2/mav_hovering_example.py "
        "enable_logging:=true real_time_factor:=0 sim_seconds:=22",
        timeout_s=240,
    )
    assert res.returncode == 0, f"{res.stdout[-3000:]}\n{res.stderr[-3000:]}"
    bags = [p for p in tmp_path.iterdir() if p.name.startswith("firefly_") and (p / "metadata.yaml").is_file()]
    assert len(bags) == 1, f"{sorted(p.name for p in tmp_path.iterdir())}\n{res.stdout[-2000:]}"
    import yaml
    from rosbags.rosbag2 import Reader

    with Reader(bags[0]) as reader:
        counts = {c.topic: (c.msgtype, c.msgcount) for c in reader.connections}
    storage = yaml.safe_load((bags[0] / "metadata.yaml").read_text())["rosbag2_bagfile_information"]["storage_identifier"]
    print(bags[0].name, storage, counts)
    assert storage == "mcap"
    assert counts["/firefly/ground_truth/odometry"][0] == "nav_msgs/msg/Odometry"
    assert counts["/firefly/command/trajectory"] == ("trajectory_msgs/msg/MultiDOFJointTrajectory", 1)
    # every reading from the first step on, none lost: 100 Hz, at least the 22 s flown
    from rosbags.typesys import Stores, get_typestore

    typestore = get_typestore(Stores.ROS2_JAZZY)
    with Reader(bags[0]) as reader:
        for topic in ("/firefly/ground_truth/odometry", "/firefly/imu"):
            stamps = []
            for conn, _, raw in reader.messages(connections=[c for c in reader.connections if c.topic == topic]):
                stamp = typestore.deserialize_cdr(raw, conn.msgtype).header.stamp
                stamps.append(stamp.sec + stamp.nanosec * 1e-9)
            gaps = [round(b - a, 4) for a, b in zip(stamps, stamps[1:]) if abs(b - a - 0.01) > 1e-6]
            assert stamps[0] == pytest.approx(0.01) and stamps[-1] >= 22.0 and not gaps, (topic, stamps[0], stamps[-1], gaps[:5])
    ev = subprocess.run(
        [
            str(REPO / "build" / "venv" / "bin" / "python"),
            str(REPO / "rotors_gazebo_compat" / "rotors_evaluation" / "scripts" / "hovering_eval.py"),
            "-b",
            str(bags[0]),
            "--mav_name",
            "firefly",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    print(ev.stdout)
    assert ev.returncode == 0, ev.stderr
    assert "[Waypoint 0]: [0.000, 0.000, 1.000, 0.000] at time 5.000 s" in ev.stdout
    assert "Position RMS error: 0.040 m" in ev.stdout


def test_the_vi_sensors_stereo_pair_reaches_rclpy_with_the_pixels_of_ros1(tmp_path):
    """The ROS 2 front end with the VI-sensor model (--model mav_with_vi_sensor): an rclpy client
    receives both cameras' images and camera_info at the VI-sensor's 30 Hz (RotorS' frame_rate; in
    basic.world's 10 ms steps the frames come 3, 3 and 4 steps apart) of their own stamps, none lost,
    with the ROS 1 plugins' frames, encoding and intrinsics; the left image at 1 s equals, pixel for
    pixel, rotors_sim's image of the same step, which test_python_ros_images shows equal
    to the ROS 1 topic's."""
    assert (REPO / "build" / "ros2-venv" / "bin" / "python").exists(), "no build/ros2-venv: run make ros2-setup"
    raw = tmp_path / "left.raw"
    r = simulator_and_client(
        tmp_path,
        "--mav firefly --seed 3 --model mav_with_vi_sensor",
        f"python {REPO}/test/ros2_clients/camera_client.py 4.0 1.0 {raw} 200",
        260,
    )
    for name in ("left/image_raw", "left/camera_info", "right/image_raw", "right/camera_info"):
        got = r[name]
        print(f"{name}: {got['count']} messages, {got['hz']:.2f} Hz of their stamps, {got['gaps']} gaps, first {got['first'][:2]}")
    for side in ("left", "right"):
        image, info = r[f"{side}/image_raw"], r[f"{side}/camera_info"]
        assert image["hz"] == pytest.approx(30.0, rel=0.05) and info["hz"] == pytest.approx(30.0, rel=0.05), (side, image, info)
        assert image["gaps"] == 0 and info["gaps"] == 0
        frame, encoding, width, height, step = image["first"]
        assert frame == f"firefly/vi_sensor/camera_{side}_optical_link" and (encoding, width, height, step) == ("mono8", 752, 480, 752)
        assert info["first"][0] == frame and info["first"][3] == "plumb_bob"
    # the right camera's projection carries the stereo baseline (P[3] = -f b), the left's none
    assert r["left/camera_info"]["first"][2][3] == 0.0 and r["right/camera_info"]["first"][2][3] < 0.0

    import numpy as np

    import rotors_sim as rs

    kept = r["kept"]
    theirs = np.frombuffer(raw.read_bytes(), np.uint8).reshape(kept["height"], kept["width"], -1)
    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=3, model=rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo")
    world.step(int(round(kept["stamp"] / world.step_size)))
    ours = world.camera_image("firefly", "firefly_vi_sensor_stereo_camera", 0)
    assert abs(world.time - kept["stamp"]) < 1e-9 and ours.shape == theirs.shape
    assert np.array_equal(ours, theirs) and theirs.std() > 5  # the same picture, and a real one


def test_mav_msgs_on_ros2_motor_commands_and_roll_pitch_yawrate_thrust(tmp_path):
    """RotorS' mav_msgs built for ROS 2 (make ros2-setup): motor_speed is published as
    mav_msgs/msg/Actuators with the signed rotor speeds, command/motor_speed drives the motors
    (--controller none) and a NaN or short command is refused, and the roll-pitch-yawrate-thrust
    controller (--controller roll_pitch_yawrate_thrust) flies command/roll_pitch_yawrate_thrust."""
    client = f"python {REPO}/test/ros2_clients/command_client.py"
    r = simulator_and_client(tmp_path, "--mav firefly --seed 3 --controller none", f"{client} none 120", 150)
    print(json.dumps(r))
    assert r["types"] == {"/firefly/motor_speed": ["mav_msgs/msg/Actuators"], "/firefly/command/motor_speed": ["mav_msgs/msg/Actuators"]}
    assert r["motor_speed_frame"] == "firefly/base_link"
    # the firefly's rotors alternate their turning direction; 2 s is many motor time constants
    assert r["speeds_at_600"] == pytest.approx([600.0, -600.0, 600.0, -600.0, 600.0, -600.0], rel=1e-3)
    assert r["z_at_600"] > r["z_start"] + 0.5  # 600 rad/s is above hover (about 543): it climbs
    assert r["speeds_after_bad"] == pytest.approx(r["speeds_at_600"], rel=1e-6)
    assert max(abs(w) for w in r["speeds_at_0"]) < 30.0
    log = (tmp_path / "sim.log").read_text()
    assert "angular_velocities[0] = nan must be a finite speed" in log and "has 3 angular_velocities, the vehicle has 6" in log, log[-2000:]
    r = simulator_and_client(tmp_path, "--mav firefly --seed 3 --controller roll_pitch_yawrate_thrust", f"{client} rpyt 120", 150)
    print(json.dumps(r))
    assert r["types"]["/firefly/command/roll_pitch_yawrate_thrust"] == ["mav_msgs/msg/RollPitchYawrateThrust"]
    assert r["roll_after_1_s"] == pytest.approx(0.1, abs=0.02)
    assert r["z_after_1_5_s"] > r["z_start"] + 0.1


def received_as_on_ros1(tmp_path, topics: dict, xacro: dict) -> dict:
    """The simulator with the vehicle's xacro arguments `xacro`, an rclpy client of `topics` (topic ->
    ROS 2 type), and each topic's first message from 1 s on compared, field for field, with the ROS 1
    plugin's message of the same step in rotors_sim (the same seed). The client's result."""
    wanted = " ".join(f"{t}={kind}" for t, kind in topics.items())
    args = " ".join(f"{k}:={v}" for k, v in xacro.items())
    r = simulator_and_client(
        tmp_path, f"--mav firefly --seed 3 {args}", f"python {REPO}/test/ros2_clients/sensors_client.py 1.0 120 {wanted}", 150
    )
    assert r["types"] == {t: [kind] for t, kind in topics.items()}

    import rotors_sim as rs

    world = rs.World("basic")
    world.spawn_mav("firefly", random_seed=3, **xacro)
    world.attach_controller("firefly", rs.LeePositionController.for_mav("firefly"))
    world.listen([t for t, _, _ in world.topics()])  # every message kept, as the simulator does

    def ros1_fields(m) -> object:
        if hasattr(m, "secs"):  # genpy's time: builtin_interfaces/Time on ROS 2
            return {"sec": m.secs, "nanosec": m.nsecs}
        if hasattr(m, "__slots__"):
            return {name.lower(): ros1_fields(getattr(m, name)) for name in m.__slots__ if name != "seq"}
        if isinstance(m, (list, tuple, bytes)):
            return [ros1_fields(v) for v in m]
        return m

    # each topic's ROS 1 message of the step its kept message is stamped with (the GPS runs at 5 Hz;
    # a topic is sent from its subscriber's discovery on, which takes its time)
    stamps = [m["header"]["stamp"]["sec"] + m["header"]["stamp"]["nanosec"] * 1e-9 for m in r["kept"].values()]
    compared = set()
    while len(compared) < len(topics) and world.time < max(stamps) + 0.5:
        world.step()
        for topic in set(topics) - compared:
            got = world.message(topic)
            ros1 = ros1_fields(got[0]) if got else None
            if ros1 and ros1["header"]["stamp"] == r["kept"][topic]["header"]["stamp"]:
                print(topic, json.dumps(r["kept"][topic])[:150])
                assert r["kept"][topic] == ros1, topic
                compared.add(topic)
    assert compared == set(topics)
    return r


def test_the_worlds_other_topics_reach_rclpy_as_the_ros1_plugins_built_them(tmp_path):
    """With enable_navigation_sensors:=true (a xacro argument, as spawn_mav.launch passes it), the
    GPS, magnetometer, barometer, the ground truth's transform and the IMU's true bias (rotors_comm,
    built for ROS 2 as mav_msgs is) reach an rclpy client with their ROS 2 types, and each one's first
    message from 1 s on equals, field for field, the ROS 1 plugin's message of the same step in
    rotors_sim (the same seed): the front end converts the plugin's own bytes (rosbags' ros1_to_cdr)."""
    topics = {
        "/firefly/gps": "sensor_msgs/msg/NavSatFix",
        "/firefly/magnetic_field": "sensor_msgs/msg/MagneticField",
        "/firefly/air_pressure": "sensor_msgs/msg/FluidPressure",
        "/firefly/ground_truth/transform": "geometry_msgs/msg/TransformStamped",
        "/firefly/ground_truth/imu_bias": "rotors_comm/msg/ImuBias",
    }
    received_as_on_ros1(tmp_path, topics, {"enable_navigation_sensors": "true"})
    assert "/firefly/motor_speed/0 (not a ROS 2 topic name)" in (tmp_path / "sim.log").read_text()


@pytest.mark.parametrize(("lidar", "topic", "kind"), [("hokuyo", "scan", "LaserScan"), ("vlp16", "velodyne_points", "PointCloud2")])
def test_lasers_reach_rclpy_as_the_ros1_plugins_built_them(tmp_path, lidar: str, topic: str, kind: str):
    """enable_lidar:=hokuyo (LaserScan) and vlp16 (PointCloud2 with ring and time): the scan reaches
    an rclpy client with its ROS 2 type, every range and byte as the ROS 1 plugin built it."""
    received_as_on_ros1(tmp_path, {f"/firefly/{topic}": f"sensor_msgs/msg/{kind}"}, {"enable_lidar": lidar})


def test_the_vi_sensor_hovering_example_on_ros2_takes_the_launch_files_vehicle_arguments(tmp_path):
    """mav_hovering_example_with_vi_sensor.py sensor_realism:=true enable_logging:=true: the firefly
    with the VI-sensor, every sensor effect on (a xacro argument, as spawn_mav.launch passes it),
    flies and records a ROS 2 bag that holds the VI-sensor's IMU (a topic the front end forwards from
    its plugin) at the world's rate; an argument the launch file does not have is refused in one line."""
    example = f"python {REPO}/rotors_gazebo_compat/rotors_ros2/mav_hovering_example_with_vi_sensor.py"
    refused = on_loopback_graph(f"{example} enable_navigation_sensors:=true", timeout_s=60)
    assert refused.returncode != 0 and "argument 'enable_navigation_sensors' is not served on ROS 2 yet" in refused.stderr
    res = on_loopback_graph(
        f"export ROS_HOME={tmp_path}; {example} sensor_realism:=true enable_logging:=true real_time_factor:=0 sim_seconds:=8",
        timeout_s=240,
    )
    assert res.returncode == 0, f"{res.stdout[-3000:]}\n{res.stderr[-3000:]}"
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_typestore

    bag = next(p for p in tmp_path.iterdir() if p.name.startswith("firefly_") and (p / "metadata.yaml").is_file())
    typestore = get_typestore(Stores.ROS2_JAZZY)
    with Reader(bag) as reader:
        imu = [c for c in reader.connections if c.topic == "/firefly/vi_sensor/imu"]
        assert imu and imu[0].msgtype == "sensor_msgs/msg/Imu", [c.topic for c in reader.connections]
        stamps = []
        for conn, _, raw in reader.messages(connections=imu):
            m = typestore.deserialize_cdr(raw, conn.msgtype)
            stamps.append(m.header.stamp.sec + m.header.stamp.nanosec * 1e-9)
            frame = m.header.frame_id
    steps = [round(b - a, 6) for a, b in zip(stamps, stamps[1:])]
    print(f"{bag.name}: /firefly/vi_sensor/imu {len(stamps)} messages from {stamps[0]:.2f} to {stamps[-1]:.2f} s, frame {frame}")
    assert frame == "firefly/vi_sensor/imu_link" and stamps[-1] >= 7.9 and set(steps) == {0.01}


def test_spawn_entity_and_delete_entity_bring_and_take_a_second_vehicle(tmp_path):
    """Gazebo ROS 2's /spawn_entity with a second firefly's URDF (namespace second) at (2, 0, 0.1): its
    ground-truth odometry appears on the graph as nav_msgs/msg/Odometry, framed as the ROS 1 plugin
    frames it, where it was put; /delete_entity removes it, and deleting it again or spawning text
    that is no model is refused with a message, the world running on."""
    import rotors_sim as rs

    urdf = tmp_path / "second.urdf"
    urdf.write_text(
        rs.world.run_xacro(
            rs.paths.package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo",
            {"mav_name": "firefly", "namespace": "second", "random_seed": 4, "enable_ground_truth": True, "enable_logging": False},
        )
    )
    r = simulator_and_client(tmp_path, "--mav firefly --seed 3", f"python {REPO}/test/ros2_clients/spawn_client.py {urdf} 120", 150)
    print(json.dumps(r))
    assert r["before"] is False and r["spawn"][0] is True and "spawned 'second'" in r["spawn"][1]
    assert r["types"] == ["nav_msgs/msg/Odometry"]
    frame, child, x = r["odometry"]
    assert (frame, child) == ("world", "second/base_link") and abs(x - 2.0) < 0.05
    assert r["delete"] == [True, "deleted 'second'"]
    assert r["delete_again"][0] is False and "no model named 'second'" in r["delete_again"][1]
    assert r["spawn_broken"][0] is False and "xml must be URDF or SDF text" in r["spawn_broken"][1]
