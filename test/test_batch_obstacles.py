"""Obstacles, depth and collisions in the batched flight engine, against geometry: the distance
from a point to a box and to a cylinder; a depth camera's pixel depth of a wall and of the ground
(the pinhole's own equation) and its D435 noise (sigma = z^2 e / (f b)); a vehicle flown straight
into a wall is flagged at the step its sphere reaches it, never later; seeded courses repeat; and
RotorS/NavigateClutter-v0 as Gymnasium's vector API and its scripted baseline use it."""

import gymnasium as gym
import numpy as np
import pytest

import rotors_sim as rs
import rotors_sim.envs  # noqa: F401 (registers the environments)
from rotors_sim import clutter
from rotors_sim._engine import ObstacleField, SimError
from rotors_sim.envs.navigate import FreeDirectionBaseline, NavigateClutterEnv, fly_courses

WALL_X, WALL_HALF = 3.0, 0.1  # a wall across x = 3 m, 0.2 m thick


def wall_batch(count: int = 2, noise: bool = False, **camera) -> tuple[rs.FlightBatch, ObstacleField]:
    batch = rs.FlightBatch("firefly", count=count, mode="lee_position", noise=False)
    field = ObstacleField(count, batch.collision_radius)
    for env in range(count):
        field.set(env, np.array([[clutter.BOX, WALL_X, 0.0, 2.0, WALL_HALF, 5.0, 2.0, 0.0]]))
    batch.set_obstacles(field)
    batch.set_depth_camera(noise=noise, **camera)
    return batch, field


def test_distance_to_a_turned_box_and_a_cylinder_is_euclidean():
    field = ObstacleField(1, 0.5)
    # a 2 x 1 x 1 m box turned 90 deg about z (its long side along y), a cylinder r 0.5 m, 2 m tall at x = 5
    field.set(0, np.array([[0, 0.0, 0.0, 0.5, 1.0, 0.5, 0.5, np.pi / 2], [1, 5.0, 0.0, 1.0, 0.5, 0.5, 1.0, 0.0]]))
    for point, expected in [
        ((0.0, 1.2, 0.5), 0.2),  # beyond the end of its long side (now along y): 1.2 - 1.0 ...
        ((1.5, 0.0, 0.5), 1.0),  # ... and beside it: 1.5 - 0.5
        ((0.8, 1.3, 1.4), np.sqrt(0.3**2 + 0.3**2 + 0.4**2)),  # off a top corner
        ((0.1, 0.1, 0.5), 0.0),  # inside
        ((6.0, 0.0, 1.0), 0.5),  # beside the cylinder
        ((5.0, 0.0, 2.5), 0.5),  # above its top
        ((5.0 + 0.6 / np.sqrt(2), 0.6 / np.sqrt(2), 2.3), np.hypot(0.1, 0.3)),  # off its rim
    ]:
        assert field.distance(0, np.array(point)) == pytest.approx(expected, abs=1e-12), point


