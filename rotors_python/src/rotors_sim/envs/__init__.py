"""Gymnasium environments on the rotors_simulator engine (no ROS):

    RotorS/Hover-v0       hold a point            (rotors_sim.envs.hover.HoverEnv)
    RotorS/Waypoints-v0   fly through waypoints   (rotors_sim.envs.waypoints.WaypointsEnv)

Both take action_type="motor" (one value per rotor) or "attitude" (roll, pitch, yaw rate, thrust).
BatchedEnv runs many of them as one vector environment (one call steps every world on threads).
Spaces and rewards: the module docstrings and docs/python.md."""

import gymnasium as gym

from rotors_sim.envs.hover import HoverEnv
from rotors_sim.envs.vector import BatchedEnv
from rotors_sim.envs.waypoints import WaypointsEnv

for _id, _entry in (("RotorS/Hover-v0", "rotors_sim.envs.hover:HoverEnv"),
                    ("RotorS/Waypoints-v0", "rotors_sim.envs.waypoints:WaypointsEnv")):
    if _id not in gym.registry:
        gym.register(id=_id, entry_point=_entry)

__all__ = ["BatchedEnv", "HoverEnv", "WaypointsEnv"]
