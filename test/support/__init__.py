"""What the tests share: paths, an isolated ROS master per test (RosGraph) and a way to run rospy
client code (the functions of test/clients/) in a child process (rospy can be initialised once per
process, so the test process itself never calls init_node), roslaunch against it, and waits."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import clients.sim
from clients.waits import poll as poll
from clients.waits import wait_until as wait_until
from rotors_evaluation.processes import kill_graph_leftovers, stop_process_group
from rotors_evaluation.ros_master import start_own_master

REPO = Path(__file__).resolve().parents[2]
TESTS = Path(__file__).resolve().parents[1]  # holds the package clients/


# a rospy client's waits end this long before run_client's timeout: time to start up, report and exit
CLIENT_REPORT_MARGIN_S = 10.0

# make test-sanitize points ROTORS_WS at a sanitizer's workspace (scripts/test_sanitize.sh)
WS = Path(os.environ.get("ROTORS_WS", REPO / "build" / "ws"))


def retry_until(make: Callable[[], Any], timeout_s: float, what: str, errors=(OSError,), period_s: float = 0.05) -> Any:
    """make() once it stops raising one of `errors` (a socket that nobody listens on yet), at most
    timeout_s of wall time; an AssertionError says what did not happen, with the last error."""
    deadline = time.monotonic() + timeout_s
    while True:
        try:
            return make()
        except errors as e:
            assert time.monotonic() < deadline, f"{what}: not within {timeout_s:g} s ({e})"
            time.sleep(period_s)


def client_name(function: Callable) -> str:
    """ "clients.module:name" of a function of test/clients/ (the child process imports it by name)."""
    module = getattr(function, "__module__", "")
    if not callable(function) or not module.startswith("clients."):
        raise TypeError(f"{function!r} is not a function of a module of test/clients/")
    return f"{module}:{function.__name__}"


class RosGraph:
    """A private ROS master plus the processes a test starts against it."""

    def __init__(self, tmp_path: Path):
        self.env = dict(os.environ)
        self.env["ROS_HOME"] = str(tmp_path / "ros_home")
        self.env["ROS_LOG_DIR"] = str(tmp_path / "ros_log")
        self.tmp_path = tmp_path
        self.procs: list[subprocess.Popen] = []
        # the master is started on a port verified to be its own (runs may overlap)
        master, self.port = start_own_master(self.env, tmp_path / "master.log")
        master.log_path = tmp_path / "master.log"  # type: ignore[attr-defined]
        self.procs.append(master)
        self.env["ROS_MASTER_URI"] = f"http://127.0.0.1:{self.port}"
        assert self.wait_for(
            lambda: self.run(["rosparam", "set", "/use_sim_time", "true"], check=False).returncode == 0, 20
        ), f"the ROS master on port {self.port} did not take /use_sim_time within 20 s"

    def start(self, cmd: list[str], name: str) -> subprocess.Popen:
        log = open(self.tmp_path / f"{name}.log", "w")
        p = subprocess.Popen(cmd, env=self.env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        p.log_path = self.tmp_path / f"{name}.log"  # type: ignore[attr-defined]
        self.procs.append(p)
        return p

    def run(self, cmd: list[str], check: bool = True, timeout: float = 60) -> subprocess.CompletedProcess:
        res = subprocess.run(cmd, env=self.env, capture_output=True, text=True, timeout=timeout)
        if check and res.returncode != 0:
            raise AssertionError(f"{cmd} failed ({res.returncode}): {res.stdout}{res.stderr}")
        return res

    def rospy(self, code: str, timeout: float = 120) -> dict:
        """Runs `code` after rospy.init_node in a child process; it fills the dict `result`. Tests call
        run_client, which runs a function of test/clients/ this way."""
        script = "import json, sys, time, rospy\nrospy.init_node('pytest_client', anonymous=True)\nresult = {}\n"
        script += textwrap.dedent(code) + "\nprint('RESULT=' + json.dumps(result))\n"
        res = subprocess.run([sys.executable, "-c", script], env=self.env, capture_output=True, text=True, timeout=timeout)
        for line in res.stdout.splitlines():
            if line.startswith("RESULT="):
                return json.loads(line[len("RESULT=") :])
        raise AssertionError(f"rospy client failed ({res.returncode}):\n{res.stdout}\n{res.stderr}")

    def run_client(self, function: Callable, timeout: float = 120, **kwargs) -> dict:
        """Runs `function` (a function of a module of test/clients/, e.g. clients.wind.speed_pairs) in a
        child process after rospy.init_node, called with `kwargs` (sent as JSON: str, numbers, bools,
        lists, dicts); returns what it returned (a JSON-serialisable dict; none gives {}). The
        client's waits share a budget of `timeout` less CLIENT_REPORT_MARGIN_S, so that a wait that
        runs out says what did not happen before the timeout ends the process."""
        budget_s = max(timeout - CLIENT_REPORT_MARGIN_S, 1.0)
        code = (
            f"sys.path.insert(0, {str(TESTS)!r})\n"
            "from clients import call\n"
            f"result = call({client_name(function)!r}, json.loads({json.dumps(kwargs)!r}), budget_s={budget_s!r})\n"
        )
        return self.rospy(code, timeout=timeout)

    @staticmethod
    def wait_for(predicate, timeout: float, period: float = 0.2) -> bool:
        """Whether `predicate` came true within `timeout` s (poll); the caller says what failed."""
        return bool(poll(predicate, timeout, period))

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


def package_path(name: str) -> Path:
    res = subprocess.run(["rospack", "find", name], capture_output=True, text=True, check=True)
    return Path(res.stdout.strip())


def launch(ros: RosGraph, package: str, launch_file: str, *args: str, name: str = "launch") -> subprocess.Popen:
    """roslaunch against this graph's master (headless)."""
    gui = [] if any(a.startswith("gui:=") for a in args) else ["gui:=false"]
    return ros.start(["roslaunch", "-p", str(ros.port), package, launch_file, *gui, *args], name)


def wait_sim_time(ros: RosGraph, t_s: float, timeout_s: float = 300.0) -> float:
    """Blocks until /clock reaches t_s; returns the sim time seen."""
    return ros.run_client(clients.sim.wait_sim_time, timeout=timeout_s + 60, t_s=t_s, timeout_s=timeout_s)["t"]


def send_hover_pose(ros: RosGraph, then: Callable | None = None, **kwargs) -> dict:
    """Sends the set point (0, 0, 1) latched on /firefly/command/pose once the controller listens,
    then calls the client function `then` (a function of test/clients/) with `kwargs` in the same
    client (the latched message lives as long as it); returns what that function returned ({} without one)."""
    return ros.run_client(clients.sim.send_hover_pose, then=client_name(then) if then else "", then_kwargs=kwargs)


def rate_from_stamps(stamps) -> float:
    """Messages per second from consecutive stamps [s]: the mean interval, leaving out an interval
    that holds a message the receiver dropped (one of 1.5 x the median interval or more; a 30 Hz
    camera on 10 ms steps has intervals of 30 and 40 ms, which a plain median reads as 33.3 Hz)."""
    gaps = np.diff(np.asarray(stamps, dtype=float))
    return float(1.0 / np.mean(gaps[gaps < 1.5 * np.median(gaps)]))


def stop_launch(proc: subprocess.Popen, timeout: float = 30.0) -> None:
    """SIGINT as Ctrl-C does, so that bags are closed and indexed."""
    stop_process_group(proc, timeout)
