"""Fuzzing: every topic and service the simulator and the nodes of the book's hovering example (plus
the estimator, the attitude controller and the joystick mapping, running beside it) subscribe to or
serve receives, for a bounded time each, random invalid and extreme messages, built
from the message definition itself:

- invalid (1 s at 100 Hz per topic): every float NaN or +-inf, arrays empty, of one element or
  1,000 long, zero quaternions; integers at their type's extremes;
- extreme (1 s at 100 Hz per topic): finite but absurd: +-1e30, 1e-300, stamps at 0 and in 2038,
  wrong and 10,000-character frame ids, time_from_start and durations at the int32 limits.

Nothing may crash, the physics state stays finite throughout, the MAV keeps hovering while the
inputs are invalid (extreme ones may be valid commands: a 1e30 m set point is flown towards at the
tilt limit, so afterwards the set point is sent again and the MAV must come back), and rejections
are rate-limited (a handful of log lines per second, not one per message; Debian's
robot_state_publisher, not ours, logs each invalid JointState). The test prints a table.

Left out, with the reason: /clock (the simulator's own output: a second publisher is a set-up error,
not an input), /rosout (ROS' log aggregation), the Empty services pause/unpause/reset (no payload;
their effects are tested in test_faults.py) and roscpp's get_loggers/set_logger_level."""
from pathlib import Path

import pytest
from conftest import NODE_PROCESS_HELPERS, RosGraph, stop_launch, wait_sim_time

