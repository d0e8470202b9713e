"""RotorS' HIL interface without mavros (rotors_hil_interface_node, fixed_wing_hil.launch): the
techpod's sensors go to the autopilot as HIL_SENSOR (100 Hz, FRD through the body-to-sensor roll
of pi) and HIL_GPS (5 Hz); the autopilot's controls come back as mav_msgs/Actuators; hil_cli's
arm, HIL mode and reboot reach it as MAVLink commands. No autopilot board is on these machines:
pymavlink on a UDP socket stands in for it (the node's serial path is pymavlink's own).
"""

import threading
import time

import numpy as np
from pymavlink import mavutil

import clients.hil_interface
from support import launch, wait_until
from support.net import free_udp_port


class AutopilotStandIn:
    """The autopilot's end of the link, read on a thread of its own (the node sends 100 HIL_SENSOR a
    second: an unread UDP socket would overflow and drop what matters)."""

    def __init__(self, port: int):
        self.link = mavutil.mavlink_connection(f"udpin:127.0.0.1:{port}", source_system=1, source_component=1)
        self.messages, self.lock, self.stop = [], threading.Lock(), False
        self.thread = threading.Thread(target=self.read, daemon=True)
        self.thread.start()

    def read(self):
        while not self.stop:
            m = self.link.recv_match(blocking=True, timeout=0.2)
            if m is not None:
                with self.lock:
                    self.messages.append(m)

    def of_type(self, kind):
        with self.lock:
            return [m for m in self.messages if m.get_type() == kind]

    def wait_for(self, kind, count=1, timeout=60.0, since_usec=0):
        """The first `count` messages of `kind` stamped at or after `since_usec` of sim time."""

        def enough() -> list:
            found = [m for m in self.of_type(kind) if getattr(m, "time_usec", 0) >= since_usec]
            return found[:count] if len(found) >= count else []

        return wait_until(enough, timeout, f"{count} {kind} from the node since {since_usec} us")


