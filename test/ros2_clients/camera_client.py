"""An rclpy client of the ROS 2 front end flying the VI-sensor model (test_ros2_graph.py): the stereo
pair's images and camera_info for `seconds` of sim time; their rates by their own stamps, frames,
encodings and intrinsics; the left image at sim time `keep_s` saved raw to `raw_path`. Prints
RESULT=<json>.
    python camera_client.py <seconds> <keep_s> <raw_path> <budget_s>"""

import json
import sys
import time

import rclpy
from rclpy.parameter import Parameter
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image

seconds, keep_s, raw_path, budget_s = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], float(sys.argv[4])
BASE = "/firefly/vi_sensor"
rclpy.init()
node = rclpy.create_node("camera_client", parameter_overrides=[Parameter("use_sim_time", value=True)])
qos = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=100, reliability=ReliabilityPolicy.RELIABLE)
got = {f"{side}/{kind}": [] for side in ("left", "right") for kind in ("image_raw", "camera_info")}
clock = {"t": 0.0}
kept = {}


def stamp_s(m) -> float:
    return m.header.stamp.sec + m.header.stamp.nanosec * 1e-9


def on_image(name):
    def take(m: Image):
        got[name].append((stamp_s(m), m.header.frame_id, m.encoding, m.width, m.height, m.step))
        if name == "left/image_raw" and "stamp" not in kept and stamp_s(m) >= keep_s:
            with open(raw_path, "wb") as f:
                f.write(bytes(m.data))
            kept.update(stamp=stamp_s(m), width=m.width, height=m.height, encoding=m.encoding)

    return take


def on_info(name):
    return lambda m: got[name].append((stamp_s(m), m.header.frame_id, list(m.k), list(m.p), m.distortion_model, list(m.d)))


for side in ("left", "right"):
    node.create_subscription(Image, f"{BASE}/{side}/image_raw", on_image(f"{side}/image_raw"), qos)
    node.create_subscription(CameraInfo, f"{BASE}/{side}/camera_info", on_info(f"{side}/camera_info"), qos)
node.create_subscription(Clock, "/clock", lambda m: clock.update(t=m.clock.sec + m.clock.nanosec * 1e-9), 10)
deadline = time.monotonic() + budget_s
while clock["t"] < seconds and time.monotonic() < deadline:
    rclpy.spin_once(node, timeout_sec=0.05)
result = {"clock": clock["t"], "kept": kept}
for name, rows in got.items():
    stamps = [r[0] for r in rows if 1.0 <= r[0] <= seconds - 0.5]
    result[name] = {
        "count": len(rows),
        "hz": (len(stamps) - 1) / (stamps[-1] - stamps[0]) if len(stamps) > 1 else 0.0,
        "gaps": sum(b - a > 0.041 for a, b in zip(stamps, stamps[1:])),  # 30 Hz in 10 ms steps: 30 or 40 ms apart
        "first": list(rows[0][1:]) if rows else None,
    }
print("RESULT=" + json.dumps(result), flush=True)
