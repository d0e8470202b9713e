"""Gymnasium environments on the rotors_simulator engine (no ROS):

    RotorS/Hover-v0       hold a point            (rotors_sim.envs.hover.HoverEnv)
    RotorS/Waypoints-v0   fly through waypoints   (rotors_sim.envs.waypoints.WaypointsEnv)
    RotorS/NavigateClutter-v0  reach a goal through clutter from depth images, a vector
                          environment only (rotors_sim.envs.navigate.NavigateClutterEnv)

Both take action_type="motor" (one value per rotor) or "attitude" (roll, pitch, yaw rate, thrust).
FlightBatchEnv runs either task as a native vector environment on rotors_sim.FlightBatch (the
batched flight engine; gym.make_vec(id, num_envs, vectorization_mode="vector_entry_point")).
BatchedEnv runs many full worlds as one vector environment (one call steps every world on threads).
Spaces and rewards: the module docstrings and docs/python.md."""

import gymnasium as gym

from rotors_sim.envs.batched import FlightBatchEnv
from rotors_sim.envs.hover import HoverEnv
from rotors_sim.envs.navigate import NavigateClutterEnv
from rotors_sim.envs.vector import BatchedEnv
from rotors_sim.envs.waypoints import WaypointsEnv

for _id, _entry, _vector in (
    ("RotorS/Hover-v0", "rotors_sim.envs.hover:HoverEnv", "rotors_sim.envs.batched:hover_vector_env"),
    ("RotorS/Waypoints-v0", "rotors_sim.envs.waypoints:WaypointsEnv", "rotors_sim.envs.batched:waypoints_vector_env"),
):
    if _id not in gym.registry:
        gym.register(id=_id, entry_point=_entry, vector_entry_point=_vector)
if "RotorS/NavigateClutter-v0" not in gym.registry:
    gym.register(
        id="RotorS/NavigateClutter-v0", entry_point=None, vector_entry_point="rotors_sim.envs.navigate:navigate_clutter_vector_env"
    )

__all__ = ["BatchedEnv", "FlightBatchEnv", "HoverEnv", "NavigateClutterEnv", "WaypointsEnv"]
