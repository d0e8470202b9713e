"""Interface contract: our mav_msgs / rotors_comm / gazebo_msgs definitions have the md5sums of the
upstream ones, computed here from the field lists in rotors_reference.md section 2.1 and 1.1 (so bags
and nodes from real RotorS set-ups interoperate)."""
import importlib
import subprocess
from pathlib import Path
import tempfile

import genmsg
import genmsg.msg_loader
import pytest

# Field lists as the reference states them (comments do not enter the md5).
REFERENCE_MSGS = {
    "mav_msgs/Actuators": "Header header\nfloat64[] angles\nfloat64[] angular_velocities\nfloat64[] normalized\n",
    "mav_msgs/AttitudeThrust": "Header header\ngeometry_msgs/Quaternion attitude\ngeometry_msgs/Vector3 thrust\n",
    "mav_msgs/RateThrust": "Header header\ngeometry_msgs/Vector3 angular_rates\ngeometry_msgs/Vector3 thrust\n",
    "mav_msgs/RollPitchYawrateThrust":
        "Header header\nfloat64 roll\nfloat64 pitch\nfloat64 yaw_rate\ngeometry_msgs/Vector3 thrust\n",
    "mav_msgs/TorqueThrust": "Header header\ngeometry_msgs/Vector3 torque\ngeometry_msgs/Vector3 thrust\n",
    "mav_msgs/FilteredSensorData": "Header header\ngeometry_msgs/Vector3 accelerometer\n"
                                   "geometry_msgs/Vector3 gyroscope\ngeometry_msgs/Vector3 magnetometer\n"
                                   "float64 barometer\n",
    "mav_msgs/GpsWaypoint": "Header header\nfloat64 latitude\nfloat64 longitude\nfloat64 altitude\n"
                            "float64 heading\nfloat64 maxSpeed\nfloat64 maxAcc\n",
    "mav_msgs/Status": "Header header\nstring vehicle_name\nstring vehicle_type\nfloat32 battery_voltage\n"
                       "string rc_command_mode\nbool command_interface_enabled\nfloat32 flight_time\n"
                       "float32 system_uptime\nfloat32 cpu_load\nstring motor_status\nbool in_air\n"
                       "string gps_status\nint32 gps_num_satellites\n"
                       'string RC_COMMAND_ATTITUDE="attitude_thrust"\n'
                       'string RC_COMMAND_ATTITUDE_HEIGHT="attitude_height"\n'
                       'string RC_COMMAND_POSITION="position"\n'
                       'string MOTOR_STATUS_RUNNING="running"\nstring MOTOR_STATUS_STOPPED="stopped"\n'
                       'string MOTOR_STATUS_STARTING="starting"\nstring MOTOR_STATUS_STOPPING="stopping"\n'
                       'string GPS_STATUS_LOCK="lock"\nstring GPS_STATUS_NO_LOCK="no_lock"\n',
    "rotors_comm/WindSpeed": "Header header\ngeometry_msgs/Vector3 velocity\n",
    "gazebo_msgs/ModelStates": "string[] name\ngeometry_msgs/Pose[] pose\ngeometry_msgs/Twist[] twist\n",
    # ethzasl_msf (reference section 8)
    "sensor_fusion_comm/DoubleArrayStamped": "Header header\nfloat64[] data\n",
    "sensor_fusion_comm/DoubleMatrixStamped": "Header header\nint32 rows\nint32 cols\nfloat64[] data\n",
    # octomap_msgs (not in Debian; shipped by us)
    "octomap_msgs/Octomap": "Header header\nbool binary\nstring id\nfloat64 resolution\nint8[] data\n",
}
REFERENCE_SRVS = {
    "rotors_comm/RecordRosbag": "bool record\n---\nbool success\n",
    "rotors_comm/Octomap": "geometry_msgs/Point bounding_box_origin\ngeometry_msgs/Point bounding_box_lengths\n"
                           "float64 leaf_size\nbool publish_octomap\nstring filename\n---\n"
                           "octomap_msgs/Octomap map\nfloat64 origin_latitude\nfloat64 origin_longitude\n"
                           "float64 origin_altitude\n",
    "gazebo_msgs/SpawnModel": "string model_name\nstring model_xml\nstring robot_namespace\n"
                              "geometry_msgs/Pose initial_pose\nstring reference_frame\n---\n"
                              "bool success\nstring status_message\n",
    "gazebo_msgs/DeleteModel": "string model_name\n---\nbool success\nstring status_message\n",
    "sensor_fusion_comm/InitScale": "float32 scale\n---\nstring result\n",
    "sensor_fusion_comm/InitHeight": "float32 height\n---\nstring result\n",
}
SEARCH_PATH = {pkg: [f"/usr/share/{pkg}/msg"] for pkg in ("std_msgs", "geometry_msgs")}
# dependencies that are not in Debian resolve to the reference texts above
_REFERENCE_DIR = Path(tempfile.mkdtemp(prefix="md5_reference_"))
for _name, _text in REFERENCE_MSGS.items():
    _pkg, _msg = _name.split("/")
    (_REFERENCE_DIR / _pkg).mkdir(exist_ok=True)
    (_REFERENCE_DIR / _pkg / f"{_msg}.msg").write_text(_text)
    SEARCH_PATH.setdefault(_pkg, [str(_REFERENCE_DIR / _pkg)])


def reference_md5(full_name: str, text: str) -> str:
    ctx = genmsg.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_from_string(ctx, text, full_name)
    genmsg.msg_loader.load_depends(ctx, spec, SEARCH_PATH)
    return genmsg.compute_md5(ctx, spec)


def reference_srv_md5(full_name: str, text: str) -> str:
    ctx = genmsg.MsgContext.create_default()
    spec = genmsg.msg_loader.load_srv_from_string(ctx, text, full_name)
    genmsg.msg_loader.load_depends(ctx, spec, SEARCH_PATH)
    return genmsg.compute_md5(ctx, spec)


def generated_class(full_name: str, kind: str):
    pkg, name = full_name.split("/")
    return getattr(importlib.import_module(f"{pkg}.{kind}"), name)


@pytest.mark.parametrize("full_name", sorted(REFERENCE_MSGS))
def test_message_md5_matches_reference(full_name: str):
    assert generated_class(full_name, "msg")._md5sum == reference_md5(full_name, REFERENCE_MSGS[full_name])


@pytest.mark.parametrize("full_name", sorted(REFERENCE_SRVS))
def test_service_md5_matches_reference(full_name: str):
    assert generated_class(full_name, "srv")._md5sum == reference_srv_md5(full_name, REFERENCE_SRVS[full_name])


def test_octomap_md5_is_upstreams():
    # octomap_msgs/Octomap as published by ROS' octomap_msgs package
    assert generated_class("octomap_msgs/Octomap", "msg")._md5sum == "9a45536b45c5e409cd49f04bb2d9999f"


def test_get_model_state_md5_is_upstreams():
    # gazebo_msgs/GetModelState of gazebo_ros_pkgs (noetic, with the response header)
    assert generated_class("gazebo_msgs/GetModelState", "srv")._md5sum == "4c515e936d3319c9610c559c60bfc3d4"


def test_rosmsg_prints_upstream_actuators_md5():
    out = subprocess.run(["rosmsg", "md5", "mav_msgs/Actuators"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "25741daf38ed25442e3a66a855ee8d9c"
