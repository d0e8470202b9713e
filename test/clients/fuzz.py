"""The fuzzing of test_fuzz.py: random invalid and extreme messages, built from the message
definitions, on every topic and service of the running graph, while watching the hovering firefly
and the nodes' processes."""

import importlib
import math
import random
import time
from struct import error as struct_error

import genpy
import rosgraph
import rospy
import rosservice
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

from clients.nodes import alive, node_pid
from clients.waits import poll, wait_until

NAN, INF = float("nan"), float("inf")
INT_RANGES = {
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "byte": (-(2**7), 2**7 - 1),
    "char": (0, 255),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}
STRINGS = ["", "no_such_frame", "x" * 10000, "\u00e9\u00e8 world"]
SKIP_TOPICS = {"/clock", "/rosout"}
SKIP_SERVICES = ("/gazebo/pause_physics", "/gazebo/unpause_physics", "/gazebo/reset_world", "/gazebo/reset_simulation")


def msg_class(type_name):
    if type_name == "Header":
        type_name = "std_msgs/Header"
    pkg, name = type_name.split("/")
    return getattr(importlib.import_module(pkg + ".msg"), name)


def scalar(base, mode):
    if base in ("float64", "float32"):
        return random.choice([NAN, INF, -INF]) if mode == "invalid" else random.choice([1e30, -1e30, 1e-300, 0.0, random.gauss(0, 10)])
    if base in INT_RANGES:
        lo, hi = INT_RANGES[base]
        return random.choice([lo, hi, -1 if lo < 0 else hi])
    if base == "bool":
        return random.random() < 0.5
    if base == "string":
        return random.choice(STRINGS)
    if base == "time":
        return genpy.Time(random.choice([0, 1, 2**31 - 1]), 0)
    if base == "duration":
        return genpy.Duration(random.choice([-(2**31), -1, 0, 2**31 - 1]), 0)
    return fill(msg_class(base)(), mode)


def value(type_name, mode):
    if not type_name.endswith("]"):
        return scalar(type_name, mode)
    base, size = type_name[: type_name.index("[")], type_name[type_name.index("[") + 1 : -1]
    n = int(size) if size else random.choice([0, 1, 1000] if base in INT_RANGES or base.startswith("float") else [0, 1, 3, 50])
    if base in ("uint8", "char"):
        return bytes(random.getrandbits(8) for _ in range(n))
    return [scalar(base, mode) for _ in range(n)]


def fill(msg, mode):
    for name, type_name in zip(msg.__slots__, msg._slot_types):
        setattr(msg, name, value(type_name, mode))
    if mode == "invalid" and msg._type == "geometry_msgs/Quaternion" and random.random() < 0.3:
        msg.x = msg.y = msg.z = msg.w = 0.0  # the zero quaternion
    return msg


