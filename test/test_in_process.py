"""Controllers in the simulator's process (in_process:=true: a nodelet on the simulation thread,
messages in memory) fly the flight they fly as separate nodes, bit for bit in lockstep; and the
rotors as kinematic joints on the body (the default) fly the flight that hinged rotor bodies fly,
within 0.1 mm."""

import numpy as np
import pytest
from rosbags.rosbag1 import Reader
from rosbags.typesys import Stores, get_typestore

from support import RosGraph
from support.flights import assert_identical_flights, fly_once, messages


def without_seq(msgs, topic: str = "firefly/command/motor_speed"):
    """header.seq zeroed on `topic`: roscpp numbers it when it serializes a message, so the
    controller's commands carry 1, 2, ... over TCP and 0 when handed over in memory."""
    return [(t, stamp, b"\0\0\0\0" + payload[4:] if t == topic else payload) for t, stamp, payload in msgs]


def test_in_process_controller_flies_the_same_flight_bit_for_bit(ros: RosGraph):
    separate = without_seq(messages(fly_once(ros, "separate"), 5.5))
    in_process = without_seq(messages(fly_once(ros, "in_process", "in_process:=true"), 5.5))
    assert_identical_flights(separate, in_process)


def positions(bag, topic: str = "firefly/ground_truth/pose") -> np.ndarray:
    store = get_typestore(Stores.ROS1_NOETIC)
    out = []
    with Reader(bag) as r:
        for conn, t, raw in r.messages(connections=[c for c in r.connections if c.topic.lstrip("/") == topic]):
            p = store.deserialize_ros1(raw, conn.msgtype).pose.position
            out.append((t, p.x, p.y, p.z))
    return np.array(sorted(out))


@pytest.mark.long  # the long tier (about 20-25 s): make test under 25 min
def test_lumped_and_hinged_rotors_fly_the_same_hover(ros: RosGraph):
    lumped = positions(fly_once(ros, "lumped"))
    hinged = positions(fly_once(ros, "hinged", "lump_rotors:=false"))
    n = min(len(lumped), len(hinged))
    assert n > 500
    assert np.array_equal(lumped[:n, 0], hinged[:n, 0])  # the same stamps
    climb = lumped[:n, 3].max() - lumped[0, 3]
    assert climb > 0.8, f"it climbed {climb:.3f} m only"  # a real flight: from the ground to 1 m
    gap = np.abs(lumped[:n, 1:] - hinged[:n, 1:]).max()
    print(f"lumped vs hinged rotors: largest position difference {gap:.2e} m over {n} poses")
    assert gap < 1e-4, f"the lumped and hinged flights differ by {gap * 1000:.3f} mm"
