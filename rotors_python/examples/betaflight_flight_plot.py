"""The real Betaflight firmware (its SITL, built by make setup) flying the iris from Python, plotted:
height, roll and pitch against the RC the pilot sends (the flight of test/test_betaflight_sitl.py).

    python rotors_python/examples/betaflight_flight_plot.py docs/betaflight_flight.png
"""

import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rotors_sim as rs  # noqa: E402
from rotors_sim.betaflight import BetaflightSitl, read_cli_file  # noqa: E402
from rotors_sim.paths import resource  # noqa: E402

DT = 0.002


def euler_deg(q):
    x, y, z, w = q
    return (
        np.degrees(np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))),
        np.degrees(np.arcsin(np.clip(2 * (w * y - z * x), -1, 1))),
    )


def main(out: str) -> None:
    world = rs.World("basic", step_size=DT)
    world.spawn_mav("iris", random_seed=5, enable_betaflight_interface=True)
    log, integral = [], 0.0

    def fly(seconds, z_ref=None, throttle=1000, roll=1500, pitch=1500, armed=True):
        nonlocal integral
        for _ in range(int(seconds / 0.02)):
            p, q, v, _ = world.link_state("iris")
            if z_ref is not None:
                err = z_ref - p[2]
                integral = float(np.clip(integral + err * 0.02, -2, 2))
                throttle = int(np.clip(1760 + 250 * err - 150 * v[2] + 60 * integral, 1000, 2000))
            world.set_rc("iris", [roll, pitch, throttle, 1500, 2000 if armed else 1000, 1800])
            world.step(10)
            log.append((world.time, p[2], *euler_deg(q), throttle, roll, pitch, armed))

    world.set_rc("iris", [1500, 1500, 1000, 1500, 1000, 1800])
    # the lockstep firmware (the default): it answers every state from the first, no waiting
    with BetaflightSitl(tempfile.mkdtemp(), read_cli_file(resource("betaflight_iris.cli"))):
        fly(6.0, armed=False)
        fly(1.0)
        fly(8.0, z_ref=1.5)
        fly(2.0, z_ref=1.5, roll=1600)
        fly(2.0, z_ref=1.5, pitch=1600)
        fly(2.0, z_ref=1.5)
        for z_ref in (1.0, 0.5, 0.1):  # down in steps, then the throttle closed on the ground
            fly(2.0, z_ref=z_ref)
        fly(1.0)
        fly(1.0, armed=False)
    t, z, roll, pitch, thr, rc_roll, rc_pitch, armed = np.array(log, dtype=float).T
    fig, ax = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
    ax[0].plot(t, z, label="height (ground truth)")
    ax[0].fill_between(t, 0, 2.5, where=armed > 0, color="0.9", label="armed (AUX1)")
    ax[0].set_ylabel("z [m]")
    ax[0].legend(loc="upper right")
    ax[1].plot(t, roll, label="roll")
    ax[1].plot(t, pitch, label="pitch (nose down +)")
    ax[1].fill_between(t, -2, 6, where=rc_roll > 1500, color="C0", alpha=0.15, label="roll stick at 1600 us")
    ax[1].fill_between(t, -2, 6, where=rc_pitch > 1500, color="C1", alpha=0.15, label="pitch stick at 1600 us")
    ax[1].set_ylabel("angle [deg]")
    ax[1].legend(loc="upper right", fontsize=8)
    ax[2].plot(t, thr, color="C2")
    ax[2].set_ylabel("throttle [us]")
    ax[2].set_xlabel("sim time [s]")
    fig.suptitle("Betaflight 4.6 SITL (real firmware, angle mode) flying RotorS' iris")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "betaflight_flight.png")
