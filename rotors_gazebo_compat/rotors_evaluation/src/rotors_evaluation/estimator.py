"""Estimator evaluation: an estimate (msf_core/odometry, msf_core/cov_core, msf_core/state_out)
against the simulator's ground truth (ground_truth/pose, ground_truth/twist, ground_truth/imu_bias)
from one flight bag. Errors use the filter's error state [dp, dv, dtheta (IMU frame), db_w, db_a]
(msf_updates/ekf/core_state.h); NEES = e^T P^-1 e is chi-square with 15 degrees of freedom for a
consistent filter."""

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rotors_evaluation.bag_data import BagError, FlightBag, _stamp

STATE_DOF = 15
# two-sided 95 % interval of chi-square with 15 degrees of freedom
NEES_BOUNDS_95 = (6.262, 27.488)


@dataclass
class Track:
    t: np.ndarray  # (N,)
    p: np.ndarray  # (N, 3) world
    q: np.ndarray  # (N, 4) w, x, y, z (world <- body)
    v: np.ndarray | None = None  # (N, 3) world

    def until(self, t_end: float) -> "Track":
        keep = self.t <= t_end
        return Track(self.t[keep], self.p[keep], self.q[keep], None if self.v is None else self.v[keep])


@dataclass
class EstimatorResult:
    bag: str
    start_time: float
    end_time: float
    position_rms: float  # [m]
    velocity_rms: float  # [m/s]
    attitude_rms_deg: float  # [deg]
    max_position_error: float  # [m]
    gyroscope_bias: dict[str, list[float]] = field(default_factory=dict)  # truth, estimate at end_time
    accelerometer_bias: dict[str, list[float]] = field(default_factory=dict)
    gyroscope_bias_relative_error: float = float("nan")
    accelerometer_bias_relative_error: float = float("nan")
    nees_mean: float = float("nan")
    nees_fraction_inside_95: float = float("nan")
    nees_samples: int = 0
    pose_gaps: list[list[float]] = field(default_factory=list)  # [begin, end] of pose outages > 0.5 s


def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product of (N, 4) w, x, y, z arrays."""
    aw, ax, ay, az = a.T
    bw, bx, by, bz = b.T
    return np.stack(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ],
        axis=1,
    )


def quat_log(q: np.ndarray) -> np.ndarray:
    """Rotation vectors of (N, 4) unit quaternions (shortest way round)."""
    q = np.where(q[:, :1] < 0, -q, q)
    s = np.linalg.norm(q[:, 1:], axis=1)
    angle = 2.0 * np.arctan2(s, q[:, 0])
    scale = np.where(s > 1e-12, angle / np.maximum(s, 1e-300), 2.0)
    return q[:, 1:] * scale[:, None]


def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """R(q) v for (N, 4) quaternions and (N, 3) vectors."""
    w, u = q[:, :1], q[:, 1:]
    return v + 2.0 * np.cross(u, np.cross(u, v) + w * v)


def _conj(q: np.ndarray) -> np.ndarray:
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def _read(bag: FlightBag, topic: str, fn):
    t, rows = [], []
    for msg, msgtype, t_ns in bag.messages(topic):
        t.append(_stamp(msg, t_ns))
        rows.append(fn(msg, msgtype))
    return np.array(t), rows


def _nearest(t_ref: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Indices into t_ref of the samples at times t (t_ref sorted)."""
    i = np.clip(np.searchsorted(t_ref, t), 1, len(t_ref) - 1)
    return np.where(np.abs(t_ref[i - 1] - t) <= np.abs(t_ref[i] - t), i - 1, i)


