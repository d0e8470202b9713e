"""Client functions of test_python_ros_images.py."""

import rospy
from sensor_msgs.msg import Image


def vi_left_image(raw_path: str) -> dict:
    """The first VI-sensor left image stamped at 1.5 s or later: its bytes to raw_path; its stamp,
    size and encoding."""
    m = rospy.wait_for_message("/firefly/vi_sensor/left/image_raw", Image, timeout=60)
    while m.header.stamp.to_sec() < 1.5:
        m = rospy.wait_for_message("/firefly/vi_sensor/left/image_raw", Image, timeout=60)
    open(raw_path, "wb").write(bytes(m.data))
    return dict(stamp=m.header.stamp.to_sec(), height=m.height, width=m.width, encoding=m.encoding)
