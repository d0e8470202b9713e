"""rotors_sim.stepper, the world's side of the ROS 2 front end, without ROS 2: every step answers the
vehicle's signed rotor speeds (motor_speed); motor commands reach the motors and bad ones are refused in
one line with the world unchanged; each controller takes only its own commands; the other topics are
answered as the plugins' ROS 1 bytes once asked for."""

import math

import pytest

from rotors_sim._engine import SimError
from rotors_sim.stepper import Stepper


def test_motor_commands_reach_the_motors_and_bad_ones_change_nothing():
    s = Stepper("firefly", "basic", 3, controller="none")
    assert s.serve({"op": "info"})["controller"] == "none" and s.frames()["motor_speed"] == "firefly/base_link"
    s.serve({"op": "motor_speeds", "speeds": [600.0] * 6})
    answer = s.serve({"op": "step", "n": 100})  # 1 s: many motor time constants
    rows = answer["motor_speed"]
    assert len(rows) >= 100 and rows[-1][0] == pytest.approx(answer["t"])
    assert rows[-1][1:] == pytest.approx([600.0, -600.0] * 3, rel=1e-3)  # signed as the rotors turn
    for bad, why in (([math.nan] * 6, "= nan must be a finite speed"), ([1.0] * 3, "has 3 angular_velocities, the vehicle has 6")):
        with pytest.raises(SimError, match=why):
            s.serve({"op": "motor_speeds", "speeds": bad})
    assert s.serve({"op": "step", "n": 10})["motor_speed"][-1][1:] == pytest.approx([600.0, -600.0] * 3, rel=1e-3)
    with pytest.raises(SimError, match="set_point is for --controller lee"):
        s.serve({"op": "set_point", "position": [0, 0, 1], "yaw": 0.0})


def test_each_controller_takes_its_own_commands_and_refuses_nan():
    s = Stepper("firefly", "basic", 3, controller="roll_pitch_yawrate_thrust")
    s.serve({"op": "roll_pitch_yawrate_thrust", "roll": 0.0, "pitch": 0.0, "yaw_rate": 0.0, "thrust": 1.2 * 1.56779 * 9.81})
    z0 = s.serve({"op": "step", "n": 1})["odometry"][-1][3]
    assert s.serve({"op": "step", "n": 100})["odometry"][-1][3] > z0 + 0.2  # 1.2 m g: it climbs
    with pytest.raises(SimError, match="thrust nan must be 1 finite number"):
        s.serve({"op": "rate_thrust", "angular_velocity": [0, 0, 0], "thrust": math.nan})
    with pytest.raises(SimError, match="--controller 'fast'"):
        Stepper("firefly", "basic", 3, controller="fast")


def test_other_topics_are_answered_as_ros1_bytes_once_asked_for():
    import base64

    import rospy  # noqa: F401  (genpy's time for the message class)
    from geometry_msgs.msg import TransformStamped

    s = Stepper("firefly", "basic", 3)
    topics = dict(s.serve({"op": "info"})["topics"])
    assert topics["/firefly/ground_truth/transform"] == "geometry_msgs/TransformStamped" and "/firefly/imu" not in topics
    assert s.serve({"op": "step", "n": 3})["messages"] == []  # none asked for yet
    s.serve({"op": "forward", "topics": ["/firefly/ground_truth/transform"]})
    answer = s.serve({"op": "step", "n": 3})
    assert [m[:2] for m in answer["messages"]] == [["/firefly/ground_truth/transform", "geometry_msgs/TransformStamped"]] * 3
    m = TransformStamped().deserialize(base64.b64decode(answer["messages"][-1][2]))
    assert m.header.stamp.to_sec() == pytest.approx(answer["t"]) and m.child_frame_id == "firefly/base_link"
    with pytest.raises(SimError, match="not among the world's other topics"):
        s.serve({"op": "forward", "topics": ["/firefly/imu"]})


def test_a_model_spawned_and_deleted_brings_and_takes_its_topics():
    import rotors_sim as rs

    s = Stepper("firefly", "basic", 3)
    xml = rs.world.run_xacro(
        rs.paths.package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo",
        {"mav_name": "firefly", "namespace": "second", "random_seed": 4, "enable_ground_truth": True, "enable_logging": False},
    )
    answer = s.serve({"op": "spawn", "xml": xml, "name": "second", "xyz": [2.0, 0.0, 0.1], "rpy": [0.0, 0.0, 0.0]})
    topics = dict(answer["topics"])
    assert answer["name"] == "second" and topics["/second/ground_truth/odometry"] == "nav_msgs/Odometry"
    s.serve({"op": "forward", "topics": ["/second/ground_truth/position"]})
    got = s.serve({"op": "step", "n": 2})["messages"]
    assert [m[0] for m in got] == ["/second/ground_truth/position"] * 2
    for bad, why in (
        ({"xml": xml, "name": "second"}, "a model named 'second' exists already"),
        ({"xml": "not xml", "name": "third"}, "xml must be URDF or SDF text"),
        ({"xml": xml, "name": "third", "xyz": [math.nan, 0, 0]}, "must be 3 finite numbers"),
    ):
        with pytest.raises(SimError, match=why):
            s.serve({"op": "spawn", **bad})
    s.serve({"op": "delete", "name": "second"})
    assert s.serve({"op": "step", "n": 2})["messages"] == []  # gone: nothing more of it
    with pytest.raises(SimError, match="no model named 'second'"):
        s.serve({"op": "delete", "name": "second"})
    s.serve({"op": "delete", "name": "firefly"})  # the vehicle itself: its readings stop, the world runs on
    answer = s.serve({"op": "step", "n": 2})
    assert answer["odometry"] == [] and answer["motor_speed"] == [] and answer["t"] > 0
