"""Hover, closed loop, for `make bench`: rotors_sim.FlightBatch (the batched flight engine) flies N
fireflies to (0, 0, 1) with the Lee controller library inside the step at 100 Hz (each odometry
message), physics at 500 Hz, in one call. Prints one JSON line.
    python rotors_batch_hover.py <vehicles> <seconds> [threads] [imu] [randomized]
imu "imu" simulates the IMU with its noise (as RotorS' vehicle carries it); "no_imu" leaves it out
(what the peers simulate: no sensors). "randomized": every vehicle its own airframe (mass,
inertia, CoG, each rotor's constants; docs/batched_flight.md), drawn once before the run."""

import json
import sys
import time

import numpy as np

import rotors_sim as rs
from rotors_sim.randomization import check_spec, draw_airframe

vehicles, seconds = int(sys.argv[1]), float(sys.argv[2])
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 0
imu = (sys.argv[4] if len(sys.argv) > 4 else "no_imu") == "imu"
randomized = (sys.argv[5] if len(sys.argv) > 5 else "nominal") == "randomized"
batch = rs.FlightBatch("firefly", vehicles, step_size=0.002, control_divisor=5, threads=threads, imu=imu)
if randomized:
    spec = check_spec(
        {"mass": ("uniform", 0.8, 1.2), "inertia": ("uniform", 0.8, 1.2), "cog": ("uniform", -0.01, 0.01)}
        | {name: ("uniform", 0.9, 1.1) for name in ("motorConstant", "momentConstant", "timeConstantUp", "timeConstantDown")}
    )
    rng = np.random.default_rng(0)
    for i in range(vehicles):
        batch.set_airframe(i, **draw_airframe(spec, batch.nominal_airframe, rng))
steps = int(round(seconds / 0.002))
batch.step(50)  # threads started, caches warm
batch.reset()
t0 = time.perf_counter()
batch.step(steps)
wall = time.perf_counter() - t0
z = float(batch.truth()[0, 2])
print(
    json.dumps(
        {
            "peer": "rotors_batch",
            "mode": "one_call",
            "worlds": vehicles,
            "sim_s": seconds,
            "wall_s": wall,
            "drone_s_per_s": vehicles * seconds / wall,
            "physics_hz": 500,
            "control_hz": 100,
            "z_end_m": z,
            "threads": batch.threads,
            "imu": imu,
            "randomized": randomized,
            "memory_bytes_per_vehicle": batch.memory(),
        }
    )
)