def load_tracks(path: Path, mav_name: str, estimate_topic: str):
    bag = FlightBag(path)
    try:
        truth_topic = bag.require(mav_name, "/ground_truth/pose", "ground truth pose")
        twist_topic = bag.require(mav_name, "/ground_truth/twist", "ground truth twist")
        est_topic = bag.require(mav_name, estimate_topic, "estimate")
        pose_xyzw = lambda m, _: [
            m.pose.position.x,
            m.pose.position.y,
            m.pose.position.z,
            m.pose.orientation.w,
            m.pose.orientation.x,
            m.pose.orientation.y,
            m.pose.orientation.z,
        ]
        t_gt, rows = _read(bag, truth_topic, pose_xyzw)
        if not len(t_gt):
            raise BagError(f"ground truth topic '{truth_topic}' has no messages")
        gt = np.array(rows)
        t_tw, tw = _read(bag, twist_topic, lambda m, _: [m.twist.linear.x, m.twist.linear.y, m.twist.linear.z])
        truth = Track(t_gt, gt[:, :3], gt[:, 3:], np.array(tw)[_nearest(t_tw, t_gt)])

        def odom(m, msgtype):
            if not msgtype.endswith("Odometry"):
                raise BagError(f"estimate topic '{est_topic}' has type {msgtype}; expected nav_msgs/Odometry")
            p, o, v = m.pose.pose.position, m.pose.pose.orientation, m.twist.twist.linear
            return [p.x, p.y, p.z, o.w, o.x, o.y, o.z, v.x, v.y, v.z]

        t_est, rows = _read(bag, est_topic, odom)
        if not len(t_est):
            raise BagError(f"estimate topic '{est_topic}' has no messages in bag '{bag.path.name}' (was the " f"estimator initialised?)")
        est = np.array(rows)
        # odometry twist is in the body frame (RotorS / MSF): v_W = R(q) v_B
        estimate = Track(t_est, est[:, :3], est[:, 3:7], rotate(est[:, 3:7], est[:, 7:10]))

        extras = {}
        for name, topic, fn in (
            ("cov", "/msf_core/cov_core", lambda m, _: np.array(m.data).reshape(m.rows, m.cols)),
            ("state", "/msf_core/state_out", lambda m, _: np.array(m.data)),
            (
                "bias",
                "/ground_truth/imu_bias",
                lambda m, _: [
                    m.gyroscope_bias.x,
                    m.gyroscope_bias.y,
                    m.gyroscope_bias.z,
                    m.accelerometer_bias.x,
                    m.accelerometer_bias.y,
                    m.accelerometer_bias.z,
                ],
            ),
            ("pose", "/odometry_sensor1/pose_with_covariance", lambda m, _: 0),
        ):
            found = bag.resolve(mav_name, topic)
            if found:
                t, rows = _read(bag, found, fn)
                extras[name] = (t, rows)
        end = bag.flight_end(mav_name)  # what was recorded after the simulation stopped for good is left out
        if end is not None:
            truth, estimate = truth.until(end.t), estimate.until(end.t)
            extras = {k: (t[t <= end.t], [r for r, keep in zip(rows, t <= end.t) if keep]) for k, (t, rows) in extras.items()}
        return truth, estimate, extras
    finally:
        bag.close()


def error_state(truth: Track, estimate: Track, idx: np.ndarray) -> np.ndarray:
    """(N, 9) [dp, dv, dtheta] of the estimate against truth samples truth[idx]."""
    dp = truth.p[idx] - estimate.p
    dv = truth.v[idx] - estimate.v
    dtheta = quat_log(quat_mul(_conj(estimate.q), truth.q[idx]))
    return np.hstack([dp, dv, dtheta])


def evaluate_estimator(
    path: Path, mav_name: str, estimate_topic: str = "/msf_core/odometry", begin: float | None = None, end: float | None = None, loaded=None
) -> EstimatorResult:
    """begin defaults to 5 s after the first estimate (convergence), end to the last one.
    `loaded`: the result of load_tracks, if the bag was read already."""
    truth, estimate, extras = loaded or load_tracks(Path(path), mav_name, estimate_topic)
    t0 = estimate.t[0] + 5.0 if begin is None else begin
    t1 = estimate.t[-1] if end is None else end
    idx = _nearest(truth.t, estimate.t)
    matched = np.abs(truth.t[idx] - estimate.t) < 1e-6  # same simulator step
    window = matched & (estimate.t >= t0) & (estimate.t <= t1)
    if not window.any():
        raise BagError(f"no estimate between {t0:.2f} s and {t1:.2f} s with ground truth at the same time")
    e = error_state(truth, estimate, idx)
    pos_err = np.linalg.norm(e[window, :3], axis=1)
    result = EstimatorResult(
        str(path),
        float(t0),
        float(t1),
        float(np.sqrt(np.mean(pos_err**2))),
        float(np.sqrt(np.mean(np.sum(e[window, 3:6] ** 2, axis=1)))),
        float(np.degrees(np.sqrt(np.mean(np.sum(e[window, 6:9] ** 2, axis=1))))),
        float(pos_err.max()),
    )
    if "pose" in extras and len(extras["pose"][0]) > 1:
        tp = extras["pose"][0]
        gaps = np.flatnonzero(np.diff(tp) > 0.5)
        result.pose_gaps = [[float(tp[i]), float(tp[i + 1])] for i in gaps]
    if "state" in extras and "bias" in extras:
        t_state, states = extras["state"]
        t_bias, biases = extras["bias"]
        k = int(np.searchsorted(t_state, t1, side="right")) - 1
        if k >= 0:
            b_true = np.array(biases)[_nearest(t_bias, np.array([t_state[k]]))[0]]
            s = states[k]  # MSF order: p(3) v(3) q(4) b_w(3) b_a(3) ...
            b_w, b_a = s[10:13], s[13:16]
            result.gyroscope_bias = {"truth": b_true[:3].tolist(), "estimate": list(map(float, b_w))}
            result.accelerometer_bias = {"truth": b_true[3:].tolist(), "estimate": list(map(float, b_a))}
            result.gyroscope_bias_relative_error = float(np.linalg.norm(b_w - b_true[:3]) / np.linalg.norm(b_true[:3]))
            result.accelerometer_bias_relative_error = float(np.linalg.norm(b_a - b_true[3:]) / np.linalg.norm(b_true[3:]))
    if "cov" in extras and "state" in extras and "bias" in extras:
        t, nees = _nees_series(truth, estimate, extras, idx, e)
        nees = nees[(t >= t0) & (t <= t1)]
        if nees.size:
            result.nees_mean, result.nees_samples = float(nees.mean()), int(nees.size)
            result.nees_fraction_inside_95 = float(np.mean((nees >= NEES_BOUNDS_95[0]) & (nees <= NEES_BOUNDS_95[1])))
    return result


