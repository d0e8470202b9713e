#!/usr/bin/env python3
"""Parameter sweeps and Monte Carlo flights on Ray:
`rosrun rotors_evaluation sweep.py sweep.yaml [-o DIR] [--workers N] [--address HOST:PORT]`.
Every flight runs isolated (own ROS master, ROS_HOME, logs), in lockstep and as fast as possible;
results go to DIR/results.csv, results.parquet and report.md with plots. Run it again to resume:
finished flights are not flown twice. The sweep file format is in rotors_evaluation/sweep_spec.py
and README ("Batch experiments")."""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation import sweep_spec  # noqa: E402


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sweep_file", type=Path)
    p.add_argument("-o", "--out", type=Path, help="results folder (default: sweep_<name> in the current folder)")
    p.add_argument("--workers", type=int, help="flights at a time (default: the machine's cores, or the cluster's)")
    p.add_argument("--address", help="a running Ray cluster (ray start --head ...), e.g. 10.0.0.5:6379")
    p.add_argument("--dry-run", action="store_true", help="check the file and list the flights, fly nothing")
    a = p.parse_args(argv)
    if a.workers is not None and a.workers < 1:
        print(f"sweep.py: --workers {a.workers}: at least 1", file=sys.stderr)
        return 2
    try:
        spec = sweep_spec.load(a.sweep_file)
    except sweep_spec.SweepError as e:
        print(f"sweep.py: {e}", file=sys.stderr)
        return 2
    out = a.out or Path(f"sweep_{spec.name}")
    if a.dry_run:
        for f in spec.flights:
            print(f"{f.index:4d} {f.id} seed {f.seed} " + " ".join(f"{k}={v}" for k, v in f.params.items()))
        return 0
    from rotors_evaluation.sweep_report import write_report, write_table
    from rotors_evaluation.sweep_run import run_sweep

    t0 = time.monotonic()
    try:
        rows = run_sweep(spec, out, address=a.address, workers=a.workers)
    except KeyboardInterrupt:
        print(f"\nsweep.py: interrupted; finished flights are kept in {out}, run the same command to resume", file=sys.stderr)
        return 130
    wall_s = time.monotonic() - t0
    tables = write_table(spec, rows, out)
    report = write_report(spec, rows, out, wall_s)
    failed = sum(r["status"] == "failed" for r in rows)
    unrepeatable = sum(r["status"] == "not repeatable" for r in rows)
    print(
        f"[sweep] {len(rows)} flights, {failed} failed, {unrepeatable} not repeatable, {wall_s:.1f} s; "
        f"{', '.join(map(str, tables))}, {report}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
