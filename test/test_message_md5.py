"""Interface contract: our mav_msgs, rotors_comm, gazebo_msgs, sensor_fusion_comm, octomap_msgs, mavros_msgs and
mav_planning_msgs definitions have the md5sums of the upstream packages, so bags and nodes from real RotorS set-ups
interoperate. The values are pinned literals, as the upstream packages' generated code states them
(rosserial ros_lib getMD5(), gennodejs md5sum(), genlisp md5sum of mav_comm, rotors_simulator,
gazebo_ros_pkgs, ethzasl_msf and mavros, looked up in public repositories), not recomputed from our files."""

import importlib
import subprocess

import pytest

UPSTREAM_MSG_MD5 = {
    "mav_msgs/Actuators": "25741daf38ed25442e3a66a855ee8d9c",
    "mav_msgs/AttitudeThrust": "7cee443b02735e42bda0ad5910302718",
    "mav_msgs/RateThrust": "119c5bf883bef42350d52ce5a7927c7c",
    "mav_msgs/RollPitchYawrateThrust": "10a56a30857affade0889a3662fc2bc9",
    "mav_msgs/TorqueThrust": "81293743ae52683b61e39c21bc0b30db",
    "mav_msgs/FilteredSensorData": "a9b51fae1f4ed3a8a0522b4ffe61659f",
    "mav_msgs/GpsWaypoint": "61c3751c96f3b418f93879727f9a070a",
    "mav_msgs/Status": "e191265664a5f7c1871338dc13be0958",
    "rotors_comm/WindSpeed": "ae00d2a331b8545eaf96c531128ff0ef",
    "gazebo_msgs/ModelStates": "48c080191eb15c41858319b4d8a609c2",
    "sensor_fusion_comm/DoubleArrayStamped": "fb60495edd59d3fcf90e173153ae8a9a",
    "sensor_fusion_comm/DoubleMatrixStamped": "c58f6b7538f12163211fe0ce597bbfd8",
    "octomap_msgs/Octomap": "9a45536b45c5e409cd49f04bb2d9999f",
    "mavros_msgs/OpticalFlowRad": "65d93e03c6188c7ee30415b2a39ad40d",
    # mav_comm's mav_planning_msgs (PolynomialTrajectory4D and PlannerService also in public gennodejs,
    # genlisp and rosserial code; the others computed by genmsg from mav_comm's own .msg files)
    "mav_planning_msgs/Point2D": "209f516d3eb691f0663e25cb750d67c1",
    "mav_planning_msgs/PointCloudWithPose": "2a8b498d41262fbae6e2ab39e0965442",
    "mav_planning_msgs/Polygon2D": "8f02263beef99aa03117a577a3eb879d",
    "mav_planning_msgs/PolygonWithHoles": "df7f266352dfcf3e4d29156dd85febf9",
    "mav_planning_msgs/PolygonWithHolesStamped": "75e2ac63509c016edab7c5a5ed67059b",
    "mav_planning_msgs/PolynomialSegment": "1bfc920140297f14773c46c1eacc4c1d",
    "mav_planning_msgs/PolynomialSegment4D": "c85fa40c94ff35d242df13d4d3a57809",
    "mav_planning_msgs/PolynomialTrajectory": "2daf5d705534e84f80980f4673a0e62b",
    "mav_planning_msgs/PolynomialTrajectory4D": "4d68d15524ede489eecd674bb6dc3ee8",
}
UPSTREAM_SRV_MD5 = {
    "rotors_comm/RecordRosbag": "5504376d5b4669d33bfb29107c817d83",
    "rotors_comm/Octomap": "a0b5f40a1676bf2554580b1ee723114a",
    "gazebo_msgs/SpawnModel": "9ed9c82c96abe1a00c3e8cdaeee24413",
    "gazebo_msgs/DeleteModel": "9ce56b4e9e54616de25d796dc972a262",
    "gazebo_msgs/GetModelState": "4c515e936d3319c9610c559c60bfc3d4",  # noetic, with the response header
    "sensor_fusion_comm/InitScale": "f8ea41d14f4e256b53793fe5b7588158",
    "sensor_fusion_comm/InitHeight": "6b19ce060384743d60708a804f1c749f",
    "mav_planning_msgs/ChangeNameService": "d82dc6474dd88dad5e1615ab1b2ca74c",
    "mav_planning_msgs/PlannerService": "118771e195038ced9b4ddec299814131",
    "mav_planning_msgs/PolygonService": "7e5305932db903eed4a95dd3377ac6bc",
}


def generated_class(full_name: str, kind: str):
    pkg, name = full_name.split("/")
    return getattr(importlib.import_module(f"{pkg}.{kind}"), name)


@pytest.mark.parametrize("full_name", sorted(UPSTREAM_MSG_MD5))
def test_message_md5_is_upstreams(full_name: str):
    assert generated_class(full_name, "msg")._md5sum == UPSTREAM_MSG_MD5[full_name], full_name


@pytest.mark.parametrize("full_name", sorted(UPSTREAM_SRV_MD5))
def test_service_md5_is_upstreams(full_name: str):
    assert generated_class(full_name, "srv")._md5sum == UPSTREAM_SRV_MD5[full_name], full_name


def test_rosmsg_prints_upstream_actuators_md5():
    out = subprocess.run(["rosmsg", "md5", "mav_msgs/Actuators"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "25741daf38ed25442e3a66a855ee8d9c"
