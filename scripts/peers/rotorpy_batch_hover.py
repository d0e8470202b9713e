"""A hover of <vehicles> Crazyflies simulated by RotorPy's batched multirotor (PyTorch), for `make bench`:
run in RotorPy's own venv (scripts/bench.py installs it with its batched extra).
    python rotorpy_batch_hover.py <vehicles> <seconds> [<torch threads>, default 1]    one JSON line
Its fastest documented use on a CPU: one simulate_batch() call for the whole flight; integrator "rk4"
(BatchedMultirotor's docstring: fixed step, faster than the default "dopri5"); one torch thread, as
RotorPy's batched examples set (torch's default here, 2 threads, ran 1,024 vehicles 70 times slower
beside another busy process: every parallel region waits for the second thread).
Each 2 ms step (500 Hz): BatchedSE3Control on every vehicle (no separate control rate; BatchedHoverTraj
reference), BatchedMultirotor (crazyflie_params, aero on as in rotorpy_hover.py, one RK4 step, motor
noise of std 0), BatchedNoWind, BatchedImu measured twice (with and without noise, as simulate_batch
always does), the speed limit check; no collision checks (check_collisions=False, the documented switch
for flights that meet no obstacle). The state history simulate_batch returns is built inside the timing."""

import json
import sys
import time

import numpy as np
import torch
from rotorpy.controllers.quadrotor_control import BatchedSE3Control
from rotorpy.sensors.imu import BatchedImu
from rotorpy.simulate import simulate_batch
from rotorpy.trajectories.hover_traj import BatchedHoverTraj
from rotorpy.vehicles.crazyflie_params import quad_params
from rotorpy.vehicles.multirotor import BatchedMultirotor, BatchedMultirotorParams
from rotorpy.wind.default_winds import BatchedNoWind
from rotorpy.world import World

n, seconds, rate = int(sys.argv[1]), float(sys.argv[2]), 500
torch.set_num_threads(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
cpu = torch.device("cpu")
hover_speed = (quad_params["mass"] * 9.81 / (4 * quad_params["k_eta"])) ** 0.5
x0 = {
    "x": torch.zeros(n, 3).double(),
    "v": torch.zeros(n, 3).double(),
    "q": torch.tensor([0.0, 0.0, 0.0, 1.0]).repeat(n, 1).double(),
    "w": torch.zeros(n, 3).double(),
    "wind": torch.zeros(n, 3).double(),
    "rotor_speeds": torch.full((n, 4), hover_speed).double(),
}
params = BatchedMultirotorParams([quad_params] * n, n, cpu)
vehicles = BatchedMultirotor(params, n, x0, cpu, integrator="rk4")
world = World({"bounds": {"extents": [-10, 10, -10, 10, -10, 10]}, "blocks": []})
t0 = time.monotonic()
out = simulate_batch(
    world, x0, vehicles, BatchedSE3Control(params, n, cpu), BatchedHoverTraj(n), BatchedNoWind(n), BatchedImu(n, device=cpu),
    np.full(n, seconds), 1.0 / rate, 0.25, terminate=False, check_collisions=False,
)  # fmt: skip
wall = time.monotonic() - t0
if np.isnan(out[1]["x"][-1]).any() or np.abs(out[1]["x"][-1]).max() > 0.05:
    sys.exit("rotorpy_batch_hover.py: a vehicle left its hover")
print(
    json.dumps(
        {
            "peer": "rotorpy_batch",
            "worlds": n,
            "vehicles": n,
            "sim_s": seconds,
            "wall_s": wall,
            "drone_s_per_s": n * seconds / wall,
            "physics_hz": rate,
            "control_hz": rate,
            "torch_threads": torch.get_num_threads(),
        }
    )
)
