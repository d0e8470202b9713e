"""Lens distortion (Gazebo's <distortion>) against OpenCV: squares on a black wall, seen through a
barrel lens with its centre off the image centre and through a pincushion lens, appear where
cv2.projectPoints puts them with the same K and plumb_bob D (within 0.5 px).

The expected position of a square is the area-weighted centroid of its projected outline (a 40 x 40
grid of its points through projectPoints), so the lens' curvature across a square does not count as
error; the squares are turned in their plane so that no edge runs along a pixel row."""

import math

import cv2
import numpy as np
import pytest

import rotors_sim as rs

W, H, HFOV = 752, 480, 1.3962634
WALL_X_M = 3.0  # the wall of squares, ahead of the camera (world x)
SIDE_M = 0.1  # a square's side: about 15 px
TURN_RAD = 0.4  # each square turned about the viewing axis


def square_points_O(y_W: float, z_W: float, n: int) -> np.ndarray:
    """An n x n grid over the square centred at (WALL_X_M, y_W, z_W) (world, camera at the origin
    looking along x), in the camera's optical frame (x right = -y_W, y down = -z_W, z = x_W)."""
    s = (np.arange(n) + 0.5) / n - 0.5
    a, b = np.meshgrid(s * SIDE_M, s * SIDE_M, indexing="ij")
    c, d = math.cos(TURN_RAD), math.sin(TURN_RAD)
    dy, dz = c * a - d * b, d * a + c * b
    return np.stack([-(y_W + dy), -(z_W + dz), np.full_like(dy, WALL_X_M)], axis=-1)


def expected_centroid(y_W: float, z_W: float, K: np.ndarray, D: np.ndarray) -> np.ndarray:
    """Area-weighted centroid of the square's image: its grid projected by OpenCV, cell by cell."""
    n = 40
    pts = square_points_O(y_W, z_W, n)
    uv, _ = cv2.projectPoints(pts.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, D)
    uv = uv.reshape(n, n, 2)
    # each cell as the quad of four neighbouring samples: area by the shoelace formula
    p00, p10, p11, p01 = uv[:-1, :-1], uv[1:, :-1], uv[1:, 1:], uv[:-1, 1:]
    quad = np.stack([p00, p10, p11, p01])
    x, y = quad[..., 0], quad[..., 1]
    area = 0.5 * np.abs(np.sum(x * np.roll(y, -1, axis=0) - np.roll(x, -1, axis=0) * y, axis=0))
    centre = quad.mean(axis=0)
    return (centre * area[..., None]).sum(axis=(0, 1)) / area.sum()


def world_sdf(lens: str, squares: list[tuple[float, float]]) -> str:
    visuals = "".join(
        f"<visual name='s{i}'><pose>{WALL_X_M} {y} {z} {TURN_RAD} 0 0</pose><geometry><box><size>0.005 {SIDE_M} "
        f"{SIDE_M}</size></box></geometry><material><diffuse>1 1 1 1</diffuse></material></visual>"
        for i, (y, z) in enumerate(squares)
    )
    # unlit (ambient 1, no sun), black sky: a square is 255, the rest 0
    return f"""<?xml version='1.0'?><sdf version='1.6'><world name='lens'>
      <physics type='ode'><max_step_size>0.01</max_step_size></physics>
      <scene><ambient>1 1 1 1</ambient><background>0 0 0 1</background></scene>
      <light name='sun' type='directional'><diffuse>0 0 0 1</diffuse><direction>0 0 -1</direction></light>
      <model name='wall'><static>true</static><link name='link'>{visuals}</link></model>
      <model name='rig'><static>true</static><link name='link'>
        <sensor name='cam' type='camera'><update_rate>100</update_rate><camera name='cam'>
          <horizontal_fov>{HFOV}</horizontal_fov><image><width>{W}</width><height>{H}</height><format>L8</format>
          </image><clip><near>0.05</near><far>50</far></clip>{lens}</camera></sensor></link></model>
    </world></sdf>"""


