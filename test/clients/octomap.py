"""The world's octomap service (test_worlds.py, test_planner_flight.py)."""

import rospy
from geometry_msgs.msg import Point
from rotors_comm.srv import Octomap


def get_octomap(origin: list, lengths: list, leaf_size: float, filename: str) -> dict:
    """/world/get_octomap of the box centred on `origin` with edges `lengths` (m) at leaf_size, saved
    to filename (not published); the map's resolution, its size in bytes, the origin's latitude."""
    rospy.wait_for_service("/world/get_octomap", timeout=60)
    res = rospy.ServiceProxy("/world/get_octomap", Octomap)(
        bounding_box_origin=Point(*origin),
        bounding_box_lengths=Point(*lengths),
        leaf_size=leaf_size,
        publish_octomap=False,
        filename=filename,
    )
    return {"resolution": res.map.resolution, "bytes": len(res.map.data), "latitude": res.origin_latitude}
