"""Hover, closed loop, for `make bench`: rotors_sim (this project from Python, no ROS) flies N
worlds of one firefly each (all 12 RotorS plugins, sensor noise seeded per world) holding (0, 0, 1)
with the Lee controller library at 100 Hz; physics at 500 Hz. Prints one JSON line.
    python rotors_sim_hover.py <worlds> <seconds> [mode] [threads]
mode "loop" (README's Python example): each control period Python reads every world's odometry,
computes the Lee controller's rotor speeds and sets them, then steps all worlds 5 physics steps.
mode "one_call" (the fastest documented use): the controller is attached inside the engine
(attach_controller) and one Batch.step call runs the whole flight, the worlds on threads."""

import json
import sys
import time

import rotors_sim as rs

worlds, seconds = int(sys.argv[1]), float(sys.argv[2])
mode = sys.argv[3] if len(sys.argv) > 3 else "one_call"
threads = int(sys.argv[4]) if len(sys.argv) > 4 else 0
if mode not in ("loop", "one_call"):
    sys.exit(f"mode '{mode}' is not loop or one_call")
SUBSTEPS = 5  # 500 Hz physics / 100 Hz control


def make(i: int) -> rs.World:
    world = rs.World("basic", step_size=0.002)
    world.spawn_mav("firefly", xyz=(0.0, 0.0, 1.0), random_seed=i, odometry_divisor=SUBSTEPS)
    world.listen(["/firefly/odometry_sensor1/odometry"])
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0.0, 0.0, 1.0])
    if mode == "one_call":
        world.attach_controller("firefly", lee)
    world.lee = lee  # kept alive with the world
    return world


batch = rs.Batch(make, worlds, threads=threads)
steps = int(round(seconds / 0.002))
t0 = time.perf_counter()
if mode == "one_call":
    batch.step(steps)
else:
    for _ in range(steps // SUBSTEPS):
        for world in batch.worlds:
            odometry = world.odometry("firefly")
            if odometry is not None:
                world.set_motor_speeds("firefly", world.lee.rotor_speeds(odometry))
        batch.step(SUBSTEPS)
wall = time.perf_counter() - t0
z = float(batch[0].link_state("firefly")[0][2])
print(
    json.dumps(
        {
            "peer": "rotors_sim",
            "mode": mode,
            "worlds": worlds,
            "sim_s": seconds,
            "wall_s": wall,
            "drone_s_per_s": worlds * seconds / wall,
            "physics_hz": 500,
            "control_hz": 100,
            "z_end_m": z,
        }
    )
)