FUZZ = r'''
import importlib, math, random, rosgraph, rosservice
from struct import error as struct_error
import genpy
from nav_msgs.msg import Odometry
from geometry_msgs.msg import PoseStamped
from std_srvs.srv import Empty

random.seed(14)
NAN, INF = float('nan'), float('inf')
INT_RANGES = {'int8': (-2**7, 2**7 - 1), 'uint8': (0, 2**8 - 1), 'byte': (-2**7, 2**7 - 1), 'char': (0, 255),
              'int16': (-2**15, 2**15 - 1), 'uint16': (0, 2**16 - 1), 'int32': (-2**31, 2**31 - 1),
              'uint32': (0, 2**32 - 1), 'int64': (-2**63, 2**63 - 1), 'uint64': (0, 2**64 - 1)}
STRINGS = ['', 'no_such_frame', 'x' * 10000, '\u00e9\u00e8 world']
MASTER = rosgraph.Master('/pytest_client')
LOG = open(LOG_PATH, errors='replace')

def msg_class(type_name):
    if type_name == 'Header':
        type_name = 'std_msgs/Header'
    pkg, name = type_name.split('/')
    return getattr(importlib.import_module(pkg + '.msg'), name)

def scalar(base, mode):
    if base in ('float64', 'float32'):
        return random.choice([NAN, INF, -INF]) if mode == 'invalid' else \
            random.choice([1e30, -1e30, 1e-300, 0.0, random.gauss(0, 10)])
    if base in INT_RANGES:
        lo, hi = INT_RANGES[base]
        return random.choice([lo, hi, -1 if lo < 0 else hi])
    if base == 'bool':
        return random.random() < 0.5
    if base == 'string':
        return random.choice(STRINGS)
    if base == 'time':
        return genpy.Time(random.choice([0, 1, 2**31 - 1]), 0)
    if base == 'duration':
        return genpy.Duration(random.choice([-2**31, -1, 0, 2**31 - 1]), 0)
    return fill(msg_class(base)(), mode)

def value(type_name, mode):
    if not type_name.endswith(']'):
        return scalar(type_name, mode)
    base, size = type_name[:type_name.index('[')], type_name[type_name.index('[') + 1:-1]
    n = int(size) if size else random.choice([0, 1, 1000] if base in INT_RANGES or base.startswith('float')
                                              else [0, 1, 3, 50])
    if base in ('uint8', 'char'):
        return bytes(random.getrandbits(8) for _ in range(n))
    return [scalar(base, mode) for _ in range(n)]

def fill(msg, mode):
    for name, type_name in zip(msg.__slots__, msg._slot_types):
        setattr(msg, name, value(type_name, mode))
    if mode == 'invalid' and msg._type == 'geometry_msgs/Quaternion' and random.random() < 0.3:
        msg.x = msg.y = msg.z = msg.w = 0.0  # the zero quaternion
    return msg

state = {'p': None, 'finite': True, 'samples': 0}
def on_odom(m):
    p, q = m.pose.pose.position, m.pose.pose.orientation
    values = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, m.twist.twist.linear.x, m.twist.twist.angular.z]
    state['finite'] = state['finite'] and all(math.isfinite(v) for v in values)
    state['p'] = (p.x, p.y, p.z)
    state['samples'] += 1
rospy.Subscriber('/firefly/ground_truth/odometry', Odometry, on_odom, queue_size=1)
set_point = rospy.Publisher('/firefly/command/pose', PoseStamped, queue_size=1, latch=True)
def send_set_point():
    cmd = PoseStamped()
    cmd.pose.position.z = 1.0
    cmd.pose.orientation.w = 1.0
    set_point.publish(cmd)

def log_lines():
    return len(LOG.readlines())

while state['p'] is None:
    time.sleep(0.05)
hover = state['p']
nodes = {n: node_pid(n) for n in WATCHED}
_, subscribers, services = MASTER.getSystemState()
types = dict(MASTER.getTopicTypes())
SKIP_TOPICS = {'/clock', '/rosout'}
targets = sorted((t, sorted(n for n in subs if not n.startswith(('/pytest_client', '/fuzz'))))
                 for t, subs in subscribers if t not in SKIP_TOPICS)
targets = [(t, subs) for t, subs in targets if subs]
rows = []

def fuzz_topic(topic, cls, mode, period_s=1.0, rate_hz=100.0):
    pub = rospy.Publisher(topic, cls, queue_size=10)
    deadline = time.monotonic() + 3.0
    while pub.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.02)
    log_lines()  # skip what came before
    sent, worst = 0, 0.0
    end = time.monotonic() + period_s
    while time.monotonic() < end:
        try:
            pub.publish(fill(cls(), mode))
            sent += 1
        except (genpy.SerializationError, struct_error, ValueError, TypeError, OverflowError):
            pass  # not representable on the wire: nothing is sent
        worst = max(worst, math.dist(state['p'], hover))
        time.sleep(1.0 / rate_hz)
    time.sleep(0.3)
    worst = max(worst, math.dist(state['p'], hover))
    pub.unregister()
    return sent, log_lines(), worst

for topic, subs in targets:
    cls = msg_class(types[topic])
    row = {'name': topic, 'type': types[topic], 'receivers': ' '.join(subs)}
    state['finite'] = True
    row['invalid'], row['invalid_log_lines'], row['invalid_offset'] = fuzz_topic(topic, cls, 'invalid')
    row['extreme'], row['extreme_log_lines'], _ = fuzz_topic(topic, cls, 'extreme')
    row['finite'] = state['finite']
    row['crashed'] = [n for n, p in nodes.items() if not alive(p)]
    # extreme inputs may be valid commands: send the set point again; the MAV must come back
    send_set_point()
    deadline = time.monotonic() + 12.0
    while math.dist(state['p'], hover) > 0.05 and time.monotonic() < deadline:
        time.sleep(0.05)
    row['recovered'] = math.dist(state['p'], hover) <= 0.05
    if not row['recovered']:
        rospy.ServiceProxy('/gazebo/reset_world', Empty)()
        send_set_point()
        time.sleep(8.0)
    rows.append(row)

SKIP_SERVICES = ('/gazebo/pause_physics', '/gazebo/unpause_physics', '/gazebo/reset_world',
                 '/gazebo/reset_simulation')
for name, _providers in sorted(services):
    if name.endswith(('/get_loggers', '/set_logger_level')) or name in SKIP_SERVICES:
        continue
    srv = rosservice.get_service_class_by_name(name)
    row = {'name': name, 'type': srv._type, 'receivers': ' '.join(_providers)}
    state['finite'] = True
    log_lines()
    calls, refused, worst = 0, 0, 0.0
    proxy = rospy.ServiceProxy(name, srv)
    for _ in range(20):
        request = fill(srv._request_class(), 'invalid')
        try:
            response = proxy(request)
            calls += 1
            if getattr(response, 'success', True) is False:
                refused += 1
        except rospy.ServiceException:
            calls += 1
            refused += 1
        except (genpy.SerializationError, struct_error, ValueError, TypeError, OverflowError):
            pass
        worst = max(worst, math.dist(state['p'], hover))
    time.sleep(0.3)
    row.update(invalid=calls, invalid_log_lines=log_lines(), invalid_offset=worst, extreme=0,
               extreme_log_lines=0, finite=state['finite'], recovered=True,
               crashed=[n for n, p in nodes.items() if not alive(p)], refused=refused)
    rows.append(row)
result['rows'] = rows
result['samples'] = state['samples']
'''

WATCHED = ["/gazebo", "/firefly/lee_position_controller_node", "/firefly/robot_state_publisher", "/bystanders/msf",
           "/bystanders/roll_pitch_yawrate_thrust_controller_node", "/bystanders/rotors_joy_interface",
           "/bystanders/planner", "/bystanders/mapping", "/bystanders/omav_pose_controller_node",
           "/bystanders/fixed_wing_joy_interface"]

