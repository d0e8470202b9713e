"""Every vehicle of a FlightBatch its own airframe: a vehicle given the airframe of a firefly
spawned with other xacro values (mass_scale, motor_constant_scale; the CoG moves with them, as the
sensors keep their mass) flies as the full world with that xacro does, to rounding, beside
vehicles of the nominal airframe; a randomisation spec draws airframes and noise seeds that repeat
for a seed and differ between episodes; bad values and specs are one line."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest

import rotors_sim as rs
from rotors_sim.envs.batched import FlightBatchEnv
from rotors_sim.paths import package_path
from rotors_sim.randomization import check_spec, draw_airframe, draw_airframe_rows, draw_airframes
from rotors_sim.world import run_xacro

DT, DIVISOR = 0.002, 5
ROUTE = [(0.0, [0.0, 0.0, 1.0], 0.0), (1.0, [0.6, 0.3, 1.3], 0.5), (2.5, [-0.3, 0.5, 1.1], -0.5)]
FLIGHT_S = 4.0
MAV = "firefly"


def scaled_world(mass_scale: float, motor_constant_scale: float) -> rs.World:
    world = rs.World("basic", step_size=DT)
    world.spawn_mav(
        MAV,
        xyz=(0.0, 0.0, 1.0),
        random_seed=7,
        odometry_divisor=DIVISOR,
        mass_scale=mass_scale,
        motor_constant_scale=motor_constant_scale,
    )
    lee = rs.LeePositionController.for_mav(MAV)
    lee.set_point(ROUTE[0][1])
    world.attach_controller(MAV, lee)
    world.lee = lee
    return world


def fly_beside(batch: rs.FlightBatch, worlds: list, flight_s: float, every: int) -> tuple[np.ndarray, np.ndarray]:
    """The batch and its vehicles' worlds over ROUTE from (0, 0, 1): each vehicle's largest distance
    from its world [m], compared every `every` physics steps, and the batch's paths (n x samples x 3)."""
    n = batch.count
    batch.reset(positions=np.tile([0.0, 0.0, 1.0], (n, 1)))
    batch.commands[:] = [*ROUTE[0][1], 0.0]
    worst_m, paths = np.zeros(n), []
    for k in range(0, int(round(flight_s / DT)), every):
        for t, p, yaw in ROUTE:
            if abs(k * DT - t) < DT / 2:
                batch.commands[:] = [*p, yaw]
                for world in worlds:
                    world.lee.set_point(p, yaw=yaw)
        batch.step(every)
        truth = batch.truth()
        for i, world in enumerate(worlds):
            world.step(every)
            worst_m[i] = max(worst_m[i], float(np.linalg.norm(world.link_state(MAV)[0] - truth[i, 0:3])))
        paths.append(truth[:, 0:3].copy())
    return worst_m, np.stack(paths, axis=1)


def test_each_vehicle_flies_its_own_airframe_as_the_world_built_with_it():
    """14 vehicles (three groups of four in lanes, two alone): every third the xacro's airframe,
    the others with mass_scale and motor_constant_scale drawn from U(0.8, 1.2) and U(0.85, 1.05);
    each compared with a full world spawned with its own xacro values, every 10 physics steps over
    the route."""
    rng = np.random.default_rng(3)
    n = 14
    scales = [(1.0, 1.0) if i % 3 == 0 else (rng.uniform(0.8, 1.2), rng.uniform(0.85, 1.05)) for i in range(n)]
    worlds = [scaled_world(*s) for s in scales]
    batch = rs.FlightBatch(MAV, n, step_size=DT, control_divisor=DIVISOR, seeds=[7] * n)
    for i, world in enumerate(worlds):
        airframe = world.engine.describe_multirotor(MAV, "odometry_sensor1/odometry").airframe
        if scales[i] != (1.0, 1.0):
            batch.set_airframe(i, **airframe)
        for key, value in batch.airframe(i).items():
            assert np.array_equal(np.asarray(value), np.asarray(airframe[key])), (i, key)
    worst_m, paths = fly_beside(batch, worlds, FLIGHT_S, every=10)
    apart_m = [float(np.max(np.linalg.norm(path - paths[0], axis=1))) for path in paths]
    for i in range(n):
        print(
            f"vehicle {i:2d}: mass_scale {scales[i][0]:.3f}, motor_constant_scale {scales[i][1]:.3f}: "
            f"{worst_m[i]:.1e} m from its world, {apart_m[i] * 1000:6.1f} mm from the nominal vehicle's path"
        )
    # to rounding: from 3e-16 m to 2e-11 m on this route, as the nominal firefly (the rounding of
    # the two engines' sums, grown by the closed loop)
    assert np.all(worst_m < 1e-10)
    # and the airframes made a difference
    assert all(apart_m[i] > 1e-3 for i in range(n) if scales[i] != (1.0, 1.0))
    assert all(apart_m[i] == 0.0 for i in range(n) if scales[i] == (1.0, 1.0))