def fuzz_every_input(log_path: str, watched: list) -> dict:
    """Fuzzes every subscribed topic (but /clock and /rosout) and every service (but the Empty ones
    that pause, unpause and reset, and the loggers'), counting the launch log's lines (log_path)
    meanwhile and watching the nodes `watched`: a row per input, and the states sampled."""
    random.seed(14)
    master = rosgraph.Master("/pytest_client")
    log = open(log_path, errors="replace")

    state = {"p": None, "finite": True, "samples": 0}

    def on_odom(m):
        p, q = m.pose.pose.position, m.pose.pose.orientation
        values = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, m.twist.twist.linear.x, m.twist.twist.angular.z]
        state["finite"] = state["finite"] and all(math.isfinite(v) for v in values)
        state["p"] = (p.x, p.y, p.z)
        state["samples"] += 1

    rospy.Subscriber("/firefly/ground_truth/odometry", Odometry, on_odom, queue_size=1)
    set_point = rospy.Publisher("/firefly/command/pose", PoseStamped, queue_size=1, latch=True)

    def send_set_point():
        cmd = PoseStamped()
        cmd.pose.position.z = 1.0
        cmd.pose.orientation.w = 1.0
        set_point.publish(cmd)

    def log_lines():
        return len(log.readlines())

    wait_until(lambda: state["p"] is not None, 90, "a ground-truth pose")
    hover = state["p"]
    nodes = {n: node_pid(n) for n in watched}
    _, subscribers, services = master.getSystemState()
    types = dict(master.getTopicTypes())
    targets = sorted(
        (t, sorted(n for n in subs if not n.startswith(("/pytest_client", "/fuzz")))) for t, subs in subscribers if t not in SKIP_TOPICS
    )
    targets = [(t, subs) for t, subs in targets if subs]
    rows = []

    def fuzz_topic(topic, cls, mode, period_s=1.0, rate_hz=100.0):
        pub = rospy.Publisher(topic, cls, queue_size=10)
        poll(lambda: pub.get_num_connections() > 0, 3.0, 0.02)
        log_lines()  # skip what came before
        sent, worst = 0, 0.0
        end = time.monotonic() + period_s
        while time.monotonic() < end:
            try:
                pub.publish(fill(cls(), mode))
                sent += 1
            except (genpy.SerializationError, struct_error, ValueError, TypeError, OverflowError):
                pass  # not representable on the wire: nothing is sent
            worst = max(worst, math.dist(state["p"], hover))
            time.sleep(1.0 / rate_hz)
        time.sleep(0.3)
        worst = max(worst, math.dist(state["p"], hover))
        pub.unregister()
        return sent, log_lines(), worst

    for topic, subs in targets:
        cls = msg_class(types[topic])
        row = {"name": topic, "type": types[topic], "receivers": " ".join(subs)}
        state["finite"] = True
        row["invalid"], row["invalid_log_lines"], row["invalid_offset"] = fuzz_topic(topic, cls, "invalid")
        row["extreme"], row["extreme_log_lines"], _ = fuzz_topic(topic, cls, "extreme")
        row["finite"] = state["finite"]
        row["crashed"] = [n for n, p in nodes.items() if not alive(p)]
        # extreme inputs may be valid commands: send the set point again; the MAV must come back
        send_set_point()
        deadline = time.monotonic() + 12.0
        while math.dist(state["p"], hover) > 0.05 and time.monotonic() < deadline:
            time.sleep(0.05)
        row["recovered"] = math.dist(state["p"], hover) <= 0.05
        if not row["recovered"]:
            rospy.ServiceProxy("/gazebo/reset_world", Empty)()
            send_set_point()
            time.sleep(8.0)
        rows.append(row)

    for name, _providers in sorted(services):
        if name.endswith(("/get_loggers", "/set_logger_level")) or name in SKIP_SERVICES:
            continue
        srv = rosservice.get_service_class_by_name(name)
        row = {"name": name, "type": srv._type, "receivers": " ".join(_providers)}
        state["finite"] = True
        log_lines()
        calls, refused, worst = 0, 0, 0.0
        proxy = rospy.ServiceProxy(name, srv)
        for _ in range(20):
            request = fill(srv._request_class(), "invalid")
            try:
                response = proxy(request)
                calls += 1
                if getattr(response, "success", True) is False:
                    refused += 1
            except rospy.ServiceException:
                calls += 1
                refused += 1
            except (genpy.SerializationError, struct_error, ValueError, TypeError, OverflowError):
                pass
            worst = max(worst, math.dist(state["p"], hover))
        time.sleep(0.3)
        row.update(
            invalid=calls,
            invalid_log_lines=log_lines(),
            invalid_offset=worst,
            extreme=0,
            extreme_log_lines=0,
            finite=state["finite"],
            recovered=True,
            crashed=[n for n, p in nodes.items() if not alive(p)],
            refused=refused,
        )
        rows.append(row)
    return {"rows": rows, "samples": state["samples"]}
