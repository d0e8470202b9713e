"""The techpod with RotorS' fixed-wing dynamics (librotors_gazebo_fw_dynamics_plugin.so), flown from
Python without ROS: trimmed level flight holds altitude and airspeed for 20 s, lift equals weight
at trim within 2 %, and an aileron step rolls right wing down at the rate the coefficients predict."""

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import clients.fixed_wing
import rotors_sim as rs
from rotors_sim import _engine
from rotors_sim.world import run_xacro
from support import launch, stop_launch

URDF = rs.paths.package_path("rotors_description") / "urdf" / "techpod_base.xacro"
FW = rs.paths.resource("fixed_wing")
SURFACE_MAX = 0.349066  # [rad] every surface of techpod.yaml
G = 9.8  # the world's gravity
V_TRIM = 15.0
HEIGHT = 50.0  # the flights' height in the basic world, whose origin is 500 m up: the air of 550 m
ALTITUDE = 500.0 + HEIGHT


def techpod_mass() -> float:
    urdf = run_xacro(URDF, {"namespace": "techpod", "mav_name": "techpod"})
    return sum(float(m.get("value")) for m in ET.fromstring(urdf).iter("mass"))


def command(elevator_rad: float = 0.0, throttle: float = 0.0, aileron: float = 0.0) -> list:
    # channels (techpod.yaml): aileron_right 0, elevator 1, flap 2, rudder 3, aileron_left 4, throttle 5
    return [-aileron, elevator_rad / SURFACE_MAX, 0.0, 0.0, aileron, throttle]


def trim(model, mass: float):
    """alpha, elevator, throttle of level flight at V_TRIM: world x and z force and the pitch moment zero
    (Newton with a numerical Jacobian)."""

    def residual(x):
        alpha, elevator, throttle = x
        w = model.compute(
            [V_TRIM * math.cos(alpha), 0.0, -V_TRIM * math.sin(alpha)], [0.0, 0.0, 0.0], command(elevator, throttle), ALTITUDE
        )
        f, m = np.asarray(w["force_B"]), np.asarray(w["moment_B"])
        # body pitched nose up by alpha (FLU): world x = cos a f_x - sin a f_z, world z = sin a f_x + cos a f_z
        fx_W = math.cos(alpha) * f[0] - math.sin(alpha) * f[2]
        fz_W = math.sin(alpha) * f[0] + math.cos(alpha) * f[2] - mass * G
        return np.array([fx_W, fz_W, m[1]])

    x = np.array([0.03, 0.0, 0.5])
    for _ in range(50):
        r = residual(x)
        J = np.column_stack([(residual(x + dx) - r) / 1e-7 for dx in np.eye(3) * 1e-7])
        x = x - np.linalg.solve(J, r)
        if np.max(np.abs(r)) < 1e-10:
            break
    return x


def fly_from_trim(world: rs.World, alpha: float, elevator: float, throttle: float, height: float = 50.0) -> None:
    q = [0.0, math.sin(-alpha / 2), 0.0, math.cos(alpha / 2)]  # nose up by alpha: about +y (left) by -alpha
    world.set_model_state("techpod", [0.0, 0.0, height], q, velocity=[V_TRIM, 0.0, 0.0])
    world.set_actuators("techpod", command(elevator, throttle))


@pytest.fixture(scope="module")
def trimmed():
    model = _engine.FixedWingModel(str(FW / "aero_params_techpod.yaml"), str(FW / "techpod.yaml"))
    mass = techpod_mass()
    return model, mass, trim(model, mass)


def test_lift_equals_weight_at_trim_within_2_percent(trimmed):
    model, mass, (alpha, elevator, throttle) = trimmed
    w = model.compute([V_TRIM * math.cos(alpha), 0.0, -V_TRIM * math.sin(alpha)], [0, 0, 0], command(elevator, throttle), ALTITUDE)
    lift = 0.5 * rs.atmosphere.density_kg_m3(ALTITUDE) * V_TRIM**2 * 0.47 * w["lift_coefficient"]
    print(
        f"techpod {mass:.3f} kg at {V_TRIM} m/s: alpha {math.degrees(alpha):.2f} deg, elevator "
        f"{math.degrees(elevator):.2f} deg, throttle {throttle:.3f}; lift {lift:.2f} N, weight {mass * G:.2f} N"
    )
    assert abs(mass - 2.81) < 0.01  # RotorS' techpod with its sensors
    assert abs(lift / (mass * G) - 1.0) < 0.02
    assert 0.0 < throttle < 1.0 and abs(elevator) < SURFACE_MAX