def report(r: EstimatorResult, out=print) -> None:
    out(f"Estimator evaluated from {r.start_time:.2f} s to {r.end_time:.2f} s against ground truth")
    out(f"Estimator position RMS error: {r.position_rms:.3f} m (max {r.max_position_error:.3f} m)")
    out(f"Estimator velocity RMS error: {r.velocity_rms:.3f} m/s")
    out(f"Estimator attitude RMS error: {r.attitude_rms_deg:.2f} deg")
    if r.gyroscope_bias:
        fmt = lambda v: "(" + ", ".join(f"{x:+.4f}" for x in v) + ")"
        out(
            f"Gyroscope bias [rad/s]: truth {fmt(r.gyroscope_bias['truth'])}, estimate "
            f"{fmt(r.gyroscope_bias['estimate'])}, error {100 * r.gyroscope_bias_relative_error:.1f} %"
        )
        out(
            f"Accelerometer bias [m/s^2]: truth {fmt(r.accelerometer_bias['truth'])}, estimate "
            f"{fmt(r.accelerometer_bias['estimate'])}, error {100 * r.accelerometer_bias_relative_error:.1f} %"
        )
    if r.nees_samples:
        out(
            f"NEES (15 states): mean {r.nees_mean:.2f}, {100 * r.nees_fraction_inside_95:.1f} % of {r.nees_samples} "
            f"samples inside the 95 % chi-square bounds [{NEES_BOUNDS_95[0]:.2f}, {NEES_BOUNDS_95[1]:.2f}]"
        )
    for begin, end in r.pose_gaps:
        out(f"Pose outage from {begin:.2f} s to {end:.2f} s ({end - begin:.2f} s)")


def _nees_series(truth: Track, estimate: Track, extras, idx: np.ndarray, e9: np.ndarray) -> tuple:
    """(t, NEES) at every estimate that has covariance, state and bias truth at the same stamp.
    idx, e9: the matched truth samples and error_state() of the estimate against them."""
    t_cov, covs = extras["cov"]
    t_state, states = extras["state"]
    t_bias, biases = extras["bias"]
    states, biases = np.array(states), np.array(biases)
    ts, values = [], []
    kc, ks, kb = _nearest(t_cov, estimate.t), _nearest(t_state, estimate.t), _nearest(t_bias, estimate.t)
    for i, t in enumerate(estimate.t):
        if max(abs(t_cov[kc[i]] - t), abs(t_state[ks[i]] - t), abs(t_bias[kb[i]] - t), abs(truth.t[idx[i]] - t)) > 1e-6:
            continue
        e = np.concatenate([e9[i], biases[kb[i], :3] - states[ks[i], 10:13], biases[kb[i], 3:] - states[ks[i], 13:16]])
        ts.append(t)
        values.append(float(e @ np.linalg.solve(covs[kc[i]], e)))
    return np.array(ts), np.array(values)


