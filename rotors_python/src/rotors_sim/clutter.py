"""Seeded clutter for the batched flight engine's obstacle fields (rotors_sim._engine.ObstacleField).

A course along x from a start at x = 1 m to a goal at x = length - 1 m, between two side walls:
boxes (turned about z) and upright cylinders standing on the ground, placed uniformly over the
floor between the two clear ends, `density` of them per square metre; optionally walls across the
course, each with a door at a random place. The same seed gives the same course.

    spec = ClutterSpec(density=0.1)
    obstacles, start, goal = generate(spec, seed=7)        # rows for ObstacleField.set
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from rotors_sim._engine import ObstacleField, SimError

BOX, CYLINDER = 0.0, 1.0
WALL_HALF_THICKNESS_M = 0.1


@dataclass(frozen=True)
class ClutterSpec:
    """A course's shape and what stands in it (lengths in metres)."""

    length_m: float = 20.0  # along x
    width_m: float = 8.0  # between the side walls' inner faces
    height_m: float = 4.0  # every obstacle stands from the ground to this height
    density: float = 0.1  # obstacles per m^2 of the floor between the clear ends
    box_fraction: float = 0.5  # the rest are cylinders
    box_side_m: tuple[float, float] = (0.4, 1.2)  # a box's side, uniform
    cylinder_radius_m: tuple[float, float] = (0.15, 0.5)
    clear_m: float = 2.5  # no obstacle within this of either end
    flight_height_m: float = 1.5  # the start's and the goal's height
    side_walls: bool = True
    cross_walls: int = 0  # walls across the course, each with a door
    door_width_m: float = 1.5

    def check(self) -> ClutterSpec:
        """Itself, or SimError naming the value that makes no course."""
        for f in fields(self):
            v = getattr(self, f.name)
            values = v if isinstance(v, tuple) else (v,)
            if not all(np.isfinite(float(x)) for x in values):
                raise SimError(f"ClutterSpec.{f.name} = {v} is not finite")
        if not (self.length_m > 2 * self.clear_m and self.width_m > 1.0 and self.height_m > self.flight_height_m > 0):
            raise SimError(
                f"ClutterSpec: need length_m > 2 clear_m ({self.length_m} vs {self.clear_m}), width_m > 1 ({self.width_m}) "
                f"and height_m > flight_height_m > 0 ({self.height_m}, {self.flight_height_m})"
            )
        if not (self.density >= 0 and 0 <= self.box_fraction <= 1 and self.cross_walls >= 0):
            raise SimError("ClutterSpec: need density >= 0, 0 <= box_fraction <= 1, cross_walls >= 0")
        for name in ("box_side_m", "cylinder_radius_m"):
            lo, hi = getattr(self, name)
            if not 0 < lo <= hi:
                raise SimError(f"ClutterSpec.{name} = ({lo}, {hi}) must be 0 < low <= high")
        if not 0 < self.door_width_m < self.width_m:
            raise SimError(f"ClutterSpec.door_width_m = {self.door_width_m} must be in (0, width_m)")
        return self


def spec_from(values: ClutterSpec | dict[str, Any] | None) -> ClutterSpec:
    """A ClutterSpec from a spec or a dict of its fields (unknown names refused)."""
    if values is None:
        return ClutterSpec().check()
    if isinstance(values, ClutterSpec):
        return values.check()
    known = {f.name for f in fields(ClutterSpec)}
    unknown = set(values) - known
    if unknown:
        raise SimError(f"clutter: {', '.join(sorted(unknown))} not known; use: {', '.join(sorted(known))}")
    converted = {k: tuple(v) if isinstance(v, (list, tuple)) else v for k, v in values.items()}
    return replace(ClutterSpec(), **converted).check()


def _box(x: float, y: float, hx: float, hy: float, h: float, yaw: float = 0.0) -> list[float]:
    return [BOX, x, y, h / 2.0, hx, hy, h / 2.0, yaw]


def generate(spec: ClutterSpec, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The obstacles of course `seed` (K x 8 rows: shape, x, y, z, half extents, yaw), its start
    and its goal (x, y, z of the vehicle's model frame)."""
    rng = np.random.default_rng(seed)
    half_w, h = spec.width_m / 2.0, spec.height_m
    margin = 1.0  # the start and the goal stay this far from the side walls
    start = np.array([1.0, rng.uniform(-half_w + margin, half_w - margin), spec.flight_height_m])
    goal = np.array([spec.length_m - 1.0, rng.uniform(-half_w + margin, half_w - margin), spec.flight_height_m])
    rows: list[list[float]] = []
    x0, x1 = spec.clear_m, spec.length_m - spec.clear_m
    count = int(round(spec.density * (x1 - x0) * spec.width_m))
    for _ in range(count):
        x, y = rng.uniform(x0, x1), rng.uniform(-half_w, half_w)
        if rng.uniform() < spec.box_fraction:
            a, b = rng.uniform(*spec.box_side_m, size=2)
            rows.append(_box(x, y, a / 2.0, b / 2.0, h, rng.uniform(0.0, np.pi)))
        else:
            r = rng.uniform(*spec.cylinder_radius_m)
            rows.append([CYLINDER, x, y, h / 2.0, r, r, h / 2.0, 0.0])
    for k in range(spec.cross_walls):
        x = x0 + (k + 1) * (x1 - x0) / (spec.cross_walls + 1)
        door = rng.uniform(-half_w + spec.door_width_m / 2.0, half_w - spec.door_width_m / 2.0)
        lo, hi = door - spec.door_width_m / 2.0, door + spec.door_width_m / 2.0
        for a, b in ((-half_w, lo), (hi, half_w)):
            if b - a > 1e-6:
                rows.append(_box(x, (a + b) / 2.0, WALL_HALF_THICKNESS_M, (b - a) / 2.0, h))
    if spec.side_walls:
        for side in (-1.0, 1.0):
            rows.append(
                _box(spec.length_m / 2.0, side * (half_w + WALL_HALF_THICKNESS_M), spec.length_m / 2.0 + 1.0, WALL_HALF_THICKNESS_M, h)
            )
    return np.array(rows, dtype=float).reshape(-1, 8), start, goal


def field(count: int, max_sphere_radius_m: float) -> ObstacleField:
    """An empty obstacle field of `count` environments for spheres up to the given radius."""
    return ObstacleField(int(count), float(max_sphere_radius_m))


def add_world(
    obstacles: ObstacleField, world: str, center: Any = (0.0, 0.0, 10.0), lengths: Any = (100.0, 100.0, 20.0), leaf_m: float = 0.25
) -> Any:
    """Every environment of `obstacles` also holds the world `world` (a name as World takes it:
    "powerplant", "warehouse", ...): its visuals for the depth rays and its static collisions'
    occupancy inside the box (center, lengths) at leaf_m for the collisions. Returns the World,
    which the field keeps alive."""
    from rotors_sim.world import World

    loaded = World(world)
    obstacles.set_world(loaded.engine, np.asarray(center, float), np.asarray(lengths, float), float(leaf_m))
    return loaded
