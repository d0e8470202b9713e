"""Client functions of test_sim_server.py."""

import time

import rospy
import tf2_ros
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import DeleteModel, GetModelState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import FluidPressure, Range
from std_srvs.srv import Empty


def pause_unpause_reset() -> dict:
    """The clock while paused, get_model_state of the box 'box' (world pose, relative to itself,
    unknown names), the clock after 1 s unpaused, the fallen box's height, the clock paused again,
    the box's height and the clock after reset_world, the clock after reset_simulation."""
    result = {}

    def clock():
        return rospy.wait_for_message("/clock", Clock, timeout=10).clock.to_sec()

    def box_z():
        m = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=10)
        return m.pose[m.name.index("box")].position.z

    result["paused_t0"] = clock()
    time.sleep(0.5)
    result["paused_t1"] = clock()
    get_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
    s = get_state("box", "")
    result["state_z"] = (s.success, s.pose.position.z, s.header.frame_id)
    s = get_state("box", "box")
    result["state_self"] = (s.success, s.pose.position.z, s.pose.orientation.w)
    s = get_state("nope", "")
    result["state_nope"] = (s.success, s.status_message)
    s = get_state("box", "nope")
    result["state_rel_nope"] = (s.success, s.status_message)
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    time.sleep(1.0)
    result["running_t"] = clock()
    rospy.ServiceProxy("/gazebo/pause_physics", Empty)()
    time.sleep(0.3)
    result["z_fallen"] = box_z()
    result["pause_t0"] = clock()
    time.sleep(0.5)
    result["pause_t1"] = clock()
    rospy.ServiceProxy("/gazebo/reset_world", Empty)()
    result["z_reset"] = box_z()
    result["t_after_reset_world"] = clock()
    rospy.ServiceProxy("/gazebo/reset_simulation", Empty)()
    time.sleep(0.3)
    result["t_after_reset_sim"] = clock()
    return result


def box_tf_and_delete() -> dict:
    """The box's position from tf (world -> box/base_link), then delete_model of it twice: the
    successes and the second answer's message."""
    result = {}
    buf = tf2_ros.Buffer()
    _listener = tf2_ros.TransformListener(buf)  # fills buf while it lives
    t = buf.lookup_transform("world", "box/base_link", rospy.Time(0), rospy.Duration(10))
    result["x"] = t.transform.translation.x
    result["y"] = t.transform.translation.y
    r = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)("box")
    result["deleted"] = r.success
    r = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)("box")
    result["deleted_again"] = r.success
    result["msg"] = r.status_message
    return result


def probe_readings() -> dict:
    """The probe's first air pressure and rangefinder readings."""
    result = {}
    result["pressure"] = rospy.wait_for_message("/probe/air_pressure", FluidPressure, timeout=20).fluid_pressure
    result["range"] = rospy.wait_for_message("/probe/lidar", Range, timeout=20).range
    return result


def spawn_turned_and_plain(urdf_path: str) -> dict:
    """The URDF at urdf_path spawned as 'turned' with the quaternion (0, 0, 0.7, 0.7) and as 'plain'
    with an all-zero one: the successes and both orientations from get_model_state."""
    rospy.wait_for_service("/gazebo/spawn_urdf_model", timeout=30)
    spawn = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)
    xml = open(urdf_path).read()
    a = spawn("turned", xml, "", Pose(position=Point(0, 0, 1), orientation=Quaternion(0, 0, 0.7, 0.7)), "world")
    b = spawn("plain", xml, "", Pose(position=Point(2, 0, 1)), "world")
    get = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
    q, p = get("turned", "world").pose.orientation, get("plain", "world").pose.orientation
    return dict(ok=[a.success, b.success], turned=[q.x, q.y, q.z, q.w], plain=[p.x, p.y, p.z, p.w])
