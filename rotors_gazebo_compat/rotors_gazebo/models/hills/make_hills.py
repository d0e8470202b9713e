#!/usr/bin/env python3
"""Writes materials/textures/hills.png, the heightmap of the hills model: 257 x 257 16-bit grey
pixels (2^8 + 1, as Gazebo requires) over 100 m x 100 m, 0-12 m (model.sdf's <size>).

Terrain: a flat valley around the spawn point rising to rolling hills,
    h(x, y) = 12 m * (1 - exp(-(r / 25 m)^2)) * (0.55 + 0.45 sin(x / 9 m) cos(y / 13 m)),
so h = 0 at the origin (the MAV starts on the ground) and h < 1 cm within 1 m of it.
Sample (row i, column j) lies at x = -50 + 100 j / 256, y = 50 - 100 i / 256 (north up)."""

from pathlib import Path

import numpy as np
from PIL import Image

N, SIZE_XY_M, SIZE_Z_M = 257, 100.0, 12.0


def height_m(x_m: np.ndarray, y_m: np.ndarray) -> np.ndarray:
    r_m = np.hypot(x_m, y_m)
    return SIZE_Z_M * (1.0 - np.exp(-((r_m / 25.0) ** 2))) * (0.55 + 0.45 * np.sin(x_m / 9.0) * np.cos(y_m / 13.0))


if __name__ == "__main__":
    column, row = np.meshgrid(np.arange(N), np.arange(N))
    x_m = -SIZE_XY_M / 2 + column * SIZE_XY_M / (N - 1)
    y_m = SIZE_XY_M / 2 - row * SIZE_XY_M / (N - 1)
    grey = np.round(height_m(x_m, y_m) / SIZE_Z_M * 65535.0).astype(np.uint16)
    out = Path(__file__).resolve().parent / "materials" / "textures" / "hills.png"
    Image.fromarray(grey).save(out)
    print(f"{out}: {N} x {N}, heights {grey.min() / 65535 * SIZE_Z_M:.2f}-{grey.max() / 65535 * SIZE_Z_M:.2f} m")
