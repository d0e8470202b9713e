"""A hover simulated by RotorPy (SE3 controller), for `make bench`: run in RotorPy's own venv
(scripts/bench.py installs it).
    python rotorpy_hover.py                    20 s at 1 kHz; prints the wall seconds (section peers)
    python rotorpy_hover.py <worlds> <seconds> at 500 Hz; one JSON line (section python_peers).
RotorPy runs its controller at the simulation rate (it has no separate control rate) and has no
batch of worlds: <worlds> must be 1."""

import json
import sys
import time

from rotorpy.controllers.quadrotor_control import SE3Control
from rotorpy.environments import Environment
from rotorpy.trajectories.hover_traj import HoverTraj
from rotorpy.vehicles.crazyflie_params import quad_params
from rotorpy.vehicles.multirotor import Multirotor

json_mode = len(sys.argv) > 1
worlds, seconds, rate = (int(sys.argv[1]), float(sys.argv[2]), 500) if json_mode else (1, 20.0, 1000)
if worlds != 1:
    sys.exit("rotorpy_hover.py: RotorPy has no batch of worlds; run it with 1")
env = Environment(vehicle=Multirotor(quad_params), controller=SE3Control(quad_params), trajectory=HoverTraj(), sim_rate=rate)
t0 = time.monotonic()
env.run(t_final=seconds, use_mocap=False, terminate=False, plot=False, animate_bool=False, verbose=False)
wall = time.monotonic() - t0
if json_mode:
    print(
        json.dumps(
            {
                "peer": "rotorpy",
                "worlds": 1,
                "sim_s": seconds,
                "wall_s": wall,
                "drone_s_per_s": seconds / wall,
                "physics_hz": rate,
                "control_hz": rate,
            }
        )
    )
else:
    print(wall)