def test_trimmed_level_flight_holds_altitude_airspeed_20_s(trimmed):
    _, _, (alpha, elevator, throttle) = trimmed
    world = rs.World("basic")
    world.spawn(URDF, "techpod", xyz=(0, 0, 50), namespace="techpod", mav_name="techpod", random_seed=1)
    fly_from_trim(world, alpha, elevator, throttle)
    heights, speeds = [], []
    for _ in range(2000):  # 20 s
        world.step()
        p, _, v, _ = world.link_state("techpod")
        heights.append(p[2])
        speeds.append(float(np.linalg.norm(v)))
    print(
        f"20 s from trim: height {min(heights):.3f}-{max(heights):.3f} m, airspeed {min(speeds):.3f}-"
        f"{max(speeds):.3f} m/s, flown {p[0]:.1f} m"
    )
    assert max(abs(h - 50.0) for h in heights) < 1.0
    assert max(abs(s - V_TRIM) for s in speeds) < 0.5
    assert p[0] > 250.0  # it flew forward at about 15 m/s


def test_aileron_step_rolls_right_wing_down_at_predicted_rate(trimmed):
    _, _, (alpha, elevator, throttle) = trimmed
    world = rs.World("basic")
    world.spawn(URDF, "techpod", xyz=(0, 0, 50), namespace="techpod", mav_name="techpod", random_seed=1)
    fly_from_trim(world, alpha, elevator, throttle)
    world.step(100)
    world.set_actuators("techpod", command(elevator, throttle, aileron=0.2))  # left aileron down, right up
    delta_a = 0.2 * SURFACE_MAX - (-0.2 * SURFACE_MAX)  # delta_ail_left - delta_ail_right
    # steady roll rate where roll damping cancels the aileron: p = -C_l,da Da 2V / (b C_l,p)
    p_predicted = -0.0117 * delta_a * 2.0 * V_TRIM / (2.59 * -0.1647)
    # 0.6 s: 3.5 roll time constants (I_xx, about 0.39 kg m^2 with the ailerons 1 m out, over the roll
    # damping qS b^2 |C_l,p| / 2V = 2.3 N m s: 0.17 s), before the yaw the roll brings on builds up
    world.step(60)
    _, q, _, w_W = world.link_state("techpod")
    x, y, z, qw = q
    R = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * qw), 2 * (x * z + y * qw)],
            [2 * (x * y + z * qw), 1 - 2 * (x * x + z * z), 2 * (y * z - x * qw)],
            [2 * (x * z - y * qw), 2 * (y * z + x * qw), 1 - 2 * (x * x + y * y)],
        ]
    )
    p_B = (R.T @ w_W)[0]  # FLU roll rate: positive = right wing down
    print(f"aileron step: roll rate {p_B:.4f} rad/s after 0.6 s, predicted steady {p_predicted:.4f} rad/s")
    assert p_B > 0.0
    assert abs(p_B - p_predicted) < 0.1 * p_predicted


def test_fixed_wing_with_joy_flies_techpod_on_joystick_commands(ros):
    # the RotorS command with joystick:=none (no gamepad, no keyboard here): the launcher sets the
    # techpod flying at 15 m/s at 60 m and unpauses (the bag's first second shows it). The trimmed
    # stick command (roll 0, pitch = the elevator's normalized trim, thrust = the trim throttle)
    # reaches the plugin some wall time after the launch, which at real_time_factor 5 on a busy machine
    # may be after the untrimmed glide has reached the ground; so once the plugin is connected,
    # /gazebo/set_model_state puts the plane at the trim state, and from there the command must hold
    # it up for 10 s
    model = _engine.FixedWingModel(str(FW / "aero_params_techpod.yaml"), str(FW / "techpod.yaml"))
    alpha, elevator, throttle = trim(model, techpod_mass())
    proc = launch(
        ros,
        "rotors_gazebo",
        "fixed_wing_with_joy.launch",
        "gui:=false",
        "joystick:=none",
        "world_name:=basic",
        "real_time_factor:=5",
        "enable_logging:=true",
    )
    try:
        got = ros.run_client(
            clients.fixed_wing.joystick_flight_from_trim,
            timeout=240,
            pitch=float(elevator / SURFACE_MAX),
            thrust=float(throttle),
            qy=math.sin(-alpha / 2),
            qw=math.cos(alpha / 2),
            v_trim=V_TRIM,
        )
    finally:
        stop_launch(proc)
    print(
        f"fixed_wing_with_joy: 10 s from trim: flown {got['x']:.0f} m, "
        f"height {got['z0']:.1f} -> {got['z']:.1f} m, forward speed {got['vx']:.1f} m/s"
    )
    assert got["reset"]
    assert got["x"] > 120.0 and abs(got["z"] - got["z0"]) < 3.0 and got["vx"] > 12.0
    # enable_logging:=true reaches the techpod's bag plugin (RotorS' spawn_fixed_wing.launch drops it)
    bags = sorted(Path(ros.env["ROS_HOME"]).glob("techpod_*.bag"))
    assert bags, "fixed_wing_with_joy.launch enable_logging:=true wrote no bag"
    from rotors_evaluation.bag_data import FlightBag

    bag = FlightBag(bags[-1])
    stamped = bag.messages("techpod/ground_truth/pose")
    poses = [(m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec, m.pose.position.x) for m, _, _ in stamped]
    bag.close()
    t0, x0 = poses[0]
    launch_x = [x for t, x in poses if t <= t0 + 1.0]
    x_m = [x for _, x in poses]
    launched = launch_x[-1] - x0  # m flown in the first second
    print(f"bag {bags[-1].name}: {len(x_m)} ground-truth poses, launched at {launched:.1f} m/s, x up to {max(x_m):.0f} m")
    assert launched > 10.0  # the launcher's 15 m/s
    assert max(x_m) > 120.0


