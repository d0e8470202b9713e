#!/usr/bin/env python3
"""The README's pictures of the textured worlds, rendered by the simulator's own cameras through the
Python module: an overview of RotorS' warehouse and of the power plant (a 960 x 600 colour camera on
a static rig), and the VI-sensor's left image (752 x 480, mono8) in each, with the sun's shadows.

    python3 rotors_python/examples/world_pictures.py docs/
"""

import sys
from pathlib import Path

import cv2
import numpy as np

import rotors_sim as rs

VI_SENSOR = rs.paths.package_path("rotors_description") / "urdf" / "mav_with_vi_sensor.gazebo"
RIG = """<sdf version='1.6'><model name='rig'><static>true</static><link name='link'>
  <sensor name='overview' type='camera'><update_rate>30</update_rate><camera><horizontal_fov>1.4</horizontal_fov>
    <image><width>960</width><height>600</height><format>R8G8B8</format></image>
    <clip><near>0.05</near><far>120</far></clip></camera></sensor></link></model></sdf>"""


def quaternion(yaw: float, pitch: float = 0.0) -> list:
    """x y z w of yaw about z, then pitch about the new y."""
    cy, sy, cp, sp = np.cos(yaw / 2), np.sin(yaw / 2), np.cos(pitch / 2), np.sin(pitch / 2)
    return [-sy * sp, cy * sp, sy * cp, cy * cp]


def next_frame(world: rs.World) -> None:
    world.step(int(np.ceil(1.0 / 30.0 / world.step_size)) + 1)


def overview(world_name: str, xyz, yaw: float, pitch: float) -> np.ndarray:
    world = rs.World(world_name)
    world.spawn(RIG, "rig", xyz, rpy=(0.0, pitch, yaw))
    next_frame(world)
    return world.camera_image("rig", "overview").copy()


def vi_left(world_name: str, xyz, yaw: float) -> np.ndarray:
    world = rs.World(world_name)
    world.spawn_mav("firefly", model=VI_SENSOR, random_seed=3, xyz=(0.0, 0.0, 30.0))
    world.set_model_state("firefly", xyz, quaternion(yaw))
    next_frame(world)
    return world.camera_image("firefly", "firefly_vi_sensor_stereo_camera", 0).reshape(480, 752).copy()


def main() -> int:
    out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    pictures = {
        "warehouse.png": overview("warehouse", (-9.5, 6.5, 6.0), -0.75, 0.45),
        "powerplant_textured.png": overview("powerplant", (44.0, 10.0, 12.0), -2.6, 0.3),
        "vi_left_warehouse.png": vi_left("warehouse", (3.0, 1.55, 1.5), np.pi),
        "vi_left_powerplant.png": vi_left("powerplant", (-4.0, -4.0, 2.0), 0.35),
    }
    for name, image in pictures.items():
        bgr = cv2.cvtColor(image, cv2.COLOR_RGB2BGR) if image.ndim == 3 else image
        cv2.imwrite(str(out / name), bgr)
        print(out / name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
