"""Hover, closed loop, for `make bench`: crazyflow (JAX on the CPU) flies N worlds of one Crazyflie
each to (0, 0, 1) with its onboard state controller at 100 Hz, physics at 500 Hz. Runs in
crazyflow's own venv (scripts/bench.py installs it). Prints one JSON line.
    python crazyflow_hover.py <worlds> <seconds> [mode]
mode "loop": each control period Python sets the state command (state_control) and calls step(5),
as a Python controller in the loop would. mode "one_call" (its fastest documented use): the state
controller runs inside Sim.step, so the command is set once and one step call runs the flight."""

import json
import sys
import time

import jax.numpy as jnp
from crazyflow.control.control import Control
from crazyflow.sim.sim import Sim

worlds, seconds = int(sys.argv[1]), float(sys.argv[2])
mode = sys.argv[3] if len(sys.argv) > 3 else "loop"
if mode not in ("loop", "one_call"):
    sys.exit(f"mode '{mode}' is not loop or one_call")
sim = Sim(n_worlds=worlds, n_drones=1, control=Control.state, freq=500, state_freq=100, device="cpu")
command = jnp.zeros((worlds, 1, 13)).at[..., 2].set(1.0)  # x, y, z = (0, 0, 1), the rest 0
substeps = 500 // 100
steps = int(round(seconds * 100))

# compile what is timed below (not timed itself)
sim.state_control(command)
sim.step(substeps if mode == "loop" else steps * substeps)
sim.data.states.pos.block_until_ready()
sim.reset()
t0 = time.perf_counter()
if mode == "loop":
    for _ in range(steps):
        sim.state_control(command)
        sim.step(substeps)
else:
    sim.state_control(command)
    sim.step(steps * substeps)
sim.data.states.pos.block_until_ready()
wall = time.perf_counter() - t0
z = float(sim.data.states.pos[0, 0, 2])
print(
    json.dumps(
        {
            "peer": "crazyflow",
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
