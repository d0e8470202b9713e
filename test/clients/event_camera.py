"""Client functions of test_event_camera.py."""

import rospy
from dvs_msgs.msg import EventArray
from sensor_msgs.msg import Image


def events_while_flying(until_s: float, figure: str = "") -> dict:
    """The event arrays of /firefly/dvs/events until sim time until_s (the firefly takes off at 5 s
    and climbs: the camera moves) and one image_raw: counts, stamps and the events' fields. With
    `figure`, a PNG there: the last frame beside the events of the busiest 50 ms (white brighter,
    black darker, on grey)."""
    arrays = []
    sub = rospy.Subscriber("/firefly/dvs/events", EventArray, arrays.append, queue_size=1000)
    image = rospy.wait_for_message("/firefly/dvs/image_raw", Image, timeout=120)
    deadline = rospy.Time.now() + rospy.Duration(300)  # sim time; bounded
    while not rospy.is_shutdown() and rospy.Time.now().to_sec() < until_s:
        if rospy.Time.now() > deadline:
            raise RuntimeError(f"sim time never reached {until_s} s (at {rospy.Time.now().to_sec():.2f} s)")
        rospy.sleep(0.1)
    sub.unregister()
    events = [e for a in arrays for e in a.events]
    if figure:
        import numpy as np
        from PIL import Image as Picture

        last = rospy.wait_for_message("/firefly/dvs/image_raw", Image, timeout=60)
        frame = np.frombuffer(bytes(last.data), np.uint8).reshape(last.height, last.width)
        shown = np.full((last.height, last.width), 128, np.uint8)
        bins = np.floor(np.array([e.ts.to_sec() for e in events]) / 0.05)
        busiest = np.bincount((bins - bins.min()).astype(int)).argmax() + bins.min() if len(bins) else -1
        for e, b in zip(events, bins):
            if b == busiest:
                shown[e.y, e.x] = 255 if e.polarity else 0
        Picture.fromarray(np.hstack([frame, np.full((last.height, 8), 255, np.uint8), shown])).save(figure)
    in_order = all(a.events[i].ts <= a.events[i + 1].ts for a in arrays for i in range(len(a.events) - 1))
    within = all(e.ts <= a.header.stamp for a in arrays for e in a.events)
    return dict(
        arrays=len(arrays), events=len(events), width=arrays[-1].width if arrays else 0,
        height=arrays[-1].height if arrays else 0, positive=sum(e.polarity for e in events),
        max_x=max((e.x for e in events), default=-1), max_y=max((e.y for e in events), default=-1),
        in_order=in_order, stamped_before_their_array=within, image=(image.width, image.height, image.encoding),
        frame=arrays[-1].header.frame_id if arrays else "",
    )  # fmt: skip