def test_depth_of_a_wall_and_of_the_ground_is_the_pinholes():
    batch, _ = wall_batch()
    batch.step(500)  # hover at (0, 0, 1)
    everyone = batch.render_depth()
    assert np.array_equal(batch.render_depth([1]), everyone[1:2], equal_nan=True)  # one vehicle's rows alone
    depth = everyone[0]
    cam = batch.depth_camera
    h, w = depth.shape
    p = batch.truth()[0, 0:3]
    fy = h / (2 * np.tan(cam["vertical_fov"] / 2))
    # a wall square to the axis: every pixel that meets it has depth = its distance (a plane at z = d)
    d_wall = WALL_X - WALL_HALF - p[0] - cam["xyz"][0]
    wall_rows = depth[: h // 2]
    assert np.nanmax(np.abs(wall_rows - d_wall)) < 2e-3, (d_wall, np.nanmin(wall_rows), np.nanmax(wall_rows))
    # the ground under the horizon, nearer than the wall: depth = height / y, y = (v - (H-1)/2) / fy
    row = h - 1
    y = (row - (h - 1) / 2) / fy
    height = p[2] + cam["xyz"][2]
    expected = height / y
    assert expected < d_wall
    assert np.allclose(depth[row], expected, rtol=2e-3), (depth[row, :3], expected)
    wall = f"wall {d_wall:.4f} m: pixels {np.nanmin(wall_rows):.4f}..{np.nanmax(wall_rows):.4f}"
    print(f"{wall}; ground row {row}: {depth[row, 0]:.4f} m, pinhole {expected:.4f} m")


def test_range_rays_read_the_wall_and_the_ground():
    batch, _ = wall_batch()
    batch.step(500)
    # forward, down, 30 deg down, and up (nothing: no return)
    tilt = np.radians(30)
    batch.set_range_rays([[1, 0, 0], [0, 0, -1], [np.cos(tilt), 0, -np.sin(tilt)], [0, 0, 1]], min_range=0.05, max_range=20.0)
    p = batch.truth()[0, 0:3]
    ranges = batch.cast_ranges()[0]
    wall = WALL_X - WALL_HALF - p[0]
    expected = [wall, p[2], min(wall / np.cos(tilt), p[2] / np.sin(tilt)), np.inf]
    print(f"ranges {np.round(ranges, 4)} against {np.round(expected, 4)}")
    assert np.allclose(ranges[:3], expected[:3], atol=2e-3) and np.isinf(ranges[3])
    with pytest.raises(SimError, match="direction 0 is not finite or is zero"):
        batch.set_range_rays([[0, 0, 0]])


def test_depth_noise_is_the_d435_model():
    batch, _ = wall_batch(count=4, noise=True)
    batch.step(500)
    depth = batch.render_depth()[:, :20]  # the rows that see the wall
    d_wall = WALL_X - WALL_HALF - batch.truth()[0, 0]
    f_px = 848 / (2 * np.tan(1.59174 / 2))
    sigma = d_wall**2 * 0.25 / (f_px * 0.05)
    measured = np.nanstd(depth - d_wall)
    print(f"D435 noise at {d_wall:.2f} m: sigma {measured:.4f} m, model z^2 e / (f b) = {sigma:.4f} m")
    assert measured == pytest.approx(sigma, rel=0.05)
    # each vehicle its own stream, and the same again after a reset at the same place
    assert not np.array_equal(depth[0], depth[1])
    batch.reset(positions=batch.truth()[:, 0:3], yaws=np.zeros(4))
    again = batch.render_depth()[:, :20]
    batch.reset(positions=batch.truth()[:, 0:3], yaws=np.zeros(4))
    assert np.array_equal(again, batch.render_depth()[:, :20], equal_nan=True)


def test_flying_into_a_wall_is_a_collision_at_the_step_it_touches():
    batch, field = wall_batch(count=1)
    batch.step(500)
    batch.commands[:] = [10.0, 0.0, 1.0, 0.0]  # a set point behind the wall: straight into it
    radius, cog = batch.collision_radius, batch.description.p_M_cog
    flagged_at = None
    for step in range(3000):
        was = batch.collided[0]
        batch.step(1)
        p_cog = batch.truth()[0, 0:3] + cog  # level flight: the CoG's offset is the model's
        gap = field.distance(0, p_cog)
        if not was and batch.collided[0]:
            flagged_at = (step, gap, np.linalg.norm(batch.truth()[0, 7:10]))
            break
        assert gap > radius - 1e-9, f"the sphere reached the wall at step {step} (gap {gap:.4f} m) without a collision"
    assert flagged_at is not None, "the vehicle never touched the wall"
    step, gap, speed = flagged_at
    print(f"collision at step {step}: gap {gap:.4f} m <= radius {radius:.4f} m at {speed:.2f} m/s")
    assert radius - speed * batch.step_size * 1.01 <= gap <= radius
    # a reset clears it
    batch.reset()
    assert not batch.collided[0]


def test_a_shared_world_is_seen_and_touched_where_its_surface_is():
    """The power plant in every environment: its visuals for the rays, its occupancy (0.25 m cells,
    RotorS' own octree) for the spheres. Walked along a ray to the plant, a sphere touches it no
    later than where the ray meets the surface, and where it first touches, rays from its centre
    find a surface within its radius and one cell's diagonal (the cells hold the surfaces)."""
    world = rs.World("powerplant")
    field = ObstacleField(2, 0.4)
    field.set_world(world.engine, [15.0, -17.0, 15.0], [80.0, 80.0, 30.0], 0.25)
    assert field.world_occupied_cells > 10000
    radius, cell = 0.3, 0.25
    checked = 0
    for origin, direction in [
        ((-30.0, -20.0, 5.0), (1.0, 0.0, 0.0)),
        ((15.0, 30.0, 6.0), (0.0, -1.0, 0.0)),
        ((60.0, -10.0, 3.0), (-1.0, 0.0, 0.0)),
    ]:
        o, d = np.array(origin), np.array(direction)
        hit = field.cast(1, o, d[None, :], 0.0, 100.0)[0]
        assert np.isfinite(hit), origin
        first = None
        for t in np.arange(0.0, hit, 0.01):
            if field.sphere_touches(1, o + t * d, radius):
                first = t
                break
        assert first is not None, f"from {origin}: no touch before the surface at {hit:.2f} m"
        around = np.array([[a, b, c] for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if (a, b, c) != (0, 0, 0)], float)
        around /= np.linalg.norm(around, axis=1, keepdims=True)
        # a fan of 26 directions and a finer ring in the plane of the walk
        ring = np.array([[np.cos(a), np.sin(a), 0.0] for a in np.linspace(0, 2 * np.pi, 360, endpoint=False)])
        nearest = field.cast(1, o + first * d, np.vstack([around, ring]), 0.0, 5.0).min()
        print(
            f"from {origin}: ray meets the surface at {hit:.2f} m; the sphere ({radius} m) first touches at {first:.2f} m, "
            f"a surface {nearest:.3f} m from its centre"
        )
        assert first <= hit - radius + 0.02  # the walk steps 0.01 m
        assert nearest <= radius + cell * np.sqrt(3)
        checked += 1
    assert checked == 3


def test_courses_repeat_for_a_seed_and_bad_input_is_one_line():
    spec = clutter.ClutterSpec()
    a, start, goal = clutter.generate(spec, 3)
    b, start_b, goal_b = clutter.generate(spec, 3)
    assert np.array_equal(a, b) and np.array_equal(start, start_b) and np.array_equal(goal, goal_b)
    assert not np.array_equal(a, clutter.generate(spec, 4)[0])
    expected = round(spec.density * (spec.length_m - 2 * spec.clear_m) * spec.width_m) + 2  # + the side walls
    assert len(a) == expected
    field = ObstacleField(1, 0.4)
    field.set(0, a)
    for p in (start, goal):  # the start and the goal are clear of the vehicle's sphere
        assert field.distance(0, p) > 0.4
    with pytest.raises(SimError, match="obstacle 0: a size is <= 0"):
        field.set(0, np.array([[0, 0, 0, 0, 0.0, 1, 1, 0]]))
    with pytest.raises(SimError, match="shape 2.0* is not 0"):
        field.set(0, np.array([[2, 0, 0, 0, 1, 1, 1, 0]]))
    with pytest.raises(SimError, match="environment 3 is not in 0..0"):
        field.set(3, a)
    with pytest.raises(SimError, match="density_m not known"):
        clutter.spec_from({"density_m": 1})
    with pytest.raises(SimError, match="horizontal_fov"):
        rs.FlightBatch("firefly", count=1).set_depth_camera(horizontal_fov=4.0)
    with pytest.raises(SimError, match="fewer|environments for 2 vehicles"):
        rs.FlightBatch("firefly", count=2).set_obstacles(ObstacleField(1, 1.0))


def test_navigate_clutter_is_a_gymnasium_vector_env():
    envs = gym.make_vec("RotorS/NavigateClutter-v0", num_envs=4, vectorization_mode="vector_entry_point")
    assert isinstance(envs.unwrapped, NavigateClutterEnv)
    obs, info = envs.reset(seed=5)
    assert obs in envs.observation_space
    first = envs.unwrapped.course_seeds.copy()
    # reset_mask: only vehicle 1 gets a new course
    envs.reset(options={"reset_mask": np.array([False, True, False, False])})
    seeds = envs.unwrapped.course_seeds
    assert seeds[1] != first[1] and np.array_equal(np.delete(seeds, 1), np.delete(first, 1))
    # a vehicle flown at full speed into what is ahead ends its episode with -10 and a new course at once
    envs.reset(seed=5)
    ended = np.zeros(4, dtype=bool)
    for _ in range(600):
        obs, reward, terminated, truncated, info = envs.step(np.tile([1.0, 0.0, 0.0, 0.0], (4, 1)))
        assert obs in envs.observation_space
        if terminated.any():
            i = np.flatnonzero(terminated)[0]
            assert info["_final_obs"][i] and info["final_info"]["_collided"][i]
            assert reward[i] <= -10.0 + 1.0
            ended[i] = True
            if ended.all():
                break
    assert ended.any()
    envs.close()


@pytest.mark.long
def test_scripted_baseline_reaches_the_goal_through_100_courses():
    env = NavigateClutterEnv(100, autoreset=False, step_after_end=True)
    rng = np.random.default_rng(0)
    results = {
        "free-direction baseline": fly_courses(env, FreeDirectionBaseline(env), seed=0),
        "random actions": fly_courses(env, lambda obs: rng.uniform(-1, 1, (env.num_envs, 4)), seed=0),
    }
    for name, counts in results.items():
        print(f"{name}: {counts} of 100 courses (seeds 0..99, density {env.course.density} per m^2)")
    assert results["random actions"]["goal"] == 0
    assert results["free-direction baseline"]["goal"] >= 80
