"""A ROS master of one's own, on a port taken without a race.

Choosing a free port and starting a master on it are two steps: a second run in between can take
the port, and both runs would then share one master (and each other's topics). start_own_master
closes the gap by checking, after start-up, that the master answering on the port is the process
it started (the master's getPid is its child's pid); otherwise it stops that child and tries another
port.

As a command (for shell scripts): `python3 -m rotors_evaluation.ros_master LOG_FILE` starts a
detached master and prints "PORT PID"; stop it with `kill -INT PID`.
"""

import os
import socket
import subprocess
import sys
import time
import xmlrpc.client
from collections.abc import Callable
from pathlib import Path

from rotors_evaluation.processes import stop_process_group

START_TIMEOUT_S = 20.0
TRIES = 8


class MasterStartError(RuntimeError):
    pass


def unused_port() -> int:
    """A port unused at this instant: only for servers that fail loudly when it is taken meanwhile."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _answers_as(port: int, proc: subprocess.Popen) -> bool:
    """Waits until a master answers on `port`; True when it is `proc`."""
    master = xmlrpc.client.ServerProxy(f"http://127.0.0.1:{port}")
    deadline = time.monotonic() + START_TIMEOUT_S
    while time.monotonic() < deadline and proc.poll() is None:
        try:
            code, _, pid = master.getPid("/ros_master_check")
            return code == 1 and pid == proc.pid
        except (OSError, xmlrpc.client.Error):
            time.sleep(0.1)
    return False


def start_own_master(env: dict[str, str], log_path: Path, preexec_fn: Callable[[], None] | None = None) -> tuple[subprocess.Popen, int]:
    """Starts `rosmaster --core` in its own session on a port nobody else holds; returns (process, port).
    `preexec_fn`, when given, must itself call os.setsid()."""
    for _ in range(TRIES):
        port = unused_port()
        with open(log_path, "a") as log:
            proc = subprocess.Popen(
                ["rosmaster", "--core", "-p", str(port)],
                env=env,
                stdout=log,
                stderr=subprocess.STDOUT,
                preexec_fn=preexec_fn,
                start_new_session=preexec_fn is None,
            )
        if _answers_as(port, proc):
            return proc, port
        stop_process_group(proc, 10)
    raise MasterStartError(f"could not start a ROS master of its own ({TRIES} ports tried); see {log_path}")


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: python3 -m rotors_evaluation.ros_master LOG_FILE  (prints 'PORT PID')", file=sys.stderr)
        return 2
    try:
        proc, port = start_own_master(dict(os.environ), Path(sys.argv[1]))
    except MasterStartError as e:
        print(e, file=sys.stderr)
        return 1
    print(port, proc.pid, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
