#!/usr/bin/env python3
"""The frame figure of docs/sensor_realism.md (S8): the hovering firefly's accelerometer (z, along the
rotors' axes) read at 1 kHz with rotorVibration on and its white noise off, the IMU rigid on the body
and on an example frame mode (f_n, zeta) with an example broadband thrust fluctuation s_T; beside it the
mode's transmissibility |T(f)|. The example values are illustrations, not defaults (the defaults are a
rigid frame and no broadband: no published measurement of RotorS' airframes).

    python3 scripts/plot_imu_frame_mode.py docs/sensor_realism_frame.png [f_n zeta s_T]
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from plot_imu_vibration import DT, hover_record, spectrum_axes


def transmissibility(f_n: float, zeta: float, f: np.ndarray) -> np.ndarray:
    # T(jw) = (w_n^2 + j 2 zeta w_n w) / (w_n^2 - w^2 + j 2 zeta w_n w)
    w_n, w = 2 * np.pi * f_n, 2 * np.pi * f
    return np.abs((w_n**2 + 2j * zeta * w_n * w) / (w_n**2 - w**2 + 2j * zeta * w_n * w))


def spectrum(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    window = np.hanning(len(x))
    return np.fft.rfftfreq(len(x), DT), 2.0 * np.abs(np.fft.rfft((x - x.mean()) * window)) / window.sum()


def main(out: str, f_n: float, zeta: float, s_t: float) -> int:
    rigid, rotor_hz = hover_record(axis="z")
    framed, _ = hover_record(axis="z", imu_frame_mode_frequency=f_n, imu_frame_mode_damping=zeta, imu_thrust_noise_density=s_t)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 3.6))
    for name, x, color in (
        ("IMU rigid on the body", rigid, "tab:blue"),
        (f"on a {f_n:.0f} Hz mode, zeta {zeta}, s_T {s_t} /sqrt(Hz)", framed, "tab:orange"),
    ):
        f, a = spectrum(x)
        left.semilogy(f[1:], a[1:], lw=0.7, color=color, label=name)
    spectrum_axes(left, rotor_hz, "hovering firefly, accelerometer z, 16 s at 1 kHz (ADIS16448 16-tap filter)")
    freqs = np.linspace(0.1, 500, 2000)
    right.semilogy(freqs, transmissibility(f_n, zeta, freqs), lw=1)
    right.axhline(1.0, color="grey", lw=0.5)
    right.axvline(rotor_hz, color="grey", lw=0.6)
    right.text(rotor_hz + 4, 0.3, f"rotors {rotor_hz:.1f} Hz", fontsize=8)
    right.set_xlabel("frequency [Hz]")
    right.set_ylabel("|T(f)|")
    right.set_title(f"the frame's mode: f_n {f_n:.0f} Hz, zeta {zeta} (base excitation)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(
        f"wrote {out}: rotors {rotor_hz:.2f} Hz, |T| there {transmissibility(f_n, zeta, np.array(rotor_hz)):.3f}, "
        f"accelerometer z std rigid {rigid.std():.4f}, on the mode {framed.std():.4f} m/s^2"
    )
    return 0


if __name__ == "__main__":
    args = sys.argv[1:]
    out = args[0] if args else "sensor_realism_frame.png"
    f_n, zeta, s_t = (float(v) for v in args[1:4]) if len(args) >= 4 else (100.0, 0.05, 0.01)
    sys.exit(main(out, f_n, zeta, s_t))
