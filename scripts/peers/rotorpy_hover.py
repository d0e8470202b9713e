"""A 20 s hover simulated by RotorPy (SE3 controller, 1 kHz), for `make bench`: run in RotorPy's own
venv (scripts/bench.py installs it); prints the wall seconds it took."""
import time

from rotorpy.controllers.quadrotor_control import SE3Control
from rotorpy.environments import Environment
from rotorpy.trajectories.hover_traj import HoverTraj
from rotorpy.vehicles.crazyflie_params import quad_params
from rotorpy.vehicles.multirotor import Multirotor

env = Environment(vehicle=Multirotor(quad_params), controller=SE3Control(quad_params), trajectory=HoverTraj(),
                  sim_rate=1000)
t0 = time.monotonic()
env.run(t_final=20, use_mocap=False, terminate=False, plot=False, animate_bool=False, verbose=False)
print(time.monotonic() - t0)
