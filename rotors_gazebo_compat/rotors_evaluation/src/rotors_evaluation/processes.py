"""Stopping a process and its process group as Ctrl-C does: SIGINT (roslaunch then stops its nodes
and the bag plugin closes its bag), then SIGKILL after a grace time."""
import os
import signal
import subprocess
from typing import Optional


def restore_sigint() -> None:
    """Makes SIGINT interrupt again in this process and in the processes it starts. A shell starts
    a background job (`cmd &`, nohup) with SIGINT ignored, and an ignored signal stays ignored
    across exec: every ROS process started from there would ignore the Ctrl-C that stops it
    cleanly (roslaunch closing its bags), and each stop would wait out its grace time and SIGKILL."""
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def stop_process_group(proc: Optional[subprocess.Popen], grace_s: float, first_signal: int = signal.SIGINT) -> bool:
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
