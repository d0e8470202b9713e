"""The fault scenarios of test_faults.py on the book's hovering example (firefly, set point
(0, 0, 1)): each watches the flight through Watch and returns its figures."""

import math
import os
import signal
import subprocess
import time

import rospy
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Quaternion, Transform, Vector3
from mav_msgs.msg import Actuators
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

from clients.nodes import alive, cpu_seconds, node_pid
from clients.waits import wait_until


class Watch:
    """The flight as the scenarios see it: state['p'] the ground-truth position at sim time
    state['t'], state['clock'] the sim time, state['command'] the sim time of the last motor command;
    and the latched set point on command/trajectory."""

    def __init__(self):
        self.state = {"t": -1.0, "p": None, "clock": -1.0}
        rospy.Subscriber("/firefly/ground_truth/odometry", Odometry, self.on_odom, queue_size=1)
        rospy.Subscriber("/clock", Clock, lambda m: self.state.update(clock=m.clock.to_sec()), queue_size=1)
        rospy.Subscriber("/firefly/command/motor_speed", Actuators, lambda m: self.state.update(command=self.state["clock"]), queue_size=1)
        self.set_point = rospy.Publisher("/firefly/command/trajectory", MultiDOFJointTrajectory, queue_size=1, latch=True)

    def on_odom(self, m):
        p = m.pose.pose.position
        self.state.update(t=m.header.stamp.to_sec(), p=(p.x, p.y, p.z))

    @staticmethod
    def until(condition, limit_s, failure):
        """Polls condition() every 10 ms; SystemExit with failure() after limit_s of wall time."""
        deadline = time.monotonic() + limit_s
        while not condition():
            if time.monotonic() > deadline:
                raise SystemExit(failure())
            time.sleep(0.01)

    def wait_clock(self, t_s, limit_s=120):
        self.until(
            lambda: self.state["clock"] >= t_s and self.state["p"] is not None,
            limit_s,
            lambda: "sim time stuck at {:.2f} s (waiting for {:.2f} s)".format(self.state["clock"], t_s),
        )
        return self.state["clock"]

    def wait_stamp(self, accept, what, limit_s=60):
        """Until the latest ground truth's stamp satisfies accept(stamp); SystemExit naming `what`."""
        self.until(
            lambda: accept(self.state["t"]),
            limit_s,
            lambda: "no ground truth {} within {} s (last stamp {:.3f} s)".format(what, limit_s, self.state["t"]),
        )
        return self.state["t"]

    def send_set_point(self):
        # a restarted controller has no reference: send (0, 0, 1) again, as a ground station would
        point = MultiDOFJointTrajectoryPoint(transforms=[Transform(translation=Vector3(0, 0, 1), rotation=Quaternion(0, 0, 0, 1))])
        msg = MultiDOFJointTrajectory(points=[point])
        msg.header.stamp = rospy.Time.now()
        self.set_point.publish(msg)


