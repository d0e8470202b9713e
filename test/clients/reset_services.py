"""The flights of test_reset_services.py: every /firefly topic recorded byte for byte over four
flights of flight_s sim time each (the first, then after reset_simulation, reset_world and
reset_world again), run after conftest's send_hover_pose."""

import io
import struct
import time

import genpy
import roslib.message
import rospy
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from clients.waits import wait_until


def record_and_reset(flight_s: float) -> dict:
    """The published /firefly topics and their types; per topic, how many messages two flights both
    have and the first of them that differs ('simulation': the first flight and the one after
    reset_simulation, header.seq aside; 'world': the two after reset_world, header stamps aside);
    how many different external forces the first flight and the first after reset_world saw."""
    phase, log, clock = [None], {}, [None]
    types = {t: kind for t, kind in rospy.get_published_topics() if t.startswith("/firefly/")}

    def recorder(topic):
        def record(msg):
            if phase[0] is not None:
                log.setdefault(phase[0], {}).setdefault(topic, []).append(bytes(msg._buff))

        return record

    subs = [rospy.Subscriber(t, rospy.AnyMsg, recorder(t), queue_size=100000) for t in types]
    rospy.Subscriber("/clock", Clock, lambda m: clock.__setitem__(0, m.clock.to_sec()), queue_size=10)
    wait_until(lambda: all(s.get_num_connections() > 0 for s in subs), 90, f"a publisher of each of the {len(types)} /firefly topics")
    pause, unpause = rospy.ServiceProxy("/gazebo/pause_physics", Empty), rospy.ServiceProxy("/gazebo/unpause_physics", Empty)

    starts = {}

    def fly(name, start_s):
        starts[name] = start_s
        phase[0] = name
        clock[0] = None
        unpause()
        deadline = time.monotonic() + 120
        while clock[0] is None or clock[0] < start_s + flight_s:
            assert time.monotonic() < deadline, f"sim time stuck at {clock[0]}"
            time.sleep(0.01)
        pause()
        time.sleep(1.0)  # what was published before the pause arrives
        phase[0] = None
        return clock[0]

    end = fly("first", 0.0)
    rospy.ServiceProxy("/gazebo/reset_simulation", Empty)()
    end = fly("after_reset_simulation", 0.0)
    rospy.ServiceProxy("/gazebo/reset_world", Empty)()
    end = fly("after_reset_world", end)
    rospy.ServiceProxy("/gazebo/reset_world", Empty)()
    end = fly("after_reset_world_again", end)

    def unnumbered(topic, data, unstamp=False):
        # roscpp numbers each publisher's messages (header.seq) and runs on across a reset, as in Gazebo
        msg = roslib.message.get_message_class(types[topic])().deserialize(data)
        if hasattr(msg, "header"):
            msg.header.seq = 0
            if unstamp:
                msg.header.stamp = genpy.Time(0)
        out = io.BytesIO()
        msg.serialize(out)
        return out.getvalue()

    def flight(name, topic):
        # the simulator repeats its state (joint_states) every 50 ms while paused, for late
        # subscribers, and once when a reset lands (that one may arrive after the next flight's
        # recording began): the flight's messages are those stamped after its start, one per stamp
        msgs = log[name].get(topic, [])
        if topic != "/firefly/joint_states":
            return msgs
        secs_nsecs = [struct.unpack_from("<II", m, 4) for m in msgs]
        stamps = [s + 1e-9 * ns for s, ns in secs_nsecs]
        return [m for i, m in enumerate(msgs) if stamps[i] > starts[name] + 1e-6 and (i == 0 or secs_nsecs[i] != secs_nsecs[i - 1])]

    def compare(a, b, canonical=lambda topic, data: data):
        # per topic: how many messages both flights have, and the first of them that differs
        out = {}
        for topic in sorted(set(log[a]) | set(log[b])):
            x, y = flight(a, topic), flight(b, topic)
            n = min(len(x), len(y))
            first = next((i for i in range(n) if canonical(topic, x[i]) != canonical(topic, y[i])), None)
            out[topic] = [n, first]
        return out

    result = {}
    result["types"] = types
    result["simulation"] = compare("first", "after_reset_simulation", unnumbered)
    result["world"] = compare("after_reset_world", "after_reset_world_again", lambda t, d: unnumbered(t, d, True))
    force = "/firefly/external_force"
    result["gust"] = [len({unnumbered(force, m, True) for m in log[name].get(force, [])}) for name in ("first", "after_reset_world")]
    return result
