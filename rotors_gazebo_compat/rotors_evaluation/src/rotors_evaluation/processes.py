"""Stopping a process and its process group as Ctrl-C does: SIGINT (roslaunch then stops its nodes
and the bag plugin closes its bag), then SIGKILL after a grace time."""

import os
import re
import signal
import subprocess
from pathlib import Path


def restore_sigint() -> None:
    """Makes SIGINT interrupt again in this process and in the processes it starts. A shell starts
    a background job (`cmd &`, nohup) with SIGINT ignored, and an ignored signal stays ignored
    across exec: every ROS process started from there would ignore the Ctrl-C that stops it
    cleanly (roslaunch closing its bags), and each stop would wait out its grace time and SIGKILL."""
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def stop_process_group(proc: subprocess.Popen | None, grace_s: float, first_signal: int = signal.SIGINT) -> bool:
    """Sends first_signal to proc's process group (proc must lead one: start_new_session=True or
    setsid) and waits up to grace_s; then SIGKILL. True when it stopped within the grace time."""
    if proc is None or proc.poll() is not None:
        return True
    try:
        os.killpg(proc.pid, first_signal)
        proc.wait(timeout=grace_s)
        return True
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait(timeout=30)
        return False
    except ProcessLookupError:
        proc.wait(timeout=30)
        return True


def graph_processes(port: int, comm: str = "") -> list[int]:
    """Pids of the processes that talk to the master on this port (ROS_MASTER_URI in their
    environment; roslaunch puts every node in a session of its own, so process groups do not
    find them), optionally only those named comm."""
    uri = re.compile(rb"(?:^|\0)ROS_MASTER_URI=http://[^:/]+:%d/?(?:\0|$)" % port)
    pids = []
    for proc in Path("/proc").glob("[0-9]*"):
        try:
            if int(proc.name) == os.getpid() or (comm and (proc / "comm").read_text().strip() != comm[:15]):
                continue
            if uri.search((proc / "environ").read_bytes()):
                pids.append(int(proc.name))
        except (OSError, ValueError):
            continue
    return pids


def kill_graph_leftovers(port: int) -> None:
    """SIGKILL to every process still talking to the master on this port: the nodes of a roslaunch
    that was itself SIGKILLed (they outlive it, each in its own session)."""
    for pid in graph_processes(port):
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
