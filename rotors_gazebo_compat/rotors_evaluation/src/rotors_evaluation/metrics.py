"""Flight metrics of RotorS' evaluation: RMS errors, settling time, collisions and scores."""

from collections.abc import Sequence

import numpy as np

from rotors_evaluation.bag_data import Series


def rms_error(series: Series, setpoint: np.ndarray) -> float:
    """sqrt(mean_i |x_i - x_sp|^2) over the samples of the series; nan if empty."""
    if series.t.size == 0:
        return float("nan")
    return float(np.sqrt(np.mean(np.sum((series.values - setpoint) ** 2, axis=1))))


def settling_time(series: Series, setpoint: np.ndarray, radius: float, min_settled_time: float, start: float) -> float | None:
    """First time after `start` from which the position error stays <= radius for at least
    min_settled_time, measured from `start`; None if it never settles in the series."""
    inside = np.linalg.norm(series.values - setpoint, axis=1) <= radius
    t = series.t
    entry = None
    for ti, ok in zip(t, inside):
        if ti < start:
            continue
        if ok and entry is None:
            entry = ti
        elif not ok:
            entry = None
        if entry is not None and ti - entry >= min_settled_time:
            return float(entry - start)
    return None


def collisions_after(collision_times: np.ndarray, start: float, end: float = float("inf")) -> np.ndarray:
    """Collisions in [start, end] (end: the --end_time of the evaluation)."""
    return collision_times[(collision_times >= start) & (collision_times <= end)]


def get_score(x: float, max_value: float, scores: Sequence[float]) -> float:
    """RotorS' scoring: scores[0] if x > max, [1] if > max/2, [2] if > max/10, else [3]."""
    if not np.isfinite(x) or x > max_value:
        return scores[0]
    if x > 0.5 * max_value:
        return scores[1]
    if x > 0.1 * max_value:
        return scores[2]
    return scores[3]
