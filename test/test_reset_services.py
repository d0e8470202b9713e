"""Gazebo's reset services repeat a flight bit for bit over ROS, as World.reset() does from Python
(test_python_module.py): the firefly with a wind gust, GPS, magnetometer, barometer and seeded IMU
and odometry noise, flown by the Lee controller node in lockstep. After /gazebo/reset_simulation
every message of every /firefly topic repeats the first flight's byte for byte; after
/gazebo/reset_world (the time runs on) they repeat with their header stamps aside."""
import textwrap
from pathlib import Path

from conftest import REPO, RosGraph, send_hover_pose, stop_launch

FLIGHT_S = 3.0
COMPARED_S = 2.5  # each flight stops at FLIGHT_S, give or take the steps a pause call takes to land

RECORD_AND_RESET = textwrap.dedent("""
    import io
    import genpy, roslib.message
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import Empty

    phase, log, clock = [None], {}, [None]
    types = {t: kind for t, kind in rospy.get_published_topics() if t.startswith('/firefly/')}

    def recorder(topic):
        def record(msg):
            if phase[0] is not None:
                log.setdefault(phase[0], {}).setdefault(topic, []).append(bytes(msg._buff))
        return record

    subs = [rospy.Subscriber(t, rospy.AnyMsg, recorder(t), queue_size=100000) for t in types]
    rospy.Subscriber('/clock', Clock, lambda m: clock.__setitem__(0, m.clock.to_sec()), queue_size=10)
    while any(s.get_num_connections() == 0 for s in subs):
        time.sleep(0.05)
    pause, unpause = rospy.ServiceProxy('/gazebo/pause_physics', Empty), rospy.ServiceProxy('/gazebo/unpause_physics', Empty)

    def fly(name, start_s):
        phase[0] = name
        clock[0] = None
        unpause()
        deadline = time.monotonic() + 120
        while clock[0] is None or clock[0] < start_s + FLIGHT_S:
            assert time.monotonic() < deadline, 'sim time stuck at %s' % clock[0]
            time.sleep(0.01)
        pause()
        time.sleep(1.0)  # what was published before the pause arrives
        phase[0] = None
        return clock[0]

    end = fly('first', 0.0)
    rospy.ServiceProxy('/gazebo/reset_simulation', Empty)()
    end = fly('after_reset_simulation', 0.0)
    rospy.ServiceProxy('/gazebo/reset_world', Empty)()
    end = fly('after_reset_world', end)
    rospy.ServiceProxy('/gazebo/reset_world', Empty)()
    end = fly('after_reset_world_again', end)

    def unnumbered(topic, data, unstamp=False):
        # roscpp numbers each publisher's messages (header.seq) and runs on across a reset, as in Gazebo
        msg = roslib.message.get_message_class(types[topic])().deserialize(data)
        if hasattr(msg, 'header'):
            msg.header.seq = 0
            if unstamp:
                msg.header.stamp = genpy.Time(0)
        out = io.BytesIO()
        msg.serialize(out)
        return out.getvalue()

    def flight(name, topic):
        # the simulator repeats its state (joint_states) every 50 ms while paused, for late
        # subscribers: of the messages with one stamp, only the first belongs to the flight
        msgs = log[name].get(topic, [])
        if topic != '/firefly/joint_states':
            return msgs
        stamps = [m[4:12] for m in msgs]
        return [m for i, m in enumerate(msgs) if i == 0 or stamps[i] != stamps[i - 1]]

    def compare(a, b, canonical=lambda topic, data: data):
        # per topic: how many messages both flights have, and the first of them that differs
        out = {}
        for topic in sorted(set(log[a]) | set(log[b])):
            x, y = flight(a, topic), flight(b, topic)
            n = min(len(x), len(y))
            first = next((i for i in range(n) if canonical(topic, x[i]) != canonical(topic, y[i])), None)
            out[topic] = [n, first]
        return out

    result['types'] = types
    result['simulation'] = compare('first', 'after_reset_simulation', unnumbered)
    result['world'] = compare('after_reset_world', 'after_reset_world_again', lambda t, d: unnumbered(t, d, True))
    force = '/firefly/external_force'
    result['gust'] = [len({unnumbered(force, m, True) for m in log[name].get(force, [])})
                      for name in ('first', 'after_reset_world')]
""").replace("FLIGHT_S", repr(FLIGHT_S))

# the topics at their RotorS rates (Hz) that must be in both flights: each is compared over at
# least COMPARED_S of its messages
RATES_HZ = {"/firefly/imu": 100, "/firefly/gps": 5, "/firefly/magnetic_field": 100, "/firefly/air_pressure": 10,
            "/firefly/ground_speed": 5, "/firefly/odometry_sensor1/odometry": 100,
            "/firefly/command/motor_speed": 100, "/firefly/wind_speed": 100, "/firefly/external_force": 100,
            "/firefly/ground_truth/pose": 100, "/firefly/joint_states": 100}


def test_reset_simulation_and_reset_world_repeat_the_flight_bit_for_bit(ros: RosGraph):
    proc = ros.start(["roslaunch", "-p", str(ros.port), str(REPO / "test/launch/reset_repeats.launch")], "launch")
    try:
        ready = ros.wait_for(lambda: "Successfully spawned" in Path(proc.log_path).read_text(), 60)
        assert ready, Path(proc.log_path).read_text()[-2000:]
        r = send_hover_pose(ros, then=RECORD_AND_RESET)  # the set point, then the flights
    finally:
        stop_launch(proc)
    for name in ("simulation", "world"):
        compared = r[name]
        print(f"reset_{name}: {len(compared)} topics, {sum(n for n, _ in compared.values())} messages compared; "
              f"differing: {({t: f for t, (_, f) in compared.items() if f is not None}) or 'none'}")
        for topic, rate_hz in RATES_HZ.items():
            assert compared.get(topic, [0])[0] >= rate_hz * COMPARED_S, (name, topic, compared.get(topic))
        assert {t: f for t, (_, f) in compared.items() if f is not None} == {}, name
    # the gust pushed the MAV in the first flight; after reset_world (from 3 s on) it is over
    assert r["gust"][0] > 1 and r["gust"][1] == 1