def restart_controller():
    return subprocess.Popen(
        [
            "rosrun",
            "rotors_control",
            "lee_position_controller_node",
            "__ns:=/firefly",
            "__name:=lee_position_controller_node",
            "odometry:=odometry_sensor1/odometry",
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )


def distance(a, b):
    return math.dist(a, b)


def controller_killed_without_lockstep() -> dict:
    """The controller killed at 12 s and restarted 0.2 s later (the set point sent again): the gap in
    the motor commands and the offsets in the 8 s after; then killed for good: the lowest height
    within 12 s."""
    watch = Watch()
    state, result = watch.state, {}
    watch.wait_clock(12.0)
    p_before = state["p"]
    os.kill(node_pid("/firefly/lee_position_controller_node"), signal.SIGKILL)
    t_kill = state["clock"]
    time.sleep(0.2)  # the controller interface holds the last command meanwhile
    controller = restart_controller()
    watch.send_set_point()
    wait_until(lambda: state.get("command", 0.0) > t_kill + 0.2, 90, "a motor command from the restarted controller", 0.01)
    result["gap"] = state["command"] - t_kill
    worst, t_end = 0.0, state["clock"] + 8.0
    while state["clock"] < t_end:
        worst = max(worst, distance(state["p"], p_before))
        time.sleep(0.02)
    result["worst_after_short_outage"] = worst
    result["error_after"] = distance(state["p"], p_before)
    # now the controller goes away for good: after commandTimeout the motors stop
    os.kill(controller.pid, signal.SIGKILL)
    result["t_killed_for_good"] = state["clock"]
    lowest, t_end = 10.0, state["clock"] + 12.0
    while state["clock"] < t_end and lowest > 0.15:
        lowest = min(lowest, state["p"][2])
        time.sleep(0.02)
    watch.wait_clock(state["clock"] + 1.0)
    result["lowest"] = lowest
    return result


def simulator_killed() -> dict:
    """The simulator killed at 20 s: whether the controller lives on, and its CPU seconds in 5 s."""
    watch = Watch()
    result = {}
    watch.wait_clock(20.0)
    lee = node_pid("/firefly/lee_position_controller_node")
    os.kill(node_pid("/gazebo"), signal.SIGKILL)
    time.sleep(2.0)
    cpu0 = cpu_seconds(lee)
    time.sleep(5.0)
    result["lee_cpu_s_in_5_s"] = cpu_seconds(lee) - cpu0
    result["lee_alive"] = alive(lee)
    return result


def reset_world_and_simulation() -> dict:
    """reset_world at 12 s, reset_simulation 8 s later: the height and the clock after each, and the
    distance to the hover position 8 s after each."""
    watch = Watch()
    state, result = watch.state, {}
    watch.wait_clock(12.0)
    p_hover = state["p"]
    rospy.ServiceProxy("/gazebo/reset_world", Empty)()
    # the height 50 ms of sim time after the reset (the clock this client holds lags the world's by a
    # step or two, so a stamp 50 ms past it is after the reset), not after some wall time
    t_reset = state["clock"]
    watch.wait_stamp(lambda t: t >= t_reset + 0.05, "50 ms after reset_world")
    result["z_after_reset_world"] = state["p"][2]
    watch.wait_clock(state["clock"] + 8.0)
    result["error_8_s_after_reset_world"] = distance(state["p"], p_hover)
    t_before = state["t"]
    rospy.ServiceProxy("/gazebo/reset_simulation", Empty)()
    # the first ground truth of the new run stamped at 50 ms or later (the clock went back to 0)
    watch.wait_stamp(lambda t: 0.05 <= t < t_before - 1.0, "50 ms into the run after reset_simulation")
    result["clock_after_reset_simulation"] = state["t"]
    result["z_after_reset_simulation"] = state["p"][2]
    watch.wait_clock(8.0)
    result["error_8_s_after_reset_simulation"] = distance(state["p"], p_hover)
    return result


def reset_simulation_repeatedly(count: int) -> dict:
    """reset_simulation `count` times at moments spread over the step (lockstep, as fast as possible):
    after each, the sim time the clock reached within 20 s of wall time (a reset served while the
    simulator waited for the controller's answer once left the clock at 0 for good)."""
    watch = Watch()
    state, reached = watch.state, []
    reset = rospy.ServiceProxy("/gazebo/reset_simulation", Empty)
    watch.wait_clock(1.0)
    for i in range(count):
        time.sleep(0.013 * (i % 7))  # lands on different phases of the lockstep turn
        reset()
        try:
            reached.append(watch.wait_clock(0.5, limit_s=20))
        except SystemExit:
            reached.append(state["clock"])
            break  # stuck for good: the rest would wait as long each
    return {"reached": reached}


def pause_and_resume() -> dict:
    """The physics paused at 12 s for 10 s of wall time: how far the clock and the MAV moved
    meanwhile, and the largest offset in the 5 s after resuming."""
    watch = Watch()
    state, result = watch.state, {}
    watch.wait_clock(12.0)
    rospy.ServiceProxy("/gazebo/pause_physics", Empty)()
    time.sleep(0.5)
    t0, p0 = state["clock"], state["p"]
    time.sleep(10.0)
    result["clock_advanced_while_paused"] = state["clock"] - t0
    result["moved_while_paused"] = distance(state["p"], p0)
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    worst, t_end = 0.0, t0 + 5.0
    watch.wait_clock(t0 + 0.1)
    while state["clock"] < t_end:
        worst = max(worst, distance(state["p"], p0))
        time.sleep(0.02)
    result["worst_after_resume"] = worst
    return result


def controller_stopped_as_in_a_debugger() -> dict:
    """The controller SIGSTOPped at 8 s for 8 s of wall time: the slowest get_model_state call and the
    sim time passed meanwhile; after SIGCONT, the sim time reached (from the stop) within 60 s."""
    watch = Watch()
    state, result = watch.state, {}
    model_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
    watch.wait_clock(8.0)
    pid = node_pid("/firefly/lee_position_controller_node")
    os.kill(pid, signal.SIGSTOP)
    t_stop = state["clock"]
    slowest, t_end = 0.0, time.monotonic() + 8.0
    while time.monotonic() < t_end:
        t0 = time.monotonic()
        assert model_state(model_name="firefly").success
        slowest = max(slowest, time.monotonic() - t0)
        time.sleep(0.05)
    result["slowest_service_call_s"] = slowest
    result["clock_while_stopped"] = state["clock"] - t_stop
    os.kill(pid, signal.SIGCONT)
    result["resumed_to"] = watch.wait_clock(t_stop + 2.0, limit_s=60) - t_stop
    return result
