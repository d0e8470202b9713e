"""Hover, closed loop, for `make bench`: crazyflow 0.4.0, its current release (JAX on the CPU, MJX),
flies N worlds of one Crazyflie each to (0, 0, 1) with its onboard state controller at 100 Hz,
physics at 500 Hz, at its fastest documented use: the command set once, one Sim.step call runs the
flight. Runs in its own venv (scripts/bench.py installs it). Prints one JSON line.
    python crazyflow040_hover.py <worlds> <seconds>
0.4.0's state command is 16 wide (x, y, z, v, a, q x y z w, body rates); a zero quaternion gives
NaN, so the command holds the identity attitude."""

import json
import sys
import time

import jax.numpy as jnp
from crazyflow.control import Control
from crazyflow.sim.sim import Sim

worlds, seconds = int(sys.argv[1]), float(sys.argv[2])
sim = Sim(n_worlds=worlds, n_drones=1, control=Control.state, freq=500, state_freq=100, device="cpu")
command = jnp.zeros(sim.data.controls.state.staged_cmd.shape).at[..., 2].set(1.0).at[..., 12].set(1.0)
steps = int(round(seconds * 500))

sim.state_control(command)  # compile what is timed below (not timed itself)
sim.step(steps)
sim.data.states.pos.block_until_ready()
sim.reset()
t0 = time.perf_counter()
sim.state_control(command)
sim.step(steps)
sim.data.states.pos.block_until_ready()
wall = time.perf_counter() - t0
z = float(sim.data.states.pos[0, 0, 2])
print(
    json.dumps(
        {
            "peer": "crazyflow040",
            "mode": "one_call",
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
