#!/usr/bin/env python3
"""rosbag2_record: records ROS 2 topics into a ROS 2 bag (MCAP storage, what `ros2 bag record`
writes on Jazzy), for machines without the rosbag2 packages (PyPI has no wheel of them). An rclpy
node subscribes to each topic as raw CDR (`raw=True`: the bytes as they came off the wire, not
deserialised and serialised again) and rosbags' rosbag2 writer stores them with their type's
definition, stamped with the node's clock (sim time: `use_sim_time` is on). The subscriptions are
reliable and keep all: with the simulator's reliable publishers (10,000 readings of history) the
recorder may fall that far behind and lose nothing.

    python rosbag2_record.py -o build/ros2-demo/firefly /firefly/ground_truth/odometry /firefly/command/trajectory ...

Each topic is subscribed to once it appears on the graph (its type taken from the graph), so the
recorder may start before the publishers. SIGINT or SIGTERM stops it: what is still on its way is
written (until 0.5 s pass without a message), then the bag is closed (metadata.yaml written)."""

from __future__ import annotations

import argparse
import signal
import sys
import time
from pathlib import Path

import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore


class Recorder(Node):
    def __init__(self, writer: Writer, topics: list[str]):
        super().__init__("rosbag2_recorder", parameter_overrides=[Parameter("use_sim_time", value=True)])
        self.writer, self.wanted = writer, list(topics)
        self.typestore = get_typestore(Stores.ROS2_JAZZY)
        self.connections: dict = {}
        self.subscriptions_held: list = []
        self.counts: dict[str, int] = {}
        self.create_timer(0.2, self.discover, clock=rclpy.clock.Clock())  # wall time: sim time may be paused

    def discover(self) -> None:
        """Subscribes to each wanted topic that has appeared, with its type from the graph."""
        found = dict(self.get_topic_names_and_types())
        for topic in list(self.wanted):
            types = found.get(topic)
            if not types:
                continue
            msgtype = types[0]
            if msgtype not in self.typestore.fielddefs:
                self.get_logger().error(f"{topic}: type {msgtype} is not in rosbags' Jazzy type store: not recorded")
                self.wanted.remove(topic)
                continue
            self.connections[topic] = self.writer.add_connection(topic, msgtype, typestore=self.typestore)
            self.counts[topic] = 0
            package, _, name = msgtype.split("/")
            module = __import__(f"{package}.msg", fromlist=[name])
            qos = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE)
            self.subscriptions_held.append(
                self.create_subscription(getattr(module, name), topic, lambda data, t=topic: self.write(t, data), qos, raw=True)
            )
            self.wanted.remove(topic)

    def write(self, topic: str, data: bytes) -> None:
        self.writer.write(self.connections[topic], self.get_clock().now().nanoseconds, data)
        self.counts[topic] += 1


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", required=True, help="the bag's directory (must not exist)")
    parser.add_argument("topics", nargs="+")
    args = parser.parse_args(argv)
    out = Path(args.output)
    if out.exists():
        print(f"rosbag2_record: {out} exists; give a new directory", file=sys.stderr)
        return 2
    writer = Writer(out, version=9, storage_plugin=StoragePlugin.MCAP)
    writer.open()
    rclpy.init()
    node = Recorder(writer, args.topics)
    stop = {"now": False}
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.update(now=True))
    try:
        while rclpy.ok() and not stop["now"]:
            rclpy.spin_once(node, timeout_sec=0.1)
        # what was published before the stop and is still on its way (a reliable, keep-all
        # subscription gets it all): drained until 0.5 s pass without a message, 30 s at most
        quiet_since, give_up = time.monotonic(), time.monotonic() + 30.0
        while rclpy.ok() and time.monotonic() - quiet_since < 0.5 and time.monotonic() < give_up:
            before = sum(node.counts.values())
            rclpy.spin_once(node, timeout_sec=0.05)
            if sum(node.counts.values()) != before:
                quiet_since = time.monotonic()
    finally:
        writer.close()
        counts = ", ".join(f"{t}: {n}" for t, n in node.counts.items()) or "nothing"
        missing = f"; never appeared: {', '.join(node.wanted)}" if node.wanted else ""
        print(f"rosbag2_record: {out}: {counts}{missing}", flush=True)
        node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
