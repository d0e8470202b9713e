"""Hover, closed loop, for `make bench`: rotors_sim (this project from Python, no ROS) flies N
worlds of one firefly each (all 12 RotorS plugins, sensor noise seeded per world) holding (0, 0, 1)
with the Lee controller library answering every odometry message (100 Hz) inside the engine's step
loop; physics at 500 Hz. The worlds step on threads, one call for all. Prints one JSON line.
    python rotors_sim_hover.py <worlds> <seconds> [threads]"""
import json
import sys
import time

import rotors_sim as rs

worlds, seconds = int(sys.argv[1]), float(sys.argv[2])
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 0


def make(i: int) -> rs.World:
    world = rs.World("basic", step_size=0.002)
    world.spawn_mav("firefly", xyz=(0.0, 0.0, 1.0), random_seed=i, odometry_divisor=5)
    world.listen(["/firefly/odometry_sensor1/odometry"])
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0.0, 0.0, 1.0])
    world.attach_controller("firefly", lee)
    world.lee = lee  # kept alive with the world
    return world


batch = rs.Batch(make, worlds, threads=threads)
steps = int(round(seconds / 0.002))
t0 = time.perf_counter()
batch.step(steps)
wall = time.perf_counter() - t0
z = float(batch[0].link_state("firefly")[0][2])
print(json.dumps({"peer": "rotors_sim", "worlds": worlds, "sim_s": seconds, "wall_s": wall,
                  "drone_s_per_s": worlds * seconds / wall, "physics_hz": 500, "control_hz": 100, "z_end_m": z}))