def intrinsics(center: tuple[float, float]) -> np.ndarray:
    f = W / (2 * math.tan(HFOV / 2))
    return np.array([[f, 0, center[0] * W - 0.5], [0, f, center[1] * H - 0.5], [0, 0, 1]])


LENSES = {
    # name: (k1, k2, k3, p1, p2, center)
    "barrel, centre moved": (-0.25, 0.06, 0.0, 0.001, -0.002, (0.53, 0.46)),
    "pincushion": (0.12, 0.02, 0.0, -0.0015, 0.001, (0.5, 0.5)),
}


@pytest.mark.parametrize("name", list(LENSES))
def test_distorted_images_put_squares_where_opencv_projects(name):
    k1, k2, k3, p1, p2, center = LENSES[name]
    K = intrinsics(center)
    D = np.array([k1, k2, p1, p2, k3])  # plumb_bob / OpenCV order
    # a grid of squares over the wall; those whose image lies wholly inside the frame are checked
    grid = [(y, z) for y in np.arange(-5.0, 5.01, 0.45) for z in np.arange(-3.5, 3.51, 0.45)]
    inside = []
    for y, z in grid:
        outline, _ = cv2.projectPoints(square_points_O(y, z, 8).reshape(-1, 1, 3), np.zeros(3), np.zeros(3), K, D)
        outline = outline.reshape(-1, 2)
        if outline[:, 0].min() > 4 and outline[:, 0].max() < W - 5 and outline[:, 1].min() > 4 and outline[:, 1].max() < H - 5:
            inside.append((y, z))
    lens = (
        f"<distortion><k1>{k1}</k1><k2>{k2}</k2><k3>{k3}</k3><p1>{p1}</p1><p2>{p2}</p2>"
        f"<center>{center[0]} {center[1]}</center></distortion>"
    )
    world = rs.World(sdf=world_sdf(lens, inside))
    world.step()
    image = world.camera_image("rig", "cam").reshape(H, W).astype(np.float64)

    count, labels = cv2.connectedComponents((image > 8).astype(np.uint8))
    measured = []
    for label in range(1, count):
        vs, us = np.nonzero(labels == label)
        weights = image[vs, us]
        measured.append([np.dot(us, weights) / weights.sum(), np.dot(vs, weights) / weights.sum()])
    measured = np.array(measured)
    errors = []
    for y, z in inside:
        predicted = expected_centroid(y, z, K, D)
        errors.append(np.linalg.norm(measured - predicted, axis=1).min())
    errors = np.array(errors)
    moved = np.array(
        [np.linalg.norm(expected_centroid(y, z, K, D) - expected_centroid(y, z, intrinsics(center), np.zeros(5))) for y, z in inside]
    )
    print(
        f"{name}: {len(inside)} squares, {count - 1} blobs; the lens moves them up to {moved.max():.1f} px; "
        f"rendered vs cv2.projectPoints: median {np.median(errors):.3f} px, max {errors.max():.3f} px"
    )
    assert count - 1 == len(inside) and len(inside) > 50
    assert moved.max() > 20.0  # the lens matters
    assert errors.max() < 0.5


def test_lens_out_of_range_is_one_error_process_keeps_working():
    folding = "<distortion><k1>-0.9</k1><k2>0</k2><k3>0</k3><p1>0</p1><p2>0</p2></distortion>"
    with pytest.raises(rs.SimError, match=r"camera 'cam': distortion k1 -0\.9.*coefficients out of range") as e:
        rs.World(sdf=world_sdf(folding, [(0.0, 0.0)]))
    assert "\n" not in str(e.value)
    world = rs.World(sdf=world_sdf("", [(0.0, 0.0)]))  # the next world loads
    world.step()
    assert world.camera_image("rig", "cam").max() == 255
