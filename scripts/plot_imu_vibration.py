#!/usr/bin/env python3
"""The figure of docs/sensor_realism.md's IMU section: the hovering firefly's accelerometer (x) read at
1 kHz with rotorVibration on and its white noise off, beside the datasheet noise density as an
amplitude in the same bins, and the ADIS16448's 16-tap Bartlett response with the rotors' frequency.

    python3 scripts/plot_imu_vibration.py docs/sensor_realism_imu.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rotors_sim as rs

DT = 0.001


def hover_record(seconds: float = 16.0, axis: str = "x", **xacro) -> tuple[np.ndarray, float]:
    """The hovering firefly's accelerometer (one axis) at 1 kHz, vibration on, white noise off, and its rotors' Hz."""
    world = rs.World("basic", step_size=DT)
    world.spawn_mav(
        "firefly", random_seed=3, sensor_realism=True, imu_accelerometer_noise_density=0.0, imu_gyroscope_noise_density=0.0, **xacro
    )
    lee = rs.LeePositionController.for_mav("firefly")
    world.attach_controller("firefly", lee)
    lee.set_point([0.0, 0.0, 1.0])
    world.step(int(4.0 / DT))
    ax = []
    for _ in range(int(seconds / DT)):
        world.step()
        ax.append(getattr(world.message("/firefly/imu")[0].linear_acceleration, axis))
    rotor_hz = abs(world.message("/firefly/motor_speed/0")[0].data) / (2 * np.pi)
    return np.array(ax), rotor_hz


def spectrum_axes(ax, rotor_hz: float, title: str) -> None:
    """An accelerometer amplitude spectrum's axes: 0-500 Hz, the rotors' frequency marked."""
    ax.axvline(rotor_hz, color="grey", lw=0.6)
    ax.text(rotor_hz + 4, 3e-9, f"rotors {rotor_hz:.1f} Hz", fontsize=8)
    ax.set_xlim(0, 500)
    ax.set_ylim(1e-9, 0.3)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude [m/s^2]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="upper right")


def main(out: str) -> int:
    ax, rotor_hz = hover_record()
    window = np.hanning(len(ax))
    f = np.fft.rfftfreq(len(ax), DT)
    amplitude = 2.0 * np.abs(np.fft.rfft((ax - ax.mean()) * window)) / window.sum()
    # white noise of density N in these bins: rms amplitude 2 N sqrt(sum w^2 / dt) / sum w
    noise = 2.0 * 0.004 * np.sqrt((window**2).sum() / DT) / window.sum()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 3.6))
    left.semilogy(f[1:], amplitude[1:], lw=0.7, label="accelerometer x, vibration on, white noise off")
    left.axhline(noise, color="tab:red", ls="--", lw=1, label="ADIS16448 noise density 0.004 m/s^2/sqrt(Hz), these bins")
    spectrum_axes(left, rotor_hz, "hovering firefly, 16 s at 1 kHz")
    fs = 819.2
    freqs = np.linspace(0.1, fs / 2, 2000)
    x = np.pi * freqs / fs
    right.semilogy(freqs, (np.sin(16 * x) / (16 * np.sin(x))) ** 2, lw=1)
    right.axvline(rotor_hz, color="grey", lw=0.6)
    right.text(rotor_hz + 4, 2e-5, f"rotors {rotor_hz:.1f} Hz", fontsize=8)
    right.set_ylim(1e-5, 1.5)
    right.set_xlabel("frequency [Hz]")
    right.set_ylabel("|H(f)|")
    right.set_title("ADIS16448 Bartlett FIR, N = 16 at 819.2 SPS", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}: rotor {rotor_hz:.2f} Hz, peak {amplitude[(f > 40) & (f < 160)].max():.2e} m/s^2, noise bins {noise:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "sensor_realism_imu.png"))
