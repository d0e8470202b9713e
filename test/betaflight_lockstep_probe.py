#!/usr/bin/env python3
"""Scratch tool (not a test): drives a Betaflight SITL binary with state packets at fixed sim
timestamps and checks the answers, to compare the lockstep build (SIMULATOR_LOCKSTEP, see
rotors_gazebo/resource/betaflight_lockstep.patch) with the stock clock-scaled one.

  betaflight_lockstep_probe.py BINARY answers       one answer per state, disarmed then armed
  betaflight_lockstep_probe.py BINARY repeat        two runs, same inputs: identical outputs?
  betaflight_lockstep_probe.py BINARY speed         states per wall second, answer awaited
  betaflight_lockstep_probe.py BINARY starts [N]    N launches in a row, each must answer
  betaflight_lockstep_probe.py BINARY plugin [N]    N launches answered the way the plugin sends (stock)

Packets as rotors_plugins' betaflight_packets.h: state (144 bytes) to UDP 9003, RC (40 bytes) to
9004, motors (4 floats) back on 9002; the CLI on TCP 5761. Each launch gets a fresh working
directory (eeprom.bin), the CLI file applied and `save` (which restarts the firmware).
"""

from __future__ import annotations

import hashlib
import math
import os
import select
import socket
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLI_FILE = ROOT / "rotors_gazebo_compat/rotors_gazebo/resource/betaflight_iris.cli"
STATE_PORT, RC_PORT, MOTOR_PORT, CLI_PORT = 9003, 9004, 9002, 5761
DT = 0.002  # [s] sim time between states


def cli_lines() -> list[str]:
    lines = []
    for raw in CLI_FILE.read_text().splitlines():
        line = raw.split("#", 1)[0].strip()
        if line:
            lines.append(line)
    return lines + ["save"]


def port_open(port: int) -> bool:
    try:
        socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
        return True
    except OSError:
        return False


def state_packet(t: float, wobble: bool = False) -> bytes:
    """The vehicle level at rest: no rotation, minus the specific force (body FLU) = (0, 0, -g).
    wobble: plus rates of a few deg/s that vary (the same for the same t), so that the PID's state,
    and so the outputs, change from state to state."""
    p, q, r = 0.0, 0.0, 0.0
    if wobble:
        p, q, r = 0.05 * math.sin(7 * t), 0.04 * math.cos(5 * t), 0.03 * math.sin(3 * t + 1)
    return struct.pack("<18d", t, p, q, r, 0, 0, -9.80665, 1, 0, 0, 0, 0, 0, 0, 8.55, 47.37, 400.0, 101325.0)


def rc_packet(t: float, throttle: int, arm: bool) -> bytes:
    channels = [1500, 1500, throttle, 1500, 2000 if arm else 1000, 1000] + [1000] * 10
    return struct.pack("<d16H", t, *channels)


class Firmware:
    def __init__(self, binary: str, workdir: str):
        self.binary, self.workdir = binary, workdir
        self.log = open(os.path.join(workdir, "betaflight.log"), "ab")
        self.process = None

    def launch(self, timeout_s: float = 20.0) -> float:
        """Starts it and waits for its CLI port: the wall time that took."""
        start = time.monotonic()
        self.process = subprocess.Popen([self.binary], cwd=self.workdir, stdout=self.log, stderr=subprocess.STDOUT)
        while not port_open(CLI_PORT):
            if self.process.poll() is not None:
                raise RuntimeError(f"exited with {self.process.returncode} at start")
            if time.monotonic() - start > timeout_s:
                raise RuntimeError("CLI port did not open")
            time.sleep(0.02)
        return time.monotonic() - start

    def cli(self, lines: list[str], timeout_s: float = 5.0) -> str:
        for attempt in range(5):
            try:
                return self._cli(lines, timeout_s)
            except (ConnectionResetError, BrokenPipeError):
                time.sleep(0.3 * (attempt + 1))
        return self._cli(lines, timeout_s)

    @staticmethod
    def _cli(lines: list[str], timeout_s: float) -> str:
        out = ""
        with socket.create_connection(("127.0.0.1", CLI_PORT), timeout=timeout_s) as s:
            for line in ["#"] + lines:
                s.sendall(line.encode() + (b"" if line == "#" else b"\r\n"))
                answer, deadline = b"", time.monotonic() + timeout_s
                while time.monotonic() < deadline:
                    s.settimeout(max(0.05, deadline - time.monotonic()))
                    try:
                        chunk = s.recv(65536)
                    except socket.timeout:
                        break
                    if not chunk:
                        break
                    answer += chunk
                    if line != "save" and answer.rstrip().endswith(b"#"):
                        break
                out += answer.decode(errors="replace")
                if "ERROR" in out:
                    raise RuntimeError(f"CLI refused {line}: {out[-200:]}")
        return out

    def start_configured(self) -> float:
        """Fresh start, CLI file, `save` (it exits), started again: the wall time of the last start."""
        self.launch()
        self.cli(cli_lines())
        self.process.wait(timeout=10)
        return self.launch()

    def stop(self) -> None:
        if self.process and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.log.close()


