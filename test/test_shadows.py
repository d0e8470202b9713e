"""The sun's shadows as Gazebo casts them, against geometry: a 1 m cube on the ground under a sun
travelling 45 deg down towards +x casts a shadow 1 m long behind it (x 0.5 to 1.5), seen by a
camera looking straight down; the shadowed ground is lit by the ambient light only. The switches
(the sun's <cast_shadows>, <scene><shadows>, the visual's <cast_shadows>, World(shadows=False))
each take the shadow away."""

import numpy as np
import pytest

import rotors_sim as rs

W, H, HFOV = 320, 240, 1.0
F_PX = W / (2 * np.tan(HFOV / 2))
CAMERA_XYZ = (1.0, 0.0, 6.0)
ALBEDO, AMBIENT, SUN = 0.8, 0.4, 0.8


def world_sdf(sun_casts: str = "true", scene_shadows: str = "true", cube_casts: str = "true") -> str:
    return f"""<?xml version="1.0"?><sdf version="1.6"><world name="default">
  <scene><ambient>{AMBIENT} {AMBIENT} {AMBIENT} 1</ambient><shadows>{scene_shadows}</shadows></scene>
  <light name="sun" type="directional"><cast_shadows>{sun_casts}</cast_shadows>
    <diffuse>{SUN} {SUN} {SUN} 1</diffuse><direction>1 0 -1</direction></light>
  <model name="ground"><static>true</static><link name="link"><visual name="v"><cast_shadows>false</cast_shadows>
    <geometry><plane><normal>0 0 1</normal><size>20 20</size></plane></geometry>
    <material><diffuse>{ALBEDO} {ALBEDO} {ALBEDO} 1</diffuse></material></visual></link></model>
  <model name="cube"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="link"><visual name="v">
    <cast_shadows>{cube_casts}</cast_shadows><geometry><box><size>1 1 1</size></box></geometry></visual></link></model>
  <model name="rig"><static>true</static><pose>{CAMERA_XYZ[0]} {CAMERA_XYZ[1]} {CAMERA_XYZ[2]} 0 1.5707963 0</pose>
    <link name="link"><sensor name="down" type="camera"><update_rate>10</update_rate><camera>
      <horizontal_fov>{HFOV}</horizontal_fov><image><width>{W}</width><height>{H}</height><format>R8G8B8</format></image>
      <clip><near>0.1</near><far>20</far></clip></camera></sensor></link></model>
</world></sdf>"""


def ground_row(world: rs.World) -> tuple:
    """Grey levels along the image column under y = 0, and the world x of each pixel row."""
    world.step(int(0.2 / world.step_size))
    image = world.camera_image("rig", "down").astype(float)
    # looking down with the camera's top towards +x: row v sees x = x_cam - (v - c_y) Z / f
    v = np.arange(H)
    x = CAMERA_XYZ[0] - (v - (H - 1) / 2) * CAMERA_XYZ[2] / F_PX
    return image[:, (W - 1) // 2, 0], x


def test_cube_casts_shadow_as_long_as_its_height_at_45_degrees():
    grey, x = ground_row(rs.World(sdf=world_sdf()))
    lit = 255 * ALBEDO * (AMBIENT + SUN * np.cos(np.pi / 4))
    shadow = 255 * ALBEDO * AMBIENT
    behind = (x > 0.6) & (x < 1.4)
    beyond = (x > 1.6) & (x < 3.0)
    before = x < -0.85  # nearer the cube the camera sees its sunlit side (x -0.5), not the ground
    print(f"ground lit {grey[beyond].mean():.1f} (expected {lit:.1f}), in the shadow {grey[behind].mean():.1f} " f"(expected {shadow:.1f})")
    assert np.allclose(grey[behind], shadow, atol=2) and np.allclose(grey[beyond], lit, atol=2)
    assert np.allclose(grey[before], lit, atol=2)
    # the shadow's far edge at x = 1.5 (cube top edge 0.5 + height 1 / tan 45), within 3 cm
    dark = (x > 0.5) & (grey < (lit + shadow) / 2)
    edge = x[dark].max()
    print(f"shadow edge at x = {edge:.3f} m (1.5 expected; a pixel is {CAMERA_XYZ[2] / F_PX * 100:.1f} cm here)")
    assert abs(edge - 1.5) < 0.03


@pytest.mark.parametrize("switch", ["sun", "scene", "visual", "option"])
def test_each_switch_takes_the_shadow_away(switch):
    sdf = world_sdf(
        sun_casts="false" if switch == "sun" else "true",
        scene_shadows="false" if switch == "scene" else "true",
        cube_casts="false" if switch == "visual" else "true",
    )
    grey, x = ground_row(rs.World(sdf=sdf, shadows=switch != "option"))
    lit = 255 * ALBEDO * (AMBIENT + SUN * np.cos(np.pi / 4))
    assert np.allclose(grey[(x > 0.6) & (x < 3.0)], lit, atol=2)