def randomized_urdf(rng: np.random.Generator) -> str:
    """The firefly's URDF with its body link's mass, inertia and CoG and each motor plugin's
    constants drawn from the ranges domain randomisation uses."""
    args = dict(mav_name=MAV, namespace=MAV, random_seed=7, enable_logging=False, enable_ground_truth=True, log_file=MAV)
    args.update(wait_to_record_bag=False, enable_mavlink_interface=False, odometry_divisor=DIVISOR)
    robot = ET.fromstring(run_xacro(package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo", args))
    inertial = next(link for link in robot.iter("link") if link.get("name") == f"{MAV}/base_link_inertia").find("inertial")
    mass = inertial.find("mass")
    mass.set("value", repr(float(mass.get("value")) * rng.uniform(0.8, 1.2)))
    inertia = inertial.find("inertia")
    for axis in ("ixx", "iyy", "izz"):
        inertia.set(axis, repr(float(inertia.get(axis)) * rng.uniform(0.8, 1.2)))
    inertial.find("origin").set("xyz", " ".join(repr(v) for v in rng.uniform(-0.01, 0.01, 3)))
    factors = {"motorConstant": (0.9, 1.1), "momentConstant": (0.9, 1.1), "timeConstantUp": (0.8, 1.5), "timeConstantDown": (0.8, 1.5)}
    for plugin in robot.iter("plugin"):
        for name, (low, high) in factors.items():
            if plugin.find(name) is not None:
                plugin.find(name).text = repr(float(plugin.find(name).text) * rng.uniform(low, high))
    return ET.tostring(robot, encoding="unicode")


def test_a_randomised_batch_of_64_flies_as_64_worlds_built_with_their_values():
    """64 vehicles, each the airframe of its own world: a firefly URDF whose body mass, inertia, CoG
    and every rotor's motor, moment and time constants were drawn anew (as a randomised episode
    draws them). Each vehicle, given its world's values, flies the route as its world does."""
    rng = np.random.default_rng(64)
    n = 64
    batch = rs.FlightBatch(MAV, n, step_size=DT, control_divisor=DIVISOR, seeds=[7] * n)
    worlds = []
    for i in range(n):
        world = rs.World("basic", step_size=DT)
        world.spawn(randomized_urdf(rng), MAV, xyz=(0.0, 0.0, 1.0))
        lee = rs.LeePositionController.for_mav(MAV)
        lee.set_point(ROUTE[0][1])
        world.attach_controller(MAV, lee)
        world.lee = lee
        worlds.append(world)
        batch.set_airframe(i, **world.engine.describe_multirotor(MAV, "odometry_sensor1/odometry").airframe)
    worst_m, _ = fly_beside(batch, worlds, 3.0, every=25)
    ends = batch.truth()[:, 0:3]
    print(
        f"64 randomised airframes: largest difference from their worlds {worst_m.max():.1e} m (median {np.median(worst_m):.1e} m); "
        f"the ends of their flights {np.ptp(ends, axis=0).round(3)} m apart (x, y, z)"
    )
    assert worst_m.max() < 1e-10
    assert np.ptp(ends, axis=0).max() > 0.01  # they are 64 different vehicles


SPEC = {
    "mass": ("uniform", 0.8, 1.2),
    "inertia": ("uniform", 0.8, 1.2),
    "cog": ("uniform", -0.01, 0.01),
    "motorConstant": ("normal", 1.0, 0.03),
    "momentConstant": ("uniform", 0.9, 1.1),
    "timeConstantUp": ("uniform", 0.8, 1.5),
    "timeConstantDown": ("uniform", 0.8, 1.5),
    "maxRotVelocity": ("uniform", 0.9, 1.0),
    "gyroscopeNoiseDensity": ("uniform", 0.5, 2.0),
    "noiseNormalPosition": ("uniform", 0.0, 0.02),
    "actuatorDelay": ("uniform", 0, 5),
}


def airframes(envs: FlightBatchEnv) -> list[dict]:
    return [envs.batch.airframe(i) for i in range(envs.num_envs)]


def same(a: dict, b: dict) -> bool:
    return all(np.array_equal(np.asarray(a[k]), np.asarray(b[k])) for k in a)


def noisy_urdf(imu_factor: float, odometry_sigma_m: float) -> str:
    """The firefly's URDF with its IMU plugin's noise parameters scaled by `imu_factor` and its
    odometry sensor given a position noise of `odometry_sigma_m` (1 sigma, each axis)."""
    args = dict(mav_name=MAV, namespace=MAV, random_seed=7, enable_logging=False, enable_ground_truth=False, log_file=MAV)
    args.update(wait_to_record_bag=False, enable_mavlink_interface=False, odometry_divisor=DIVISOR)
    robot = ET.fromstring(run_xacro(package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo", args))
    for plugin in robot.iter("plugin"):
        if plugin.get("filename") == "librotors_gazebo_imu_plugin.so":
            for element in plugin:
                if element.tag.startswith(("gyroscope", "accelerometer")) and not element.tag.endswith("CorrelationTime"):
                    element.text = repr(float(element.text) * imu_factor)
        if plugin.get("filename") == "librotors_gazebo_odometry_plugin.so":
            plugin.find("noiseNormalPosition").text = " ".join([repr(odometry_sigma_m)] * 3)
    return ET.tostring(robot, encoding="unicode")


def test_each_vehicle_measures_with_its_own_noise_as_the_world_built_with_it():
    """Two vehicles of one batch, the second given the airframe of a world whose IMU noise is three
    times the xacro's and whose odometry has 2 cm of position noise: each vehicle's IMU and odometry
    readings are its world's, draw for draw (the same seed), over 1 s of free fall from 5 m (rotors
    stopped: no controller, no ground contact in between)."""
    worlds = []
    for urdf in (None, noisy_urdf(3.0, 0.02)):
        world = rs.World("basic", step_size=DT)
        if urdf is None:
            world.spawn_mav(MAV, xyz=(0.0, 0.0, 5.0), random_seed=7, odometry_divisor=DIVISOR, enable_ground_truth=False)
        else:
            world.spawn(urdf, MAV, xyz=(0.0, 0.0, 5.0))
        world.listen([f"/{MAV}/imu"])
        worlds.append(world)
    batch = rs.FlightBatch(MAV, 2, step_size=DT, control_divisor=DIVISOR, seeds=[7, 7], mode="rotor_speeds")
    noisy = worlds[1].engine.describe_multirotor(MAV, "odometry_sensor1/odometry").airframe
    assert noisy["gyroscopeNoiseDensity"] == 3.0 * batch.nominal_airframe["gyroscopeNoiseDensity"]
    batch.set_airframe(1, **noisy)
    batch.reset(positions=np.tile([0.0, 0.0, 5.0], (2, 1)))  # the noise is drawn from the airframe at a reset
    worst = np.zeros((2, 2))  # vehicle x (IMU [m/s^2], odometry position [m])
    accel_spread = [[], []]
    for _ in range(500):
        batch.step(1)
        for i, world in enumerate(worlds):
            world.step(1)
            imu, _ = world.message(f"/{MAV}/imu")
            a = np.array([imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z])
            worst[i, 0] = max(worst[i, 0], float(np.abs(a - batch.imu[i, 3:6]).max()))
            worst[i, 1] = max(worst[i, 1], float(np.abs(world.odometry(MAV).position_W - batch.odometry[i, 0:3]).max()))
            accel_spread[i].append(batch.imu[i, 3:6].copy())
    spread = [float(np.std(np.diff(np.array(s), axis=0))) for s in accel_spread]
    print(
        f"xacro noise: IMU {worst[0, 0]:.1e} m/s^2, odometry {worst[0, 1]:.1e} m from its world; "
        f"3x IMU noise, 2 cm odometry: {worst[1, 0]:.1e} m/s^2, {worst[1, 1]:.1e} m; "
        f"accelerometer step-to-step spread {spread[0]:.3f} and {spread[1]:.3f} m/s^2"
    )
    assert np.all(worst[:, 0] < 1e-6) and np.all(worst[:, 1] < 1e-9)
    assert 2.5 < spread[1] / spread[0] < 3.5  # the white noise scales with its density


def test_randomised_airframes_repeat_for_a_seed_and_differ_between_episodes():
    envs = FlightBatchEnv("hover", 8, randomization=SPEC, imu=True)
    nominal = envs.batch.nominal_airframe
    envs.reset(seed=11)
    first = airframes(envs)
    # every vehicle its own, every parameter of the spec drawn, each within its range
    assert not any(same(first[0], a) for a in first[1:])
    for a in first:
        assert 0.8 <= a["mass"] / nominal["mass"] <= 1.2
        assert np.all(np.abs(a["cog"] - nominal["cog"]) <= 0.01)
        assert np.all((a["timeConstantUp"] / nominal["timeConstantUp"] >= 0.8) & (a["timeConstantUp"] / nominal["timeConstantUp"] <= 1.5))
        assert len(set(a["motorConstant"])) == envs.batch.rotor_count  # one draw per rotor
        assert np.all(np.linalg.eigvalsh(a["inertia"]) > 0)
        assert 0.5 <= a["gyroscopeNoiseDensity"] / nominal["gyroscopeNoiseDensity"] <= 2.0
        assert np.all((a["noiseNormalPosition"] >= 0.0) & (a["noiseNormalPosition"] <= 0.02))
    rng = np.random.default_rng(0)
    actions = [rng.uniform(-0.2, 0.2, envs.action_space.shape).astype(np.float32) for _ in range(50)]

    def fly():
        out = []
        for a in actions:
            obs, *_ = envs.step(a)
            out.append(np.hstack([obs, envs.batch.imu]))
        return np.array(out)

    flown = fly()
    envs.reset(seed=11)
    assert all(same(a, b) for a, b in zip(first, airframes(envs)))
    assert np.array_equal(flown, fly())  # the same seed: the same airframes, noise and flight
    envs.reset()  # the next episode: new airframes and new noise
    second = airframes(envs)
    assert not any(same(a, b) for a, b in zip(first, second))
    imu_first, imu_second = flown[0, :, -6:], (envs.step(actions[0])[0], envs.batch.imu.copy())[1]
    assert not np.array_equal(imu_first, imu_second)
    # the spec off again: the xacro's airframe for every vehicle from the next reset on
    envs.reset(options={"randomization": None})
    assert all(same(nominal, a) for a in airframes(envs))


def test_an_actuator_delay_shifts_the_motors_by_its_steps():
    """Vehicle 1 with actuatorDelay 10, both commanded the same rotor speeds (changing every step):
    its rotors do what vehicle 0's did 10 physics steps earlier, bit for bit (stopped until then)."""
    batch = rs.FlightBatch(MAV, 2, mode="rotor_speeds", step_size=DT, noise=False)
    batch.set_airframe(1, actuatorDelay=10)
    batch.reset()
    assert batch.airframe(1)["actuatorDelay"] == 10 and batch.airframe(0)["actuatorDelay"] == 0
    speeds = []
    for k in range(60):
        batch.commands[:] = 400.0 + 5.0 * k + 30.0 * np.sin(0.3 * k)
        batch.step(1)
        speeds.append(batch.rotor_speeds.copy())
    speeds = np.array(speeds)
    assert np.all(speeds[:10, 1] == 0.0) and np.all(speeds[:10, 0] != 0.0)
    assert np.array_equal(speeds[10:, 1], speeds[:-10, 0])


def test_draws_follow_the_spec_and_bad_input_is_one_line():
    nominal = rs.FlightBatch(MAV, 1).nominal_airframe
    spec = check_spec({"mass": ("fixed", 1.25), "inertia": ("fixed", 0.81), "maxRotVelocity": ("fixed", 0.5)})
    a = draw_airframe(spec, nominal, np.random.default_rng(0))
    assert a["mass"] == nominal["mass"] * 1.25 and np.allclose(np.diag(a["inertia"]), 0.81 * np.diag(nominal["inertia"]))
    assert np.array_equal(a["maxRotVelocity"], nominal["maxRotVelocity"] * 0.5) and set(a) == {"mass", "inertia", "maxRotVelocity"}
    wind = draw_airframe(
        check_spec({"windGustForceMean": ("fixed", 4.0), "windGustStart": ("uniform", 1.0, 2.0)}), nominal, np.random.default_rng(0)
    )
    assert wind["windGustForceMean"] == 4.0 and 1.0 <= wind["windGustStart"] <= 2.0  # values in the SDF's units, not factors
    with pytest.raises(rs.SimError, match="drew windForceVariance = -1; it must be >= 0"):
        draw_airframe(check_spec({"windForceVariance": ("fixed", -1.0)}), nominal, np.random.default_rng(0))
    bad = {
        "wingspan": r"'wingspan' is not an airframe parameter; use one of: mass, inertia, cog",
        "mass_gauss": r"'mass_gauss' is not an airframe parameter",
    }
    for name, match in bad.items():
        with pytest.raises(rs.SimError, match=match):
            check_spec({name: ("uniform", 0.9, 1.1)})
    with pytest.raises(rs.SimError, match=r"randomization\['mass'\]: distribution 'gauss' is not known"):
        check_spec({"mass": ("gauss", 1.0, 0.1)})
    with pytest.raises(rs.SimError, match=r"randomization\['mass'\]: low 1.2 > high 0.8"):
        check_spec({"mass": ("uniform", 1.2, 0.8)})
    with pytest.raises(rs.SimError, match=r"give \('uniform', low, high\) with finite numbers"):
        check_spec({"mass": ("uniform", 0.8, float("nan"))})
    with pytest.raises(rs.SimError, match="drew a mass factor of -0.5; the mass must stay > 0"):
        draw_airframe(check_spec({"mass": ("fixed", -0.5)}), nominal, np.random.default_rng(0))
    batch = rs.FlightBatch(MAV, 2)
    batch.step(10)
    before = batch.truth()
    for values, match in [
        ({"mass": 0.0}, r"vehicle 1: mass = 0.000000 kg must be > 0"),
        ({"motorConstant": [1e-5] * 4}, r"vehicle 1: motorConstant must have one value per rotor \(6\)"),
        ({"timeConstantDown": [0.02, 0.02, 0.02, 0.02, 0.02, -1.0]}, r"vehicle 1, rotor 5: timeConstantDown = -1 must be > 0 s"),
        ({"inertia": np.diag([0.03, 0.04, -0.1])}, r"vehicle 1: inertia .* is not symmetric positive definite"),
        ({"cog": [0.0, np.nan, 0.0]}, r"vehicle 1: the CoG must be finite"),
        ({"battery": 3.0}, r"'battery' is not an airframe parameter; use mass, inertia, cog, actuatorDelay, motorConstant"),
        ({"actuatorDelay": 2.5}, r"vehicle 1: actuatorDelay must be a whole number of physics steps"),
        ({"actuatorDelay": -1}, r"vehicle 1: actuatorDelay = -1 steps must be in 0..1000"),
    ]:
        with pytest.raises(rs.SimError, match=match):
            batch.set_airframe(1, **values)
    assert same(batch.airframe(1), batch.nominal_airframe)  # nothing changed, and the batch flies on
    batch.step(10)
    assert np.isfinite(batch.truth()).all() and not np.array_equal(before, batch.truth())
    with pytest.raises(rs.SimError, match="vehicle 2 is not in 0..1"):
        batch.set_airframe(2, mass=1.0)


def test_airframes_set_in_one_call_are_those_set_one_by_one_and_a_bad_row_changes_none():
    """set_airframes (the environments' reset) gives each vehicle what set_airframe gives it; a bad
    value names its vehicle and leaves every vehicle as it was; the rows drawn for several
    generators are the dicts drawn for each."""
    spec = check_spec(
        {
            "mass": ("uniform", 0.8, 1.2),
            "inertia": ("uniform", 0.8, 1.2),
            "cog": ("uniform", -0.01, 0.01),
            "motorConstant": ("normal", 1.0, 0.03),
            "actuatorDelay": ("uniform", 0, 3),
        }
    )
    one, bulk = rs.FlightBatch(MAV, 6), rs.FlightBatch(MAV, 6)
    nominal = one.nominal_airframe
    picked = [1, 4, 5]
    rows = draw_airframe_rows(spec, nominal, [np.random.default_rng(k) for k in picked])
    each = draw_airframes(spec, nominal, [np.random.default_rng(k) for k in picked])
    for i, airframe in zip(picked, each):
        one.set_airframe(i, **airframe)
    bulk.set_airframes(picked, **rows)
    for i in range(6):
        a, b = one.airframe(i), bulk.airframe(i)
        assert all(np.array_equal(a[k], b[k]) for k in a), f"vehicle {i}"
    assert bulk.airframe(4)["mass"] != nominal["mass"] and bulk.airframe(0)["mass"] == nominal["mass"]
    before = [bulk.airframe(i) for i in range(6)]
    bad = {k: v.copy() for k, v in rows.items()}
    bad["mass"][2] = -1.0
    with pytest.raises(rs.SimError, match=r"^FlightBatch.set_airframe: vehicle 5: mass = -1.000000 kg must be > 0$"):
        bulk.set_airframes(picked, **bad)
    with pytest.raises(rs.SimError, match=r"set_airframes: mass must have one row per vehicle \(3\)"):
        bulk.set_airframes(picked, mass=np.ones(2))
    assert all(all(np.array_equal(a[k], bulk.airframe(i)[k]) for k in a) for i, a in enumerate(before))


def test_each_vehicle_its_own_wind_as_the_world_spawned_with_it():
    """RotorS' wind gust (mav_with_wind_gust.gazebo): vehicle 1 given the wind of a world spawned
    with another gust (force, start, direction) flies as that world, beside vehicle 0 with the
    nominal gust; a wind parameter on a vehicle without a wind plugin is one line."""
    model = package_path("rotors_description") / "urdf" / "mav_with_wind_gust.gazebo"
    gusts = [
        dict(wind_gust_start=1.0, wind_gust_force_mean=3.0),
        dict(wind_gust_start=0.5, wind_gust_force_mean=6.0, wind_gust_direction="0 1 0"),
    ]
    worlds = []
    for gust in gusts:
        world = rs.World("basic", step_size=DT)
        world.spawn_mav(MAV, xyz=(0.0, 0.0, 1.0), random_seed=7, odometry_divisor=DIVISOR, model=model, **gust)
        world.lee = rs.LeePositionController.for_mav(MAV)
        world.lee.set_point(ROUTE[0][1])
        world.attach_controller(MAV, world.lee)
        worlds.append(world)
    batch = rs.FlightBatch(MAV, 2, step_size=DT, control_divisor=DIVISOR, seeds=[7, 7], model=model, **gusts[0])
    other = worlds[1].engine.describe_multirotor(MAV, "odometry_sensor1/odometry").airframe
    batch.set_airframe(1, **other)
    assert batch.airframe(1)["windGustForceMean"] == 6.0 and np.allclose(batch.airframe(1)["windGustDirection"], [0, 1, 0])
    worst_m, paths = fly_beside(batch, worlds, 2.5, every=10)
    pushed_apart_m = float(np.max(np.linalg.norm(paths[1] - paths[0], axis=1)))
    print(f"two gusts: {worst_m[0]:.1e} and {worst_m[1]:.1e} m from their worlds; the paths up to {pushed_apart_m:.3f} m apart")
    assert np.all(worst_m < 1e-10) and pushed_apart_m > 0.05
    no_wind = rs.FlightBatch(MAV, 1)
    with pytest.raises(rs.SimError, match="'windForceMean' given, but the vehicle has no wind plugin"):
        no_wind.set_airframe(0, windForceMean=1.0)
    with pytest.raises(rs.SimError, match="vehicle 0, wind: windGustDuration = -1 must be >= 0 s"):
        batch.set_airframe(0, windGustDuration=-1.0)


def test_a_failed_motor_turns_no_more_and_an_unaware_controller_loses_the_vehicle():
    """maxRotVelocity 0 on rotor 2: that rotor stays stopped. Lee's controller, which does not know
    it and keeps allocating to six rotors, lets the firefly fall away from its set point, while the
    same controller holds the vehicle whose rotors all turn (in the full world the controller is
    told of the failure and re-allocates: test_motor_failure.py)."""
    batch = rs.FlightBatch(MAV, 2, step_size=DT, control_divisor=DIVISOR, noise=False)
    speeds = batch.nominal_airframe["maxRotVelocity"].copy()
    speeds[2] = 0.0
    batch.set_airframe(1, maxRotVelocity=speeds)
    batch.reset(positions=np.tile([0.0, 0.0, 1.0], (2, 1)))
    batch.commands[:] = [0.0, 0.0, 1.0, 0.0]
    batch.step(2500)  # 5 s
    rotors, p = batch.rotor_speeds, batch.truth()[:, 0:3]
    print(f"rotor 2 of the failed vehicle: {rotors[1, 2]} rad/s; positions after 5 s {np.round(p, 3).tolist()}")
    assert rotors[1, 2] == 0.0 and abs(rotors[0, 2]) > 400.0
    assert np.linalg.norm(p[0] - [0.0, 0.0, 1.04]) < 0.01 and np.linalg.norm(p[1] - [0.0, 0.0, 1.0]) > 0.5
