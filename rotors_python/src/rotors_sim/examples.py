"""The book's examples flown from Python without ROS.

hovering_example() is mav_hovering_example.launch in one loop: the vehicle spawned as
spawn_mav.launch spawns it, the Lee position controller library with the same yaml files, the
waypoint (0, 0, 1) due 5 s after the start and released with the first odometry stamped at or after
that time, as the ROS controller node releases it. Each odometry message gives one motor command,
applied before the next step: what lockstep does with the ROS nodes. With attached=True the
controller answers inside the engine's step loop (World.attach_controller): the same flight, faster.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from rotors_sim.controllers import LeePositionController
from rotors_sim.world import World


@dataclass
class HoverFlight:
    time_s: np.ndarray  # after each step
    position_W: np.ndarray  # ground truth, N x 3
    commands: list = field(default_factory=list)  # (odometry stamp, rotor speeds) per command
    messages: list = field(default_factory=list)  # (topic, time_s, ROS wire bytes) of `record` topics


def hovering_example(
    mav_name: str = "firefly",
    random_seed: int = 42,
    duration_s: float = 15.0,
    waypoint=(0.0, 0.0, 1.0, 0.0),
    due_s: float = 5.0,
    record: tuple[str, ...] = (),
    world: World | None = None,
    attached: bool = False,
) -> HoverFlight:
    world = world or World("basic")
    world.spawn_mav(mav_name, random_seed=random_seed)
    lee = LeePositionController.for_mav(mav_name)
    lee.set_point(waypoint[:3], yaw=waypoint[3], due=due_s)
    if attached:
        world.attach_controller(mav_name, lee)
    engine = world.engine
    seen = {topic: 0 for topic in record}
    times, positions, commands, messages = [], [], [], []
    last_odometry = 0
    steps = int(round(duration_s / world.step_size))
    for _ in range(steps):
        odometry = world.odometry(mav_name)
        if not attached and odometry is not None and odometry.count != last_odometry:
            last_odometry = odometry.count
            speeds = lee.rotor_speeds(odometry)
            world.set_motor_speeds(mav_name, speeds)
            commands.append((odometry.time_s, speeds))
        world.step()
        times.append(world.time)
        positions.append(world.link_state(mav_name)[0])
        for topic in record:
            got = engine.message(topic)
            if got is not None and got[1] != seen[topic]:
                seen[topic] = got[1]
                messages.append((topic, world.time, got[2]))
    return HoverFlight(np.array(times), np.array(positions), commands, messages)
