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
