#!/usr/bin/env python3
"""Writes the power plant's concrete texture: cast concrete over 4 x 4 m, 1024 x 1024 texels (4 mm
each), seamless (it repeats on every face, mapped by world coordinates).

The image is ours, made from seeded noise, so it is reproducible bit for bit:
- mottling at every scale from 4 mm to 4 m: a Gaussian random field with a 1/f amplitude spectrum,
  built in the Fourier domain, hence periodic (no seam where the texture repeats);
- air pores of 1-3 mm radius, darker, with a lighter rim;
- the formwork: panel seams every 2 m across and 1 m up, and tie holes on a 0.5 m grid.

Usage: make_concrete_texture.py OUT.png
"""

import sys

import cv2
import numpy as np

TEXELS = 1024
METRES = 4.0
SEED = 20261125


def mottling(rng: np.random.Generator) -> np.ndarray:
    """Periodic noise of zero mean and unit standard deviation, amplitude ~ 1/f."""
    fx = np.fft.fftfreq(TEXELS)[:, None]
    fy = np.fft.fftfreq(TEXELS)[None, :]
    f = np.hypot(fx, fy)
    f[0, 0] = 1.0
    spectrum = (rng.normal(size=f.shape) + 1j * rng.normal(size=f.shape)) / f
    spectrum[0, 0] = 0.0
    field = np.real(np.fft.ifft2(spectrum))
    return (field - field.mean()) / field.std()


def disc(image: np.ndarray, row: float, col: float, radius: float, value: float, wrap: bool = True) -> None:
    """Darkens (value < 0) or lightens a soft disc, wrapped around the edges so the tile stays seamless."""
    r = int(np.ceil(radius + 2))
    rows = np.arange(int(row) - r, int(row) + r + 1)
    cols = np.arange(int(col) - r, int(col) + r + 1)
    d = np.hypot(rows[:, None] - row, cols[None, :] - col)
    weight = np.clip(radius + 0.5 - d, 0.0, 1.0)
    image[np.ix_(rows % TEXELS, cols % TEXELS)] += value * weight


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit("usage: make_concrete_texture.py OUT.png")
    rng = np.random.default_rng(SEED)
    texel_m = METRES / TEXELS
    grey = 0.62 + 0.11 * mottling(rng)
    # fine grain of the surface: uncorrelated from texel to texel, a little
    grey += 0.025 * rng.normal(size=grey.shape)
    # air pores: a rim a little lighter, the pore dark
    for _ in range(2500):
        row, col = rng.uniform(0, TEXELS, 2)
        radius = rng.uniform(0.001, 0.003) / texel_m
        disc(grey, row, col, radius + 1.0, +0.05)
        disc(grey, row, col, radius, -0.35)
    # formwork panel seams: 2 m across (u), 1 m up (v); two texels wide, darker
    for u in np.arange(0.0, METRES, 2.0):
        c = int(round(u / texel_m))
        grey[:, [c % TEXELS, (c + 1) % TEXELS]] -= 0.12
    for v in np.arange(0.0, METRES, 1.0):
        r = int(round(v / texel_m))
        grey[[r % TEXELS, (r + 1) % TEXELS], :] -= 0.12
    # tie holes, 25 mm across, on a 0.5 m grid set off the seams by 0.25 m
    for u in np.arange(0.25, METRES, 0.5):
        for v in np.arange(0.25, METRES, 0.5):
            disc(grey, v / texel_m, u / texel_m, 0.0125 / texel_m + 1.5, -0.08)
            disc(grey, v / texel_m, u / texel_m, 0.0125 / texel_m, -0.3)
    image = np.clip(np.round(255.0 * grey), 0, 255).astype(np.uint8)
    if not cv2.imwrite(sys.argv[1], image):
        sys.exit(f"make_concrete_texture.py: cannot write '{sys.argv[1]}'")
    print(f"{sys.argv[1]}: {TEXELS} x {TEXELS} texels over {METRES} x {METRES} m, mean {image.mean():.1f}")


if __name__ == "__main__":
    main()
