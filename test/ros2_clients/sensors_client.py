"""An rclpy client of the ROS 2 front end's bridged topics (test_ros2_graph.py): for each topic given as
topic=pkg/msg/Type, the ROS 2 type the graph reports and the first message stamped at or after
`keep_s` of sim time, as plain fields. Prints RESULT=<json>.
    python sensors_client.py <keep_s> <budget_s> topic=pkg/msg/Type ..."""

import importlib
import sys

import rclpy
from budget import Budget, report


def fields(m):
    """A ROS 2 message as nested dicts and lists (arrays as lists)."""
    if hasattr(m, "get_fields_and_field_types"):
        return {name: fields(getattr(m, name)) for name in m.get_fields_and_field_types()}
    if isinstance(m, (list, tuple)) or hasattr(m, "tolist"):
        return [fields(v) for v in (m.tolist() if hasattr(m, "tolist") else m)]
    return m


def main() -> None:
    keep_s = float(sys.argv[1])
    wanted = dict(arg.split("=", 1) for arg in sys.argv[3:])
    rclpy.init()
    node = rclpy.create_node("sensors_client")
    kept: dict = {}

    def keep(topic: str, m) -> None:
        if topic not in kept and m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 >= keep_s - 1e-9:
            kept[topic] = fields(m)

    for topic, ros2_type in wanted.items():
        package, _, name = ros2_type.split("/")
        cls = getattr(importlib.import_module(f"{package}.msg"), name)
        node.create_subscription(cls, topic, lambda m, topic=topic: keep(topic, m), 100)
    budget = Budget(node, float(sys.argv[2]), "sensors_client")
    budget.until(lambda: len(kept) == len(wanted), lambda: f"got {sorted(kept)} of {sorted(wanted)}")
    types = dict(node.get_topic_names_and_types())
    report(node, {"types": {t: types.get(t) for t in wanted}, "kept": kept})


if __name__ == "__main__":
    main()
