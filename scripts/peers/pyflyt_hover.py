"""Hover, closed loop, for `make bench`: PyFlyt (PyBullet) flies QuadX drones in its position mode
(flight mode 7) holding (0, 0, 1), physics at 500 Hz and control at 100 Hz (PyFlyt's defaults are
240 / 120 Hz). N drones share one Aviary, 3 m apart (PyFlyt has no batch of worlds). Runs in
PyFlyt's own venv (scripts/bench.py installs it). Prints one JSON line.
    python pyflyt_hover.py <drones> <seconds>"""

import json
import sys
import time

import numpy as np
from PyFlyt.core import Aviary

drones, seconds = int(sys.argv[1]), float(sys.argv[2])
side = int(np.ceil(np.sqrt(drones)))
start = np.array([[3.0 * (i % side), 3.0 * (i // side), 1.0] for i in range(drones)])
env = Aviary(
    start_pos=start, start_orn=np.zeros((drones, 3)), drone_type="quadx", render=False, physics_hz=500, drone_options={"control_hz": 100}
)
env.set_mode(7)
env.set_all_setpoints(np.column_stack([start[:, 0], start[:, 1], np.zeros(drones), start[:, 2]]))
steps = int(round(seconds * 100))  # one Aviary.step is one control period
t0 = time.perf_counter()
for _ in range(steps):
    env.step()
wall = time.perf_counter() - t0
z = float(env.state(0)[-1][2])
env.disconnect()
print(
    json.dumps(
        {
            "peer": "pyflyt",
            "worlds": drones,
            "sim_s": seconds,
            "wall_s": wall,
            "drone_s_per_s": drones * seconds / wall,
            "physics_hz": 500,
            "control_hz": 100,
            "z_end_m": z,
        }
    )
)
