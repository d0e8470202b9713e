"""A sweep's results: one table (CSV and Parquet, one row per flight) and a report (markdown and PNG
plots: the first metric against each varied parameter, box plots over seeds, the failure list)."""

import csv
import math
from collections import OrderedDict
from pathlib import Path
from typing import Any

import numpy as np

from rotors_evaluation.sweep_spec import SweepSpec

FIRST = ["id", "index", "repetition", "seed"]
LAST = ["status", "reason", "sim_s", "wall_s", "unwaited_steps", "host", "node", "bag", "log_tail"]


def columns(spec: SweepSpec, rows: list[dict[str, Any]]) -> list[str]:
    metrics = OrderedDict()
    for r in rows:
        for k in r:
            if k not in FIRST and k not in LAST and k not in spec.vary:
                metrics[k] = None
    return FIRST + list(spec.vary) + list(metrics) + LAST


def write_table(spec: SweepSpec, rows: list[dict[str, Any]], out_dir: Path) -> list[Path]:
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols = columns(spec, rows)
    csv_path, parquet_path = out_dir / "results.csv", out_dir / "results.parquet"
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({c: r.get(c, "") for c in cols})
    # one type per column: numbers as float64, anything else (or mixed) as text
    table = {}
    for c in cols:
        values = [r.get(c) for r in rows]
        if all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in values):
            table[c] = pa.array([None if v is None else float(v) for v in values], pa.float64())
        else:
            table[c] = pa.array([None if v is None else str(v) for v in values], pa.string())
    pq.write_table(pa.table(table), parquet_path)
    return [csv_path, parquet_path]


def _metric(spec: SweepSpec, rows: list[dict[str, Any]]) -> str:
    """The metric the plots show: the first evaluation's position RMS."""
    kind = spec.evaluations[0]
    return "estimator_position_rms_m" if kind == "estimator" else f"{kind}_position_rms_m"


def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _by_combination(spec: SweepSpec, rows: list[dict[str, Any]], metric: str) -> "OrderedDict[tuple, list[float]]":
    """The metric of the ok flights of each combination of varied values (every combination that
    has a flight appears, possibly with no values)."""
    groups: OrderedDict[tuple, list[float]] = OrderedDict()
    for r in rows:
        values = groups.setdefault(tuple(r.get(n) for n in spec.vary), [])
        if r["status"] == "ok" and _number(r.get(metric)):
            values.append(r[metric])
    return groups


def _text(v: Any) -> str:
    return f"{v:.4g}" if _number(v) else str(v)


def _save(fig, ax, title: str, ylabel: str, path: Path) -> Path:
    """Labels, grid and layout shared by the sweep's figures; writes and closes the figure."""
    import matplotlib.pyplot as plt

    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot(spec: SweepSpec, rows: list[dict[str, Any]], out_dir: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    metric = _metric(spec, rows)
    ok = [r for r in rows if r["status"] == "ok" and _number(r.get(metric))]
    saved = []
    for name in spec.vary:
        fig, ax = plt.subplots(figsize=(6, 4))
        values = list(OrderedDict.fromkeys(spec.vary[name]))
        numeric = all(_number(v) for v in values)
        xs = [r[name] if numeric else values.index(r[name]) for r in ok]
        ax.scatter(xs, [r[metric] for r in ok], s=18, alpha=0.6, label="flights")
        means = [
            (v if numeric else i, np.mean([r[metric] for r in ok if r[name] == v]))
            for i, v in enumerate(values)
            if any(r[name] == v for r in ok)
        ]
        if means:
            ax.plot(*zip(*means), "o-", color="C3", label="mean")
        if not numeric:
            ax.set_xticks(range(len(values)), [str(v) for v in values])
        ax.set_xlabel(name)
        ax.legend(fontsize=8)
        saved.append(_save(fig, ax, f"{spec.name}: {metric} against {name}", metric, out_dir / f"{metric}_vs_{name.replace('/', '_')}.png"))
    # one box per parameter combination, over its repetitions (seeds)
    groups = {
        ", ".join(f"{n.split('.')[-1]}={_text(v)}" for n, v in zip(spec.vary, key)) or "all": values
        for key, values in _by_combination(spec, rows, metric).items()
        if values
    }
    if groups:
        fig, ax = plt.subplots(figsize=(max(6, 0.6 * len(groups) + 2), 4.5))
        ax.boxplot(list(groups.values()))
        ax.set_xticks(range(1, len(groups) + 1), list(groups), rotation=60, ha="right", fontsize=7)
        saved.append(
            _save(
                fig,
                ax,
                f"{spec.name}: {metric} over {spec.repetitions} seed(s) per combination",
                metric,
                out_dir / f"{metric}_boxplot_over_seeds.png",
            )
        )
    return saved


def write_report(spec: SweepSpec, rows: list[dict[str, Any]], out_dir: Path, wall_s: float) -> Path:
    metric = _metric(spec, rows)
    plots = plot(spec, rows, out_dir)
    ok = [r for r in rows if r["status"] == "ok"]
    failed = [r for r in rows if r["status"] != "ok"]  # failed, or not repeatable (lockstep did not wait)
    lines = [
        f"# Sweep {spec.name}",
        "",
        f"- sweep file: `{spec.source}`; launch `{spec.launch_file.name}`; {spec.sim_time_s:g} s of sim time per "
        f"flight, lockstep, " + (f"paced at {spec.real_time_factor:g}x real time" if spec.real_time_factor > 0 else "as fast as possible"),
        f"- {len(rows)} flights: {len(ok)} ok, {sum(r['status'] == 'not repeatable' for r in rows)} not repeatable, "
        f"{sum(r['status'] == 'failed' for r in rows)} failed; wall time of this run {wall_s:.1f} s",
        f"- fixed: {', '.join(f'{k}={v}' for k, v in spec.fixed.items()) or 'nothing'}",
        f"- varied: {', '.join(f'{k} ({len(v)} values)' for k, v in spec.vary.items()) or 'nothing'}; "
        f"{spec.repetitions} repetition(s) from seed {spec.seed}",
        f"- evaluation: {', '.join(spec.evaluations)}",
        "",
        f"## {metric} per combination (mean, std and count over the repetitions)",
        "",
    ]
    names = list(spec.vary)
    header = names + ["mean", "std", "n"]
    lines += ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for key, values in _by_combination(spec, rows, metric).items():
        stats = [f"{np.mean(values):.4f}", f"{np.std(values):.4f}", str(len(values))] if values else ["-", "-", "0"]
        lines.append("| " + " | ".join([*map(_text, key), *stats]) + " |")
    lines += ["", "## Plots", ""] + [f"![{p.stem}]({p.name})" for p in plots]
    lines += ["", "## Failures (and flights that are not repeatable)", ""]
    if not failed:
        lines.append("none")
    for r in failed:
        params = ", ".join(f"{n}={r.get(n)}" for n in names)
        lines += [
            f"- flight {r['index']} (`{r['id']}`, seed {r['seed']}{', ' + params if params else ''}): " f"{r['status']}: {r['reason']}",
            "",
            "  ```",
            *("  " + line for line in (r.get("log_tail") or "").splitlines()[-8:]),
            "  ```",
        ]
    path = out_dir / "report.md"
    path.write_text("\n".join(lines) + "\n")
    return path