def test_fixed_wing_hil_launch_exchanges_hil_with_autopilot(ros):
    port = free_udp_port()
    autopilot = AutopilotStandIn(port)
    # seeded, so that the IMU's turn-on bias is the same draw in every run
    launch(ros, "rotors_gazebo", "fixed_wing_hil.launch", f"mavlink_url:=udpout:127.0.0.1:{port}", "random_seed:=11")
    autopilot.wait_for("HIL_SENSOR", 1, timeout=90)
    autopilot.link.mav.heartbeat_send(1, 3, 0, 0, 0)  # the node answers to the first heartbeat's system
    # 2 s once the techpod has come to rest: it is spawned 0.1 m up and the world runs from launch
    # (unpaused, as fast as it can), so the node's first samples can hold the drop and the bounces
    sensors = autopilot.wait_for("HIL_SENSOR", 200, since_usec=3_000_000)
    gps = autopilot.of_type("HIL_GPS")
    rate = (len(sensors) - 1) / ((sensors[-1].time_usec - sensors[0].time_usec) * 1e-6)
    s = sensors[-1]
    print(
        f"{len(sensors)} HIL_SENSOR at {rate:.0f} Hz of sim time, {len(gps)} HIL_GPS; at rest: acc "
        f"({s.xacc:.2f}, {s.yacc:.2f}, {s.zacc:.2f}) m/s^2, {s.abs_pressure:.1f} hPa, mag z {s.zmag:.3f} G"
    )
    assert 90 < rate < 110
    # FRD: the specific force at rest is g up, -z; the mean of 2 s keeps the ADIS16448's turn-on bias
    # (sigma 0.196 m/s^2 an axis) and the techpod rests a little pitched on its belly: its length is g
    # within 1.0 m/s^2 (5 sigma of the bias along g: no seed's draw fails it) and it points within
    # 10 deg of -z
    mean = np.mean([[m.xacc, m.yacc, m.zacc] for m in sensors], axis=0)
    assert abs(np.linalg.norm(mean) - 9.81) < 1.0 and -mean[2] > np.cos(np.radians(10.0)) * np.linalg.norm(mean), mean
    assert s.zmag > 0.3 and all(m.fields_updated & 0x3F == 0x3F for m in sensors)  # accel and gyro each time
    # magnetometer and barometer bits when their plugins published since the last HIL_SENSOR
    assert sum(m.fields_updated & 0x1FC0 == 0x1BC0 for m in sensors) > len(sensors) / 2
    assert gps and gps[-1].fix_type == 3 and abs(gps[-1].lat) > 0
    # the autopilot's controls: mav_msgs/Actuators, normalized, on command/motor_speed
    results = {}
    listener = threading.Thread(target=lambda: results.update(ros.run_client(clients.hil_interface.normalized_controls)))
    listener.start()
    end = time.monotonic() + 5.0
    while listener.is_alive() and time.monotonic() < end:  # the autopilot answers on its link
        autopilot.link.mav.hil_actuator_controls_send(0, [0.1, -0.2, 0.3, 0, 0, 0.8] + [0.0] * 10, 129, 0)
        time.sleep(0.02)
    listener.join(30)
    print("Actuators.normalized:", [round(v, 3) for v in results["normalized"][:6]])
    assert [round(v, 3) for v in results["normalized"][:6]] == [0.1, -0.2, 0.3, 0.0, 0.0, 0.8]
    # hil_cli: arm and reboot as commands to the autopilot, HIL mode as SET_MODE
    for action in ("arm", "reboot", "hil"):
        out = ros.run(["rosrun", "rotors_hil_interface", "hil_cli", action, "--node", "/techpod/rotors_hil_interface_node"])
        print(out.stdout.strip())
    commands = autopilot.wait_for("COMMAND_LONG", 2, timeout=10)
    assert [(m.command, m.param1, m.target_system) for m in commands] == [(400, 1.0, 1), (246, 1.0, 1)]
    mode = autopilot.wait_for("SET_MODE", 1, timeout=10)[0]
    assert mode.base_mode & mavutil.mavlink.MAV_MODE_FLAG_HIL_ENABLED and mode.target_system == 1
    autopilot.stop = True


def test_one_frames_module_the_codecs_and_the_hil_node_share():
    """rotors_sim.frames is rotors_plugins' autopilot/frames.h, bound: checked here against the
    rotation matrices (R_NED_FRD = T_NED_ENU R_ENU_FLU T_FLU_FRD) for random attitudes, and the HIL
    node's HIL_STATE_QUATERNION fields use it."""
    import numpy as np

    from rotors_hil_interface import hil_messages as hm
    from rotors_sim import frames

    T_NED_ENU = np.array([[0, 1, 0], [1, 0, 0], [0, 0, -1]])
    T_FLU_FRD = np.diag([1, -1, -1])
    rng = np.random.default_rng(7)
    for _ in range(20):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        R_ENU_FLU = np.array([hm.world_from_body(q, e) for e in np.eye(3)]).T
        q_ned = np.asarray(frames.ned_frd_from_enu_flu(q))
        R_NED_FRD = np.array([hm.world_from_body(q_ned, e) for e in np.eye(3)]).T
        np.testing.assert_allclose(R_NED_FRD, T_NED_ENU @ R_ENU_FLU @ T_FLU_FRD, atol=1e-12)
        assert q_ned[0] >= 0.0
        v = rng.normal(size=3)
        np.testing.assert_allclose(frames.ned_from_enu(v), T_NED_ENU @ v)
        np.testing.assert_allclose(frames.frd_from_flu(v), T_FLU_FRD @ v)
        fields = hm.hil_state_fields(q, v, v, 47.0, 8.0, 500.0, hm.world_from_body([q[0], -q[1], -q[2], -q[3]], [0, 0, 9.80665]))
        np.testing.assert_allclose(fields["attitude_quaternion"], q_ned, atol=1e-7)
        assert max(abs(fields["xacc"]), abs(fields["yacc"]), abs(fields["zacc"])) <= 1  # at rest: a = 0