@pytest.mark.parametrize("wind_direction, wind_speed", [("-1 0 0", 5.0), ("0 0 1", 1.0)])
def test_wind_changes_airspeed_and_aoa_as_the_model_says(trimmed, wind_direction, wind_speed):
    # trimmed at 15 m/s over the ground, in a 5 m/s headwind (airspeed 20 m/s) or a 1 m/s updraft (angle
    # of attack up by atan(1 / 15)): the plugin's first acceleration is the model's force at
    # v_air = v - wind, divided by the mass (the wind plugin's speed reaches the plugin over the bus)
    model, mass, (alpha, elevator, throttle) = trimmed
    wind_W = float(wind_speed) * np.array([float(c) for c in wind_direction.split()])
    world = rs.World("basic")
    world.spawn(
        URDF,
        "techpod",
        xyz=(0, 0, 50),
        namespace="techpod",
        mav_name="techpod",
        random_seed=1,
        enable_wind=True,
        wind_direction=wind_direction,
        wind_speed_mean=wind_speed,
    )
    fly_from_trim(world, alpha, elevator, throttle)
    world.step(1)  # the plugin's forces act from the state of the step before (RotorS' order)
    _, _, v0, _ = world.link_state("techpod")
    world.step(1)  # one 10 ms step: the plane's climb soon lowers the angle of attack again
    _, _, v1, _ = world.link_state("techpod")
    a_W = (v1 - v0) / world.step_size
    # the model at the trim attitude (nose up by alpha about -y): body = R^T world
    c, s = math.cos(alpha), math.sin(alpha)
    R = np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])  # FLU body axes in the world, pitched nose up
    v_air_B = R.T @ (np.array([V_TRIM, 0.0, 0.0]) - wind_W)
    w = model.compute(list(v_air_B), [0.0, 0.0, 0.0], command(elevator, throttle), ALTITUDE)
    a_model = R @ np.asarray(w["force_B"]) / mass - [0.0, 0.0, G]
    print(
        f"wind {wind_W} m/s: airspeed {w['airspeed']:.2f} m/s, alpha {math.degrees(w['alpha']):.2f} deg "
        f"(trim {math.degrees(alpha):.2f}); acceleration {np.round(a_W, 3)} m/s^2, model {np.round(a_model, 3)}"
    )
    assert w["airspeed"] == pytest.approx(np.linalg.norm(v_air_B), abs=1e-9)
    if wind_W[0] != 0.0:
        assert w["airspeed"] == pytest.approx(V_TRIM + 5.0, abs=0.01)
    else:
        assert w["alpha"] == pytest.approx(alpha + math.atan(1.0 / V_TRIM), abs=1e-3)
    assert a_W[2] > 0.5  # more lift: it climbs
    # (within 0.2 m/s^2: in the step measured the pitch rate the new moment makes has begun to turn it)
    assert np.allclose(a_W, a_model, rtol=0.02, atol=0.2)


def test_deflection_out_of_range_is_one_line_changes_nothing(trimmed):
    _, _, (alpha, elevator, throttle) = trimmed
    world = rs.World("basic")
    world.spawn(URDF, "techpod", xyz=(0, 0, 50), namespace="techpod", mav_name="techpod", random_seed=1)
    fly_from_trim(world, alpha, elevator, throttle)
    with pytest.raises(
        rs.SimError,
        match=r"normalized\[4\] = 1\.5 puts the aileron_left at 0\.523599 rad, outside "
        r"its deflection range \[-0\.349066, 0\.349066\] rad",
    ):
        world.set_actuators("techpod", command(elevator, throttle, aileron=1.5))
    world.step(200)  # the trim command stays in force: level flight
    p, _, v, _ = world.link_state("techpod")
    assert abs(p[2] - 50.0) < 0.5 and abs(np.linalg.norm(v) - V_TRIM) < 0.3
