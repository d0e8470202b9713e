"""Runs a sweep's flights on Ray: an embedded local Ray using the machine's cores by default, or a
running Ray cluster (address) whose nodes have the project installed and sourced. Rows stream back
as flights finish and are appended to results.jsonl, so an interrupted sweep resumes without
re-flying what finished. The driver never flies: each flight is a Ray task (one CPU)."""

import json
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from rotors_evaluation.sweep_flight import failed_row, run_flight
from rotors_evaluation.sweep_spec import SweepSpec

RESULTS_LOG = "results.jsonl"


def finished_rows(out_dir: Path) -> dict[str, dict[str, Any]]:
    """The rows of flights that finished in earlier runs of this sweep (ok or failed), by id."""
    rows: dict[str, dict[str, Any]] = {}
    path = out_dir / RESULTS_LOG
    if path.exists():
        for line in path.read_text().splitlines():
            try:
                row = json.loads(line)
            except json.JSONDecodeError:
                continue  # a line cut short by an interruption: that flight runs again
            rows[row["id"]] = row
    return rows


class Progress:
    """done / failed / remaining and the estimated time left, on one line (rewritten on a terminal)."""

    def __init__(self, total: int, already: int, workers: int, stream=sys.stderr):
        self.total, self.done, self.failed, self.workers, self.stream = total, already, 0, max(workers, 1), stream
        self.t0, self.finished_here = time.monotonic(), 0
        self.tty = hasattr(stream, "isatty") and stream.isatty()

    def update(self, row: dict[str, Any] | None) -> None:
        if row is not None:
            self.done += 1
            self.finished_here += 1
            self.failed += row["status"] != "ok"  # failed or not repeatable
        left = self.total - self.done
        if self.finished_here:
            per_flight = (time.monotonic() - self.t0) / self.finished_here
            eta = f"{int(per_flight * left // 60)}:{int(per_flight * left % 60):02d}"
        else:
            eta = "?"
        width = 24
        bar = "#" * (width * self.done // max(self.total, 1))
        text = f"[sweep] [{bar:<{width}}] {self.done}/{self.total} done, {self.failed} not ok, {left} remaining, " f"about {eta} left"
        if row is not None and row["status"] != "ok":
            text += f"  (flight {row['index']} {row['status']}: {row['reason']})"
        print(("\r" + text) if self.tty else text, end="" if self.tty else "\n", file=self.stream, flush=True)

    def close(self) -> None:
        if self.tty:
            print(file=self.stream)


def run_sweep(
    spec: SweepSpec,
    out_dir: Path,
    address: str | None = None,
    workers: int | None = None,
    on_row: Callable[[dict[str, Any]], None] | None = None,
    stream=sys.stderr,
) -> list[dict[str, Any]]:
    """Flies every flight of the sweep that has no row yet; returns the rows of all its flights."""
    import ray

    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "sweep.json").write_text(json.dumps(spec.to_json(), indent=1, default=str) + "\n")
    done = finished_rows(out_dir)
    todo = [f for f in spec.flights if f.id not in done]
    print(
        f"[sweep] {spec.name}: {len(spec.flights)} flights, {len(spec.flights) - len(todo)} finished before, "
        f"{len(todo)} to fly; results in {out_dir}",
        file=stream,
        flush=True,
    )
    rows = {f.id: done[f.id] for f in spec.flights if f.id in done}
    if todo:
        if address:
            ray.init(address=address, log_to_driver=False, configure_logging=False)
        else:
            ray.init(
                num_cpus=workers or os.cpu_count(), include_dashboard=False, log_to_driver=False, configure_logging=False
            )  # workers inherit this environment (ROS, PYTHONPATH)
        try:
            parallel = int(ray.cluster_resources().get("CPU", 1))
            if address and workers:
                parallel = min(parallel, workers)
            progress = Progress(len(spec.flights), len(spec.flights) - len(todo), parallel, stream)
            sweep_json = spec.to_json()
            if spec.engine == "batch":  # one task per vehicle: its flights in one FlightBatch
                from rotors_evaluation.sweep_batch import fly_group, groups

                remote = ray.remote(num_cpus=1, max_retries=0)(fly_group)
                waiting = groups(sweep_json, [f.__dict__ for f in todo])
            else:  # one task per flight
                remote = ray.remote(num_cpus=1, max_retries=0)(run_flight)
                waiting = [f.__dict__ for f in todo]
            pending: dict[Any, Any] = {}
            log = open(out_dir / RESULTS_LOG, "a")
            while waiting or pending:
                while waiting and len(pending) < parallel:  # at most `parallel` in flight: limits with --workers
                    task = waiting.pop(0)
                    ref = (
                        remote.remote(sweep_json, task)
                        if spec.engine == "batch"
                        else remote.remote(sweep_json, task, str(out_dir.resolve()))
                    )
                    pending[ref] = task
                ready, _ = ray.wait(list(pending), num_returns=1)
                for ref in ready:
                    task = pending.pop(ref)
                    flights = task if spec.engine == "batch" else [task]
                    try:
                        result = ray.get(ref)
                        got = result if spec.engine == "batch" else [result]
                    except Exception as e:  # the worker itself died: recorded like any failed flight
                        got = [failed_row(f, f"Ray task failed: {str(e).splitlines()[0]}") for f in flights]
                    for row in got:
                        log.write(json.dumps(row, default=str) + "\n")
                        log.flush()
                        rows[row["id"]] = row
                        progress.update(row)
                        if on_row:
                            on_row(row)
            progress.close()
            log.close()
        finally:
            ray.shutdown()
    return [rows[f.id] for f in spec.flights]
