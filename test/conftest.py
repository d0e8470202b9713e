"""Shared fixtures: an isolated ROS master per test and a way to run rospy code in a child process
(rospy can be initialised once per process, so the test process itself never calls init_node)."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path
from typing import Dict, Iterator, List

import pytest
from rotors_evaluation.processes import kill_graph_leftovers, restore_sigint, stop_process_group
from rotors_evaluation.ros_master import start_own_master

REPO = Path(__file__).resolve().parents[1]


def pytest_configure(config):
    restore_sigint()  # run as a background job (nohup make test &), the ROS processes would ignore Ctrl-C
    config.addinivalue_line("markers", "long: the long tier (minutes each): run by make test-all and make test-long, "
                                       "not by make test")
# make test-sanitize points ROTORS_WS at a sanitizer's workspace (scripts/test_sanitize.sh)
WS = Path(os.environ.get("ROTORS_WS", REPO / "build" / "ws"))


# Process helpers for rospy client code (RosGraph.rospy): a node's pid from the master, whether a
# pid lives (not a zombie), its CPU seconds.
NODE_PROCESS_HELPERS = """
import os, rosgraph, xmlrpc.client
def node_pid(name):
    uri = rosgraph.Master('/pytest_client').lookupNode(name)
    return xmlrpc.client.ServerProxy(uri).getPid('/pytest_client')[2]
def _stat_fields(pid):
    return open('/proc/%d/stat' % pid).read().rsplit(')', 1)[1].split()
def alive(pid):
    try:
        return _stat_fields(pid)[0] != 'Z'
    except OSError:
        return False
def cpu_seconds(pid):
    fields = _stat_fields(pid)
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')
"""


class RosGraph:
    """A private ROS master plus the processes a test starts against it."""

    def __init__(self, tmp_path: Path):
        self.env = dict(os.environ)
        self.env["ROS_HOME"] = str(tmp_path / "ros_home")
        self.env["ROS_LOG_DIR"] = str(tmp_path / "ros_log")
        self.tmp_path = tmp_path
        self.procs: List[subprocess.Popen] = []
        # the master is started on a port verified to be its own (runs may overlap)
        master, self.port = start_own_master(self.env, tmp_path / "master.log")
        master.log_path = tmp_path / "master.log"  # type: ignore[attr-defined]
        self.procs.append(master)
        self.env["ROS_MASTER_URI"] = f"http://127.0.0.1:{self.port}"
        self.wait_for(lambda: self.run(["rosparam", "set", "/use_sim_time", "true"], check=False).returncode == 0, 20)

    def start(self, cmd: List[str], name: str) -> subprocess.Popen:
        log = open(self.tmp_path / f"{name}.log", "w")
        p = subprocess.Popen(cmd, env=self.env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        p.log_path = self.tmp_path / f"{name}.log"  # type: ignore[attr-defined]
        self.procs.append(p)
        return p

    def run(self, cmd: List[str], check: bool = True, timeout: float = 60) -> subprocess.CompletedProcess:
        res = subprocess.run(cmd, env=self.env, capture_output=True, text=True, timeout=timeout)
        if check and res.returncode != 0:
            raise AssertionError(f"{cmd} failed ({res.returncode}): {res.stdout}{res.stderr}")
        return res

    def rospy(self, code: str, timeout: float = 120) -> Dict:
        """Runs `code` after rospy.init_node in a child process; it fills the dict `result`."""
        script = "import json, sys, time, rospy\nrospy.init_node('pytest_client', anonymous=True)\nresult = {}\n"
        script += textwrap.dedent(code) + "\nprint('RESULT=' + json.dumps(result))\n"
        res = subprocess.run([sys.executable, "-c", script], env=self.env, capture_output=True, text=True,
                             timeout=timeout)
        for line in res.stdout.splitlines():
            if line.startswith("RESULT="):
                return json.loads(line[len("RESULT="):])
        raise AssertionError(f"rospy client failed ({res.returncode}):\n{res.stdout}\n{res.stderr}")

    @staticmethod
    def wait_for(predicate, timeout: float, period: float = 0.2) -> bool:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if predicate():
                return True
            time.sleep(period)
        return False

    def stop(self) -> None:
        for p in reversed(self.procs):
            if p.poll() is None:
                try:
                    os.killpg(p.pid, signal.SIGINT)
                except ProcessLookupError:
                    pass
        for p in reversed(self.procs):
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                print(f"TEARDOWN-TIMEOUT {p.args}", file=sys.stderr)
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        # the nodes of a roslaunch that was SIGKILLed (a fault test, or the timeout above) outlive it,
        # each in a session of its own: whatever still talks to this graph's master goes too
        kill_graph_leftovers(self.port)


@pytest.fixture
def ros(tmp_path: Path) -> Iterator[RosGraph]:
    graph = RosGraph(tmp_path)
    try:
        yield graph
    finally:
        graph.stop()


def package_path(name: str) -> Path:
    res = subprocess.run(["rospack", "find", name], capture_output=True, text=True, check=True)
    return Path(res.stdout.strip())


def launch(ros: RosGraph, package: str, launch_file: str, *args: str, name: str = "launch") -> subprocess.Popen:
    """roslaunch against this graph's master (headless)."""
    gui = [] if any(a.startswith("gui:=") for a in args) else ["gui:=false"]
    return ros.start(["roslaunch", "-p", str(ros.port), package, launch_file, *gui, *args], name)


def wait_sim_time(ros: RosGraph, t_s: float, timeout_s: float = 300.0) -> float:
    """Blocks until /clock reaches t_s; returns the sim time seen."""
    return ros.rospy(f"""
        from rosgraph_msgs.msg import Clock
        deadline = time.monotonic() + {timeout_s}
        t = 0.0
        while t < {t_s}:
            if time.monotonic() > deadline:
                raise SystemExit('sim time stuck at %.2f s' % t)
            try:
                t = rospy.wait_for_message('/clock', Clock, timeout=5).clock.to_sec()
            except rospy.ROSException:
                pass
        result['t'] = t
    """, timeout=timeout_s + 60)["t"]


def send_hover_pose(ros: RosGraph, then: str = "") -> Dict:
    """Sends the set point (0, 0, 1) latched on /firefly/command/pose once the controller listens,
    then runs the rospy code `then` in the same client (the latched message lives as long as it);
    returns the `result` that code filled."""
    return ros.rospy(textwrap.dedent("""
        from geometry_msgs.msg import PoseStamped
        pub = rospy.Publisher('/firefly/command/pose', PoseStamped, queue_size=1, latch=True)
        while pub.get_num_connections() == 0:  # the controller is up and listens to poses
            time.sleep(0.05)
        cmd = PoseStamped()
        cmd.pose.position.z = 1.0
        cmd.pose.orientation.w = 1.0
        pub.publish(cmd)
        time.sleep(1.0)
    """) + textwrap.dedent(then))


def stop_launch(proc: subprocess.Popen, timeout: float = 30.0) -> None:
    """SIGINT as Ctrl-C does, so that bags are closed and indexed."""
    stop_process_group(proc, timeout)