# The hovering example with the camera gimbal (its command topics in the simulator), plus the
# project's other input-taking nodes outside its control loop ("bystanders": the estimator, the
# attitude controller, the joystick mapping for multirotors and for the fixed wing, the planner, the
# mapping node and the omav's pose controller), so that their inputs are fuzzed too without steering
# the MAV.
FUZZ_LAUNCH = """<launch>
  <include file="$(find rotors_gazebo)/launch/mav_hovering_example.launch">
    <arg name="real_time_factor" value="1"/>
    <arg name="gui" value="false"/>
    <arg name="enable_gimbal" value="true"/>
  </include>
  <group ns="bystanders">
    <node name="msf" pkg="msf_updates" type="pose_sensor" clear_params="true" output="screen">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/msf_simulator.yaml"/>
    </node>
    <node name="roll_pitch_yawrate_thrust_controller_node" pkg="rotors_control"
          type="roll_pitch_yawrate_thrust_controller_node" output="screen">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/roll_pitch_yawrate_thrust_controller_firefly.yaml"/>
      <rosparam command="load" file="$(find rotors_gazebo)/resource/firefly.yaml"/>
    </node>
    <node name="rotors_joy_interface" pkg="rotors_joy_interface" type="rotors_joy_interface" output="screen"/>
    <node name="fixed_wing_joy_interface" pkg="rotors_joy_interface" type="rotors_joy_interface" output="screen">
      <param name="is_fixed_wing" value="true"/>
      <remap from="joy" to="fixed_wing_joy"/>
    </node>
    <node name="planner" pkg="rotors_planning" type="rotors_planner_node" output="screen">
      <param name="map_source" value="topic"/>
      <param name="robot_radius" value="0.3"/>
    </node>
    <node name="mapping" pkg="rotors_planning" type="rotors_mapping_node" output="screen">
      <param name="frame_id" value="world"/>
    </node>
    <node name="omav_pose_controller_node" pkg="rotors_control" type="omav_pose_controller_node" output="screen">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/omav_pose_controller.yaml"/>
      <rosparam command="load" file="$(find rotors_gazebo)/resource/omav.yaml"/>
    </node>
  </group>
</launch>
"""
# Debian's robot_state_publisher (not ours) logs one line per invalid JointState, and tf2's
# BufferCore (in every node with a tf2 listener, here the mapping node) one per invalid transform;
# neither may crash.
NOT_RATE_LIMITED_UPSTREAM = {"/firefly/joint_states", "/tf", "/tf_static"}


@pytest.mark.long  # the long tier: make test-all / make test-long
def test_fuzzing_every_input_of_the_hovering_example(ros: RosGraph, tmp_path: Path):
    launch_file = tmp_path / "fuzz.launch"
    launch_file.write_text(FUZZ_LAUNCH)
    proc = ros.start(["roslaunch", "-p", str(ros.port), str(launch_file)], "launch")
    try:
        wait_sim_time(ros, 10.0)
        prelude = f"LOG_PATH = {str(Path(proc.log_path))!r}\nWATCHED = {WATCHED!r}\n"
        res = ros.rospy(prelude + NODE_PROCESS_HELPERS + FUZZ, timeout=900)
    finally:
        stop_launch(proc)
    rows = res["rows"]
    header = (f"{'topic / service':44} {'type':36} {'invalid':>7} {'extreme':>7} {'crashes':>7} {'non-finite':>10} "
              f"{'offset (inv.)':>13} {'log lines/s':>11} {'back':>5}")
    print("\n" + header + "\n" + "-" * len(header))
    for r in rows:
        lines_per_s = max(r["invalid_log_lines"], r["extreme_log_lines"])
        print(f"{r['name']:44} {r['type']:36} {r['invalid']:7d} {r['extreme']:7d} {len(r['crashed']):7d} "
              f"{0 if r['finite'] else 1:10d} {r['invalid_offset'] * 1000:10.1f} mm {lines_per_s:11d} "
              f"{'yes' if r['recovered'] else 'reset':>5}")
    print(f"{len(rows)} inputs, {sum(r['invalid'] + r['extreme'] for r in rows)} messages and calls, "
          f"{res['samples']} states sampled")
    names = {r["name"] for r in rows}
    for expected in ("/firefly/command/motor_speed", "/firefly/gazebo/command/motor_speed",
                     "/firefly/command/trajectory", "/firefly/command/pose", "/firefly/odometry_sensor1/odometry",
                     "/firefly/motor_failure", "/gazebo/spawn_urdf_model", "/gazebo/delete_model",
                     "/firefly/set_motor_failure", "/bystanders/msf_core/imu_state_input",
                     "/bystanders/msf_updates/pose_with_covariance_input", "/bystanders/command/roll_pitch_yawrate_thrust",
                     "/bystanders/joy", "/bystanders/msf/pose_sensor/initialize_msf_scale",
                     "/bystanders/fixed_wing_joy", "/bystanders/goal", "/bystanders/octomap_binary",
                     "/bystanders/cloud_in", "/firefly/gimbal_pitch_cmd"):
        assert expected in names, f"{expected} was not fuzzed: {sorted(names)}"
    for r in rows:
        assert r["crashed"] == [], f"{r['name']}: {r['crashed']} crashed"
        assert r["finite"], f"{r['name']}: the physics state became non-finite"
        assert r["invalid_offset"] < 0.05, f"{r['name']}: invalid input moved the MAV {r['invalid_offset']:.3f} m"
        assert r["name"] in NOT_RATE_LIMITED_UPSTREAM or (r["invalid_log_lines"] <= 12 and r["extreme_log_lines"] <= 12), (
            f"{r['name']}: {r['invalid_log_lines']} / {r['extreme_log_lines']} log lines in 1 s: not rate-limited")
        assert r["recovered"], f"{r['name']}: the MAV did not come back to its set point after the extreme inputs"
