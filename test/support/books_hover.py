"""The book's hovering figure (section 3.6) as a check on a bag of the hovering example: the set
point (0, 0, 1), 0.040 m position RMS over the 10 s from 5 s after it, and no rotation."""

from pathlib import Path

import numpy as np

from rotors_evaluation.bag_data import load_flight
from rotors_evaluation.metrics import rms_error


def assert_hovers_like_the_book(bag: Path, label: str) -> float:
    """Asserts the figure on the firefly's bag and returns the position RMS [m]."""
    data = load_flight(bag, "firefly", "/ground_truth/pose", "/ground_truth/twist", "/command/trajectory", "/wrench", "/motor_speed")
    wp = data.waypoints[0]
    assert np.allclose(wp.position, [0, 0, 1])
    pos_rms = rms_error(data.position.window(wp.t + 5, wp.t + 15), wp.position)
    print(f"{label}: position RMS {pos_rms:.4f} m over 10 s (book: 0.040 m)")
    assert abs(pos_rms - 0.040) <= 0.005, pos_rms
    assert rms_error(data.angular_velocity.window(wp.t + 5, wp.t + 15), np.zeros(3)) < 1e-3
    return pos_rms