def plot_estimator(truth: Track, estimate: Track, extras, out_dir: Path, prefix: str, save: bool) -> list[Path]:
    from rotors_evaluation.plots import _finish, plt  # matplotlib only when plotting

    saved: list[Path] = []
    idx = _nearest(truth.t, estimate.t)
    e = error_state(truth, estimate, idx)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for k, label in enumerate("xyz"):
        ax.plot(estimate.t, e[:, k], label=f"{label} error", color=f"C{k}", linewidth=0.8)
    if "cov" in extras:
        t_cov, covs = extras["cov"]
        sigma = np.sqrt(np.array([np.diag(c)[:3] for c in covs]))
        for k in range(3):
            ax.plot(t_cov, 3 * sigma[:, k], ":", color=f"C{k}", linewidth=0.8)
            ax.plot(t_cov, -3 * sigma[:, k], ":", color=f"C{k}", linewidth=0.8)
    ax.set_ylim(-0.1, 0.1)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("ground truth - estimate [m]")
    ax.set_title("Estimator position error (dotted: 3 sigma of the filter)")
    ax.legend()
    ax.grid(True)
    _finish(fig, "estimator_position_error", out_dir, prefix, save, saved)
    if "state" in extras and "bias" in extras:
        t_state, states = extras["state"][0], np.array(extras["state"][1])
        t_bias, biases = extras["bias"][0], np.array(extras["bias"][1])
        fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
        for row, (cols, name, unit) in enumerate(
            ((slice(10, 13), "gyroscope bias", "rad/s"), (slice(13, 16), "accelerometer bias", "m/s^2"))
        ):
            truth_cols = slice(0, 3) if row == 0 else slice(3, 6)
            for k, label in enumerate("xyz"):
                axes[row].plot(t_state, states[:, cols][:, k], color=f"C{k}", label=f"{label} estimate")
                axes[row].plot(t_bias, biases[:, truth_cols][:, k], "--", color=f"C{k}", label=f"{label} truth")
            axes[row].set_ylabel(f"{name} [{unit}]")
            axes[row].grid(True)
        axes[0].legend(ncol=3, fontsize="small")
        axes[1].set_xlabel("time [s]")
        axes[0].set_title("IMU biases: estimate (solid) and simulated truth (dashed)")
        _finish(fig, "estimator_biases", out_dir, prefix, save, saved)
        if "cov" in extras:
            t, nees = _nees_series(truth, estimate, extras, idx, e)
            fig, ax = plt.subplots(figsize=(8, 4.5))
            ax.semilogy(t, nees, linewidth=0.6, label="NEES")
            for b in NEES_BOUNDS_95:
                ax.axhline(b, color="r", linestyle="--", linewidth=0.8)
            ax.set_xlabel("time [s]")
            ax.set_ylabel("NEES (15 states)")
            ax.set_title("Filter consistency (dashed: 95 % chi-square bounds)")
            ax.grid(True)
            _finish(fig, "estimator_nees", out_dir, prefix, save, saved)
    return saved


def main(argv=None) -> int:
    """estimator_eval.py: the estimate against ground truth from one bag (see the module doc)."""
    import argparse
    import json
    import sys
    from dataclasses import asdict

    from rotors_evaluation.options import str2bool

    p = argparse.ArgumentParser(
        description="Evaluate a state estimator's output against the simulator's ground " "truth (estimator RMS, bias estimates, NEES)."
    )
    p.add_argument("-b", "--bagfile", required=True, type=Path)
    p.add_argument("-n", "--mav_name", default="")
    p.add_argument("--estimate_topic", default="/msf_core/odometry", help="nav_msgs/Odometry of the estimator")
    p.add_argument("--begin_time", type=float, help="[s] default: 5 s after the first estimate")
    p.add_argument("-e", "--end_time", type=float, help="[s] default: the last estimate")
    p.add_argument("-s", "--save_plots", nargs="?", const=True, default=False, type=str2bool)
    p.add_argument("-d", "--plot", nargs="?", const=True, default=True, type=str2bool)
    p.add_argument("--prefix", default="")
    p.add_argument("--plot_dir", type=Path, default=Path("."))
    p.add_argument("--json", type=Path, help="also write the result as JSON here ('-' = stdout)")
    a = p.parse_args(argv)
    try:
        loaded = load_tracks(a.bagfile, a.mav_name, a.estimate_topic)
        result = evaluate_estimator(a.bagfile, a.mav_name, a.estimate_topic, a.begin_time, a.end_time, loaded)
    except BagError as e:
        print(f"estimator_eval.py: {e}", file=sys.stderr)
        return 1
    report(result)
    if a.save_plots or a.plot:
        saved = plot_estimator(*loaded, a.plot_dir, a.prefix, a.save_plots)
        if a.plot and not a.save_plots:
            from rotors_evaluation.plots import plt

            if plt.get_backend().lower() != "agg":
                plt.show()
        if saved:
            print("Plots saved: " + ", ".join(str(s) for s in saved))
    if a.json:
        text = json.dumps(asdict(result), indent=2, allow_nan=True)
        print(text) if str(a.json) == "-" else a.json.write_text(text + "\n")
    return 0