class Link:
    def __init__(self):
        self.motors = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.motors.bind(("127.0.0.1", MOTOR_PORT))
        self.out = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)

    def drain(self) -> int:
        n = 0
        while select.select([self.motors], [], [], 0)[0]:
            self.motors.recv(256)
            n += 1
        return n

    def send_state(self, t: float, wobble: bool = False) -> None:
        self.out.sendto(state_packet(t, wobble), ("127.0.0.1", STATE_PORT))

    def send_rc(self, t: float, throttle: int, arm: bool) -> None:
        self.out.sendto(rc_packet(t, throttle, arm), ("127.0.0.1", RC_PORT))

    def answer(self, timeout_s: float) -> bytes | None:
        if select.select([self.motors], [], [], timeout_s)[0]:
            return self.motors.recv(256)
        return None

    def close(self) -> None:
        self.motors.close()
        self.out.close()


def rc_schedule(k: int) -> tuple[int, bool] | None:
    """RC of step k: none for the first 0.5 s, then throttle low and disarmed, arm at 6 s (after the
    firmware's 5 s power-on arming grace, on its clock), throttle 1500 us from 7 s (AUX2 low: no
    angle mode)."""
    t = k * DT
    if t < 0.5:
        return None
    return (1500 if t >= 7.0 else 1000), t >= 6.0


def lockstep_run(binary: str, steps: int, timeout_s: float = float(os.environ.get("ANSWER_TIMEOUT", "2")),
                 rc: bool = True, wobble: bool = True) -> dict:
    """One launch: `steps` states, each answered before the next goes out (RC before its state, as
    the lockstep firmware wants it). Returns the answers, extra answers and the wall time of the exchange."""
    with tempfile.TemporaryDirectory(prefix="bf_probe_") as workdir:
        fc, link = Firmware(binary, workdir), Link()
        try:
            fc.start_configured()
            link.drain()
            answers, missing, extra = [], 0, 0
            cpu0 = cpu_s(fc.process.pid)
            start = time.monotonic()
            for k in range(1, steps + 1):
                t = k * DT
                # RC first: the lockstep firmware reads the RC that came before each state with it
                if rc and (cmd := rc_schedule(k)) is not None:
                    link.send_rc(t, *cmd)
                link.send_state(t, wobble)
                a = link.answer(timeout_s)
                if a is None:
                    missing += 1
                    answers.append(b"")
                    continue
                answers.append(a)
                extra += link.drain()
            wall = time.monotonic() - start
            cpu = cpu_s(fc.process.pid) - cpu0
            time.sleep(0.05)
            extra += link.drain()
            return {"answers": answers, "missing": missing, "extra": extra, "wall": wall, "cpu": cpu,
                    "log": Path(workdir, "betaflight.log").read_text(errors="replace")}
        finally:
            fc.stop()
            link.close()


