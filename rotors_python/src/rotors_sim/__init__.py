"""rotors_sim: the rotors_simulator engine from Python, without ROS.

    import rotors_sim as rs
    world = rs.World("basic")                      # rotors_gazebo/worlds/basic.world
    world.spawn_mav("firefly", random_seed=7)      # the RotorS xacro, plugins and all
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0, 0, 1])
    for _ in range(1000):
        odometry = world.odometry("firefly")        # the odometry plugin's message, as on ROS
        if odometry is not None:
            world.set_motor_speeds("firefly", lee.rotor_speeds(odometry))
        world.step()

See docs/python.md.
"""

from rotors_sim._engine import SimError, atmosphere, frames, step_all
from rotors_sim.batch import Batch
from rotors_sim.controllers import AttitudeLevelController, LeePositionController
from rotors_sim.flight_batch import FlightBatch
from rotors_sim.world import Odometry, World, known_vehicles

__all__ = [
    "AttitudeLevelController",
    "Batch",
    "FlightBatch",
    "LeePositionController",
    "Odometry",
    "SimError",
    "World",
    "atmosphere",
    "frames",
    "known_vehicles",
    "step_all",
]
