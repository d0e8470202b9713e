"""Hover, closed loop, for `make bench`: gym-pybullet-drones (PyBullet) flies Crazyflie 2.X drones
(CtrlAviary, PyBullet's own physics) with its DSL PID controller holding (0, 0, 1), physics at
500 Hz and control at 100 Hz unless given (its defaults are 240 / 48 Hz; physics a multiple of
control). N drones share one aviary, 3 m apart (it has no batch of worlds). Runs in its own venv
(scripts/bench.py installs it from a clone). Prints one JSON line.
    python gym_pybullet_drones_hover.py <drones> <seconds> [<physics_hz> <control_hz>]"""

import json
import sys
import time

import numpy as np
from gym_pybullet_drones.control.DSLPIDControl import DSLPIDControl
from gym_pybullet_drones.envs.CtrlAviary import CtrlAviary
from gym_pybullet_drones.utils.enums import DroneModel, Physics

drones, seconds = int(sys.argv[1]), float(sys.argv[2])
physics_hz, control_hz = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) > 4 else (500, 100)
side = int(np.ceil(np.sqrt(drones)))
start = np.array([[3.0 * (i % side), 3.0 * (i // side), 1.0] for i in range(drones)])
env = CtrlAviary(
    drone_model=DroneModel.CF2X,
    num_drones=drones,
    initial_xyzs=start,
    initial_rpys=np.zeros((drones, 3)),
    physics=Physics.PYB,
    pyb_freq=physics_hz,
    ctrl_freq=control_hz,
    gui=False,
    record=False,
    obstacles=False,
    user_debug_gui=False,
)
controllers = [DSLPIDControl(drone_model=DroneModel.CF2X) for _ in range(drones)]
action = np.zeros((drones, 4))  # rotor speeds [RPM]
obs, _ = env.reset()
steps = int(round(seconds * control_hz))  # one env.step is one control period
t0 = time.perf_counter()
for _ in range(steps):
    for j in range(drones):
        action[j], _, _ = controllers[j].computeControlFromState(
            control_timestep=env.CTRL_TIMESTEP, state=obs[j], target_pos=start[j], target_rpy=np.zeros(3)
        )
    obs, _, _, _, _ = env.step(action)
wall = time.perf_counter() - t0
z = float(obs[0][2])
env.close()
print(
    json.dumps(
        {
            "peer": "gym_pybullet_drones",
            "worlds": drones,
            "sim_s": seconds,
            "wall_s": wall,
            "drone_s_per_s": drones * seconds / wall,
            "physics_hz": physics_hz,
            "control_hz": control_hz,
            "z_end_m": z,
        }
    )
)
