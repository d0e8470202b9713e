"""Client functions of test_clean_runs.py."""

import rospy
from geometry_msgs.msg import PoseStamped
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty


def hover_set_point_then_unpause(until_s: float) -> dict:
    """Latches the set point (0, 0, 1) on /firefly/command/pose and unpauses the simulation at once,
    without waiting for the controller; holds the latched set point until the clock reaches until_s."""
    pub = rospy.Publisher("/firefly/command/pose", PoseStamped, queue_size=1, latch=True)
    cmd = PoseStamped()
    cmd.pose.position.z = 1.0
    cmd.pose.orientation.w = 1.0
    pub.publish(cmd)
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    # the latched set point lives as long as this client: until the flight is done
    while rospy.wait_for_message("/clock", Clock).clock.to_sec() < until_s:
        pass
    return {}
