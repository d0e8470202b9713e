"""RotorS' remaining worlds, from Python without ROS: each loads, its terrain or
room stands where RotorS' files put it, and the firefly hovers in it with the Lee controller.
(The ROS hovering example in the waypoint world: test_worlds.py.)"""

import cv2
import numpy as np

import rotors_sim as rs
from rotors_sim.paths import package_path

MODELS = package_path("rotors_gazebo") / "models"
BALL = (
    "<sdf version='1.6'><model name='ball'><link name='link'><inertial><mass>1</mass></inertial>"
    "<collision name='c'><geometry><sphere><radius>0.5</radius></sphere></geometry></collision></link>"
    "</model></sdf>"
)


def terrain_height_m(image: str, size_xy_m: float, size_z_m: float, pos_z_m: float, x: float, y: float) -> float:
    """The height of an SDF heightmap at (x, y) [m] from its image (rows run towards -y), bilinear."""
    grey = cv2.imread(str(image), cv2.IMREAD_GRAYSCALE).astype(float)
    n = grey.shape[0]
    u, v = (x / size_xy_m + 0.5) * (n - 1), (0.5 - y / size_xy_m) * (n - 1)
    c, r = min(int(u), n - 2), min(int(v), n - 2)
    fu, fv = u - c, v - r
    h = (1 - fv) * ((1 - fu) * grey[r, c] + fu * grey[r, c + 1]) + fv * ((1 - fu) * grey[r + 1, c] + fu * grey[r + 1, c + 1])
    return pos_z_m + h / 255.0 * size_z_m


def hover(world: rs.World, xyz, duration_s: float = 8.0, **spawn_args):
    world.spawn_mav("firefly", xyz=xyz, random_seed=3, **spawn_args)
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([xyz[0], xyz[1], xyz[2] + 1.0])
    world.attach_controller("firefly", lee)
    world.step(int(round(duration_s / world.step_size)))
    return world.link_state("firefly")[0]


def flat_points(image: str, size_xy_m: float, size_z_m: float, pos_z_m: float, above_m: float, count: int):
    """(x, y) of the `count` highest samples above `above_m` whose 3 x 3 neighbourhood is flat
    within one grey level: there a ball dropped on the terrain stays where it lands."""
    grey = cv2.imread(str(image), cv2.IMREAD_GRAYSCALE).astype(float)
    n = grey.shape[0]
    found = []
    for r in range(1, n - 1):
        for c in range(1, n - 1):
            patch = grey[r - 1 : r + 2, c - 1 : c + 2]
            if np.ptp(patch) <= 1 and pos_z_m + grey[r, c] / 255.0 * size_z_m > above_m:
                found.append((grey[r, c], (c / (n - 1) - 0.5) * size_xy_m, (0.5 - r / (n - 1)) * size_xy_m))
    return [(x, y) for _, x, y in sorted(found, reverse=True)[:count]]


def test_the_yosemite_terrain_is_rotors_heightmap():
    world = rs.World("yosemite")
    image = MODELS / "yosemite/materials/textures/yosemite.png"
    points = flat_points(image, 1000, 125, -15, 5.0, 3)
    assert len(points) == 3
    for i, (x, y) in enumerate(points):
        world.spawn(BALL.replace("'ball'", f"'ball{i}'"), f"ball{i}", xyz=(x, y, terrain_height_m(image, 1000, 125, -15, x, y) + 1.0))
    world.step(int(round(3.0 / world.step_size)))
    for i, (x, y) in enumerate(points):
        rest = np.asarray(world.link_state(f"ball{i}")[0])
        ground = terrain_height_m(image, 1000, 125, -15, x, y)
        print(f"yosemite at ({x:.0f}, {y:.0f}): heightmap {ground:.2f} m, ball centre at {rest[2]:.2f} m")
        assert np.linalg.norm(rest[:2] - [x, y]) < 0.2 and abs(rest[2] - (ground + 0.5)) < 0.1


def test_the_firefly_hovers_in_yosemite():
    p = hover(rs.World("yosemite"), (0.0, 0.0, 0.1))
    assert np.linalg.norm(p - [0.0, 0.0, 1.1]) < 0.1, p


def test_hemicyl_ridge_along_y_wind_field_blows_at_the_hover():
    world = rs.World("hemicyl")
    image = MODELS / "hemicyl/materials/textures/hemicyl257.png"
    top = terrain_height_m(image, 4000, 202.3346, 0.0, 0.0, 500.0)
    world.spawn(BALL, "ball", xyz=(0.0, 500.0, top + 0.6))
    world.step(int(round(0.5 / world.step_size)))  # before it rolls off the crest
    rest = np.asarray(world.link_state("ball")[0])
    print(f"hemicyl ridge top at (0, 500): heightmap {top:.2f} m; ball centre at {rest[2]:.2f} m")
    assert top > 195.0 and abs(rest[2] - (top + 0.5)) < 0.1
    p = hover(
        world,
        (-1000.0, 0.0, 0.1),
        enable_wind=True,
        use_custom_static_wind_field=True,
        custom_wind_field_path=str(MODELS / "hemicyl/wind_field_hemicyl.txt"),
    )
    wind, count = world.message("/firefly/wind_speed")
    speed = np.linalg.norm([wind.velocity.x, wind.velocity.y, wind.velocity.z])
    print(f"hemicyl at (-1000, 0, 1.1): wind {speed:.2f} m/s from the field; firefly at {p.round(3)}")
    assert count > 0 and speed > 0.5 and np.linalg.norm(p - [-1000.0, 0.0, 1.1]) < 0.3


def test_occupancy_grid_room_has_rotors_ceiling_firefly_hovers():
    world = rs.World("waypoint")
    p = hover(world, (0.0, 0.0, 0.1))
    assert np.linalg.norm(p - [0.0, 0.0, 1.1]) < 0.1, p
    lee = rs.LeePositionController.for_mav("firefly")
    lee.set_point([0.0, 0.0, 5.0])  # above the ceiling (3.5 m)
    world.detach_controllers()
    world.attach_controller("firefly", lee)
    highest, touched = 0.0, set()
    for _ in range(400):
        world.step(1)
        highest = max(highest, float(world.link_state("firefly")[0][2]))
        touched |= {c["collision1"] + " " + c["collision2"] for c in world.contacts()}
    print(f"sent to 5 m: highest {highest:.3f} m; touched {sorted(touched)[:2]}")
    assert highest < 3.5 and any("Ceiling" in t for t in touched)


def test_the_pelican_world_flies_the_pelican():
    world = rs.World("pelican")
    world.spawn_mav("pelican", random_seed=2)
    lee = rs.LeePositionController.for_mav("pelican")
    lee.set_point([0.0, 0.0, 1.0])
    world.attach_controller("pelican", lee)
    world.step(1500)
    z = []
    for _ in range(100):
        world.step(1)
        z.append(world.link_state("pelican")[0][2])
    p = world.link_state("pelican")[0]
    print(f"pelican in pelican.world: {p.round(3)}, z steady within {np.ptp(z) * 1000:.1f} mm")
    # it holds its height below the set point: the controller's pelican.yaml is not the model (book
    # note 1), as in the basic world (test_vehicles_flight.py)
    assert np.linalg.norm(p[:2]) < 0.01 and abs(p[2] - 1.0) < 0.2 and np.ptp(z) < 0.005
