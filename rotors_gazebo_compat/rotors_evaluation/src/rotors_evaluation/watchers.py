"""Small ROS clients that watch a running simulation for the sweeps and the benchmark, run in a
process of their own (rospy initialises once per process):

    python -m rotors_evaluation.watchers NAME [ARGS...]

Each prints its result on its last line. clock: sim time at 10 Hz, forever; rtf [BEGIN END]: sim s
per wall s between two sim times (5, 25); vi: stereo pairs per sim s and sim s per wall s, images
subscribed; lidar TOPIC: clouds per sim s and sim s per wall s; swarm N END: sets N fireflies
hovering on a grid, unpauses, sim s per wall s from 2 s to END; airborne: 'ready', then the wall and
sim time at which the firefly's ground truth is 0.2 m up; soak_hover: the largest offset of the nine
swarm fireflies' heights from 1.04 m (the height at which the Lee controller holds their 1 m set
points: the hovering example's 0.040 m offset); not a 3-D error from each set point."""

import sys
import threading
import time
from collections.abc import Callable

import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty


class SimClock:
    """One /clock subscription for the whole run, polled on the wall clock (no busy loop, no
    re-subscribing: fast runs stay measurable)."""

    def __init__(self):
        self.t = -1.0
        self._sub = rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=1)

    def _on_clock(self, msg: Clock) -> None:
        self.t = msg.clock.to_sec()

    def wait_until(self, t_sim: float, limit_s: float = 300.0, poll_s: float = 0.005) -> tuple[float, float]:
        """The wall and sim time at which sim time t_sim was seen; exits naming the stuck time."""
        deadline = time.monotonic() + limit_s
        while self.t < t_sim:
            if time.monotonic() > deadline:
                sys.exit(f"sim time stuck at {self.t:.2f} s, waiting for {t_sim} s")
            time.sleep(poll_s)
        return time.monotonic(), self.t


def _init(name: str) -> None:
    rospy.init_node(name, anonymous=True, disable_signals=True)


def clock() -> None:
    _init("watch_clock")
    sim = SimClock()
    while True:
        print(f"{sim.t:.4f}", flush=True)
        time.sleep(0.1)


def rtf(begin: str = "5", end: str = "25") -> None:
    _init("watch_rtf")
    sim = SimClock()
    w0, s0 = sim.wait_until(float(begin))
    w1, s1 = sim.wait_until(float(end))
    print((s1 - s0) / (w1 - w0))


def _counting(topic: str, count: dict[str, int], key: str) -> rospy.Subscriber:
    """AnyMsg: received whole but not deserialised, so the watcher's Python costs little."""

    def on_message(_msg) -> None:
        count[key] += 1

    return rospy.Subscriber(topic, rospy.AnyMsg, on_message, queue_size=5)


def vi() -> None:
    _init("watch_vi")
    count = {"left": 0, "right": 0}
    subs = [_counting(f"/firefly/vi_sensor/{side}/image_raw", count, side) for side in count]  # noqa: F841
    sim = SimClock()
    w0, s0 = sim.wait_until(8.0, limit_s=120.0, poll_s=0.05)
    n0 = count["right"]
    w1, s1 = sim.wait_until(28.0, limit_s=120.0, poll_s=0.05)
    print((count["right"] - n0) / (s1 - s0), (s1 - s0) / (w1 - w0))


def lidar(topic: str) -> None:
    _init("watch_lidar")
    count = {"clouds": 0}
    sub = _counting(topic, count, "clouds")  # noqa: F841
    sim = SimClock()
    w0, s0 = sim.wait_until(3.0, limit_s=120.0)
    n0 = count["clouds"]
    w1, s1 = sim.wait_until(23.0, limit_s=300.0)
    print((count["clouds"] - n0) / (s1 - s0), (s1 - s0) / (w1 - w0))


def swarm(n: str, end: str) -> None:
    _init("watch_swarm")
    count = int(n)
    pubs = [rospy.Publisher(f"/firefly{i + 1}/command/pose", PoseStamped, queue_size=1, latch=True) for i in range(count)]
    deadline = time.monotonic() + 240
    while any(p.get_num_connections() == 0 for p in pubs) or len(rospy.get_published_topics()) < 3 * count:
        if time.monotonic() > deadline:
            sys.exit("controllers did not come up")
        time.sleep(0.2)
    for i, p in enumerate(pubs):
        m = PoseStamped()
        m.pose.position.x, m.pose.position.y, m.pose.position.z = (i % 5) * 2.0, (i // 5) * 2.0, 1.0
        m.pose.orientation.w = 1.0
        p.publish(m)
    time.sleep(2.0)
    sim = SimClock()
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    w0, s0 = sim.wait_until(2.0)
    w1, s1 = sim.wait_until(float(end))
    print((s1 - s0) / (w1 - w0))


def airborne() -> None:
    _init("watch_airborne")
    up = threading.Event()
    seen: dict[str, float] = {}

    def on_odometry(m: Odometry) -> None:
        if m.pose.pose.position.z > 0.2 and not up.is_set():
            seen.update(wall=time.monotonic(), sim=m.header.stamp.to_sec())
            up.set()

    sub = rospy.Subscriber("/firefly/ground_truth/odometry", Odometry, on_odometry, queue_size=1)  # noqa: F841
    print("ready", flush=True)
    print(seen["wall"], seen["sim"]) if up.wait(120) else print("nan nan")
    sys.stdout.flush()


def soak_hover() -> None:
    _init("watch_soak_hover")
    z = [rospy.wait_for_message(f"/firefly{i}/ground_truth/odometry", Odometry, timeout=30).pose.pose.position.z for i in range(1, 10)]
    print(max(abs(v - 1.04) for v in z))


WATCHERS: dict[str, Callable[..., None]] = {
    "clock": clock,
    "rtf": rtf,
    "vi": vi,
    "lidar": lidar,
    "swarm": swarm,
    "airborne": airborne,
    "soak_hover": soak_hover,
}


def command(name: str, *args: str) -> list[str]:
    """The command line that runs watcher `name` with `args` in this Python."""
    if name not in WATCHERS:
        raise ValueError(f"unknown watcher '{name}'; one of {', '.join(WATCHERS)}")
    return [sys.executable, "-m", "rotors_evaluation.watchers", name, *args]


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in WATCHERS:
        print(f"usage: python -m rotors_evaluation.watchers {{{','.join(WATCHERS)}}} [ARGS...]", file=sys.stderr)
        return 2
    WATCHERS[argv[0]](*argv[1:])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