def cpu_s(pid: int) -> float:
    """User + system CPU time of a process [s]."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def motors(a: bytes) -> tuple[float, ...]:
    return struct.unpack("<4f", a) if len(a) == 16 else ()


def cmd_answers(binary: str) -> None:
    steps = 4500  # 9 s of sim time
    r = lockstep_run(binary, steps)
    print(f"states {steps}, answered {steps - r['missing']}, missing {r['missing']}, extra answers {r['extra']}")
    for t in (1.0, 5.99, 6.5, 6.99, 7.002, 7.1, 8.0, 9.0):
        k = int(round(t / DT))
        print(f"  t = {t:4.2f} s: motors {[round(m, 4) for m in motors(r['answers'][k - 1])]}")


def cmd_repeat(binary: str) -> None:
    steps = 4500
    runs = [lockstep_run(binary, steps) for _ in range(2)]
    for i, r in enumerate(runs):
        digest = hashlib.sha256(b"".join(r["answers"])).hexdigest()[:16]
        armed = sum(1 for a in r["answers"] if any(m > 0 for m in motors(a)))
        print(f"run {i + 1}: missing {r['missing']}, extra {r['extra']}, states with motors > 0: {armed}, "
              f"distinct outputs {len(set(r['answers']))}, "
              f"sha256 of all answers {digest}")
    a, b = runs[0]["answers"], runs[1]["answers"]
    diff = [k for k in range(steps) if a[k] != b[k]]
    print("identical bit for bit" if not diff else
          f"differ at {len(diff)} states, first at t = {(diff[0] + 1) * DT:.3f} s: {motors(a[diff[0]])} vs {motors(b[diff[0]])}")


def cmd_speed(binary: str) -> None:
    steps = 20000
    r = lockstep_run(binary, steps, rc=True)
    rate = steps / r["wall"]
    print(f"{steps} states in {r['wall']:.2f} s wall: {rate:.0f} states/s = {rate * DT:.1f} x real time "
          f"at {DT * 1e3:.0f} ms steps (missing {r['missing']}, extra {r['extra']}); the firmware's CPU time "
          f"{r['cpu'] / steps * 1e6:.1f} us per state")


def cmd_starts(binary: str, n: int) -> None:
    """Each launch: started, configured (CLI, save: it exits), started again, and the first state
    sent right after the exec, while it initialises (again every 50 ms until answered: copies sent
    before its socket is bound are dropped by the kernel), then 500 states in lockstep, each of
    which must be answered once."""
    ok = 0
    for i in range(n):
        with tempfile.TemporaryDirectory(prefix="bf_probe_") as workdir:
            fc, link = Firmware(binary, workdir), Link()
            try:
                fc.launch()
                transcript = fc.cli(cli_lines())
                try:
                    fc.process.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    fc.log.flush()
                    log = Path(workdir, "betaflight.log").read_text(errors="replace")
                    log = "\n".join(l for l in log.splitlines() if "FLASH_ProgramWord" not in l)
                    print(f"launch {i + 1:2d}: CONFIGURATION FAILED, the CLI answered {transcript[:80]!r}; "
                          f"its log:\n{log}", flush=True)
                    continue
                fc.process = subprocess.Popen([fc.binary], cwd=workdir, stdout=fc.log, stderr=subprocess.STDOUT)
                t0 = time.monotonic()
                first = None
                while first is None and time.monotonic() - t0 < 30:
                    link.send_state(DT)
                    if link.answer(0.05) is not None:
                        first = time.monotonic() - t0
                time.sleep(0.1)
                copies = link.drain()
                answered, extra = 0, 0
                for k in range(2, 502):
                    link.send_state(k * DT)
                    if link.answer(2.0) is None:
                        break
                    answered += 1
                    extra += link.drain()
                good = first is not None and answered == 500 and extra == 0
                ok += good
                print(f"launch {i + 1:2d}: first state answered {first or float('nan'):.2f} s after exec "
                      f"({copies} more copies answered), then {answered}/500 answered, {extra} extra: "
                      f"{'ok' if good else 'FAILED'}", flush=True)
            finally:
                fc.stop()
                link.close()
    print(f"{ok}/{n} launches answered every state")


def cmd_plugin(binary: str, n: int) -> None:
    """Stock build, sent the way the plugin sends: CLI port open, 3 s settle, paced 2 ms until 100
    answers, then each state waits up to 20 ms for its answer. Silent: < 100 answers in 10 s."""
    ok = 0
    for i in range(n):
        with tempfile.TemporaryDirectory(prefix="bf_probe_") as workdir:
            fc, link = Firmware(binary, workdir), Link()
            try:
                fc.start_configured()
                time.sleep(float(os.environ.get("SETTLE", "3")))
                link.drain()
                answers, k, t0 = 0, 0, time.monotonic()
                while answers < 100 and time.monotonic() - t0 < 10:
                    k += 1
                    link.send_state(k * DT)
                    time.sleep(DT)
                    answers += link.drain()
                lock_answers = 0
                if answers >= 100:
                    for _ in range(500):
                        k += 1
                        link.send_state(k * DT)
                        if link.answer(0.02) is not None:
                            lock_answers += 1
                            link.drain()
                ok += answers >= 100
                print(f"launch {i + 1:2d}: {answers} answers to the first {k} states paced, "
                      f"then {lock_answers}/500 answered within 20 ms", flush=True)
            finally:
                fc.stop()
                link.close()
    print(f"{ok}/{n} launches answered")


def main() -> None:
    binary, what = sys.argv[1], sys.argv[2]
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 30
    {"answers": lambda: cmd_answers(binary), "repeat": lambda: cmd_repeat(binary),
     "speed": lambda: cmd_speed(binary), "starts": lambda: cmd_starts(binary, n),
     "plugin": lambda: cmd_plugin(binary, n)}[what]()


if __name__ == "__main__":
    main()
