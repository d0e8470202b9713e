"""The call an RL loop makes, for `make bench`: N fireflies in rotors_sim's FlightBatchEnv ("hover",
motor actions: each rotor's speed, physics at 500 Hz, 100 Hz actions), one FlightBatchEnv.step per
control period from Python with the actions of a fixed hover (each rotor at the hover speed), with
its observations, rewards and autoreset; beside it the raw engine in the same mode (rotor_speeds,
no controller, no IMU, as the environment; randomized: every vehicle flying an airframe drawn from
the same spec, drawn once) stepped in one call. Prints one JSON line.
    python rotors_env_hover.py <vehicles> <seconds> [randomized|nominal]
randomized: every vehicle its own airframe, drawn again at each reset (docs/batched_flight.md)."""

import json
import sys
import time

import numpy as np

import rotors_sim as rs
from rotors_sim.envs.batched import FlightBatchEnv
from rotors_sim.randomization import check_spec, draw_airframes

vehicles, seconds = int(sys.argv[1]), float(sys.argv[2])
randomized = (sys.argv[3] if len(sys.argv) > 3 else "nominal") == "randomized"
SPEC = {"mass": ("uniform", 0.8, 1.2), "inertia": ("uniform", 0.8, 1.2), "motorConstant": ("normal", 1.0, 0.03)}
envs = FlightBatchEnv("hover", vehicles, randomization=SPEC if randomized else None, episode_s=1e6)
d = envs.batch.description
hover_speed = np.sqrt(d.mass_kg * -d.gravity_W[2] / sum(r["motor_constant"] for r in d.rotors))
action = np.tile(2.0 * hover_speed / envs.max_rot_velocity - 1.0, (vehicles, 1)).astype(np.float32)
envs.reset(seed=0)
for _ in range(5):
    envs.step(action)  # threads started, caches warm
periods = int(round(seconds * 100))
t0 = time.perf_counter()
for _ in range(periods):
    envs.step(action)
env_wall = time.perf_counter() - t0

raw = rs.FlightBatch("firefly", vehicles, mode="rotor_speeds", step_size=0.002, control_divisor=5, imu=False)
if randomized:
    rngs = [np.random.default_rng(i) for i in range(vehicles)]
    for i, airframe in enumerate(draw_airframes(check_spec(SPEC), raw.nominal_airframe, rngs)):
        raw.set_airframe(i, **airframe)
raw.commands[:] = hover_speed
raw.step(50)
raw.reset()
t0 = time.perf_counter()
raw.step(periods * 5)
raw_wall = time.perf_counter() - t0
print(
    json.dumps(
        {
            "peer": "rotors_env",
            "worlds": vehicles,
            "sim_s": seconds,
            "randomized": randomized,
            "env_steps_per_s": periods / env_wall,
            "drone_s_per_s": vehicles * seconds / env_wall,
            "raw_drone_s_per_s": vehicles * seconds / raw_wall,
            "physics_hz": 500,
            "control_hz": 100,
            "threads": raw.threads,
        }
    )
)
