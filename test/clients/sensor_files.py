"""Client functions of test_rotors_sensor_files.py."""

import importlib
import time

import numpy as np
import rospy

DEPTH_TOPICS = ("/tof/rgbd/camera_depth/depth/image_raw", "/probe/camera/depth/image_raw")


def collect(topics: dict) -> dict:
    """Subscribes to `topics` (topic -> message type) until each has 12 messages (150 s at most):
    per topic the header stamps, the image size and encoding of images, the depth statistics of
    DEPTH_TOPICS; and the published topics' types."""
    stamps = {t: [] for t in topics}
    sizes, depth = {}, {}

    def subscriber(topic, type_name):
        pkg, name = type_name.split("/")
        cls = getattr(importlib.import_module(pkg + ".msg"), name)

        def cb(m):
            stamps[topic].append(m.header.stamp.to_sec())
            if hasattr(m, "encoding"):
                sizes[topic] = (m.width, m.height, m.encoding)
            if topic in DEPTH_TOPICS:
                d = np.frombuffer(m.data, dtype=np.float32)
                v = d[np.isfinite(d)]
                depth[topic] = dict(
                    valid=int(v.size),
                    nan=int(np.isnan(d).sum()),
                    min=float(v.min()) if v.size else 0.0,
                    max=float(v.max()) if v.size else 0.0,
                )

        return rospy.Subscriber(topic, cls, cb, queue_size=50)

    _subscribers = [subscriber(t, k) for t, k in topics.items()]  # held while collecting
    deadline = time.monotonic() + 150
    while time.monotonic() < deadline and min(len(v) for v in stamps.values()) < 12:
        time.sleep(0.2)
    return dict(stamps=stamps, sizes=sizes, depth=depth, types=dict(rospy.get_published_topics()))
