"""An IMU that feels the rotors (rotorVibration, docs/sensor_realism.md), flown in the full world:
the firefly hovering with sensor_realism on shows its rotors in the IMU's spectrum at the motor
model's own speed, through a frame's mode with that mode's transmissibility; motors off, the
spectrum is flat at the datasheet noise density; the batch refuses
a vehicle whose IMU vibrates. (The model's equations, the Bartlett filter and aliasing: the gtests in
rotors_plugins/test/test_imu_vibration_model.cpp.)"""

import numpy as np
import pytest

import rotors_sim as rs

DT = 0.001  # a 1 kHz reader: the rotors (about 86 Hz in hover) and their alias-free spectrum


def record_imu(world: rs.World, seconds: float, speeds: bool = True):
    acc, gyr, rotor_hz = [], [], []
    for k in range(int(round(seconds / DT))):
        world.step()
        m = world.message("/firefly/imu")[0]
        acc.append([m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z])
        gyr.append([m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z])
        if speeds and k % 50 == 0:
            rotor_hz.append([abs(world.message(f"/firefly/motor_speed/{i}")[0].data) / (2 * np.pi) for i in range(6)])
    return np.array(acc), np.array(gyr), np.array(rotor_hz)


def amplitude_spectrum(x: np.ndarray):
    """Amplitude [signal units] per frequency of a Hann-windowed record."""
    window = np.hanning(len(x))
    return np.fft.rfftfreq(len(x), DT), 2.0 * np.abs(np.fft.rfft((x - x.mean()) * window)) / window.sum()


def hovering_firefly(**xacro) -> rs.World:
    world = rs.World("basic", step_size=DT)
    world.spawn_mav("firefly", random_seed=3, sensor_realism=True, **xacro)
    lee = rs.LeePositionController.for_mav("firefly")
    world.attach_controller("firefly", lee)
    lee.set_point([0.0, 0.0, 1.0])
    world.step(int(4.0 / DT))  # take off and settle
    return world


def test_hovering_imu_shows_each_rotor_at_the_motor_models_speed():
    # white noise off (xacro args), so the rotors stand alone above the flight's own motion
    world = hovering_firefly(imu_accelerometer_noise_density=0.0, imu_gyroscope_noise_density=0.0)
    acc, gyr, rotor_hz = record_imu(world, 16.0)
    rotor_hz = rotor_hz.mean(axis=0)
    print("rotor frequencies from motor_speed/<N> [Hz]:", rotor_hz.round(2))
    for name, x in (("accelerometer x", acc[:, 0]), ("accelerometer y", acc[:, 1]), ("gyroscope z", gyr[:, 2])):
        f, a = amplitude_spectrum(x)
        band = (f > 40.0) & (f < 160.0)
        peak = f[band][np.argmax(a[band])]
        floor = np.median(a[band])
        print(f"{name}: peak {peak:.2f} Hz, {a[band].max():.3g} ({a[band].max() / floor:.0f} x the band's median)")
        for f_rotor in rotor_hz:
            assert abs(peak - f_rotor) < 1.0, f"{name}: peak at {peak:.2f} Hz, rotor at {f_rotor:.2f} Hz"
        assert a[band].max() > 20.0 * floor


def test_motors_off_the_spectrum_is_flat_at_the_datasheet_density():
    # on the ground with motors off and rotorVibration on: the accelerometer's amplitude spectrum of
    # white noise with density N (discrete sigma = N / sqrt(dt)) has mean level N sqrt(pi / T) ...
    # checked here as a power spectral density: mean |X|^2 dt / n = N^2 in every band
    world = rs.World("basic", step_size=DT)
    world.spawn_mav("firefly", random_seed=5, sensor_realism=True)
    world.step(500)
    acc, gyr, _ = record_imu(world, 20.0, speeds=False)
    n = len(acc)
    f = np.fft.rfftfreq(n, DT)
    for name, x, density in (("accelerometer", acc[:, 0], 0.004), ("gyroscope", gyr[:, 0], 0.0003394)):
        psd = np.abs(np.fft.rfft(x - x.mean())) ** 2 * DT / n  # two-sided, per Hz
        levels = [psd[(f > lo) & (f < lo + 80.0)].mean() for lo in (20.0, 120.0, 220.0, 320.0, 400.0)]
        print(f"{name}: sqrt(PSD) by band {np.sqrt(levels).round(6)} (datasheet {density})")
        assert np.allclose(np.sqrt(levels), density, rtol=0.1)


def frame_transmissibility(f_n: float, zeta: float, f: np.ndarray) -> np.ndarray:
    """|T(j w)| of the base-excited mode, T = (w_n^2 + j 2 zeta w_n w) / (w_n^2 - w^2 + j 2 zeta w_n w)."""
    w_n, w = 2 * np.pi * f_n, 2 * np.pi * np.asarray(f)
    return np.abs((w_n**2 + 2j * zeta * w_n * w) / (w_n**2 - w**2 + 2j * zeta * w_n * w))


def test_a_frame_mode_passes_the_rotor_lines_with_its_transmissibility():
    # The same flight twice (the IMU does not feed Lee, so the rotors turn alike): the IMU rigid on the
    # body, then on a 100 Hz mode with zeta 0.05 (xacro args). The rotors' line in the accelerometer grows
    # by |T| at their frequency (about 3.6 at 86.5 Hz).
    f_n, zeta = 100.0, 0.05
    quiet = dict(imu_accelerometer_noise_density=0.0, imu_gyroscope_noise_density=0.0)
    lines = {}
    for name, xacro in (("rigid", quiet), ("mode", dict(quiet, imu_frame_mode_frequency=f_n, imu_frame_mode_damping=zeta))):
        acc, _, rotor_hz = record_imu(hovering_firefly(**xacro), 8.0)
        f, a = amplitude_spectrum(acc[:, 0])
        band = (f > 80.0) & (f < 92.0)  # the six rotors; the register read's image at 94 Hz left out
        lines[name] = np.sqrt(np.sum(a[band] ** 2))
        rotor_hz = rotor_hz.mean(axis=0)
    expected = np.sqrt(np.mean(frame_transmissibility(f_n, zeta, rotor_hz) ** 2))
    print(
        f"rotors at {rotor_hz.round(2)} Hz; accelerometer x line: rigid {lines['rigid']:.3g}, on the mode "
        f"{lines['mode']:.3g} m/s^2: x {lines['mode'] / lines['rigid']:.3f} (|T| {expected:.3f})"
    )
    assert lines["mode"] / lines["rigid"] == pytest.approx(expected, rel=0.1)


def test_frame_parameters_without_their_partner_are_refused_in_one_line():
    world = rs.World("basic", step_size=DT)
    with pytest.raises(rs.SimError, match="frameModeDamping = -1"):
        world.spawn_mav("firefly", random_seed=3, sensor_realism=True, imu_frame_mode_frequency=100.0)
    with pytest.raises(rs.SimError, match="rotorVibration is off"):
        world.spawn_mav("firefly", random_seed=3, imu_thrust_noise_density=0.01)


def test_the_batch_refuses_an_imu_that_vibrates():
    with pytest.raises(rs.SimError, match="rotorVibration on; the batch does not step rotor vibration"):
        rs.FlightBatch("firefly", 4, seeds=[1, 2, 3, 4], sensor_realism=True)
