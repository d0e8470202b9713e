"""A sweep file: which launch file to fly, what to hold fixed, what to vary (grids, lists, seeded
random draws), how often to repeat each combination and which evaluation to run on each bag.
Everything is checked before any flight starts; a bad entry is one SweepError line naming it.

    name: lee_gains_x_wind
    launch: rotors_gazebo/mav_hovering_example.launch   # <package>/<file> or a path
    sim_time_s: 20          # each flight flies this long in sim time (lockstep, as fast as possible)
    wall_limit_s: 180       # a flight still running after this is stopped and recorded as failed
    real_time_factor: 0     # 0: as fast as possible; e.g. 10 keeps non-lockstep nodes (set point
                            # publishers) in step on a loaded machine
    repetitions: 2          # per combination; repetition r uses seed + r (launch arg random_seed)
    seed: 1
    evaluation: hovering    # or a list of: hovering, waypoints, disturbance, estimator
    eval_options: {delay_first_evaluation: 5, rms_calc_time: 10}
    keep_bags: false
    fixed:  {launch.mav_name: firefly, model.enable_wind: true}
    vary:
      controller.position_gain.x: [2, 4, 6]              # a list
      model.wind_force_mean: {linspace: [0, 3, 4]}        # start, stop, count
      controller.mass: {uniform: [1.4, 1.7], draws: 3}    # seeded draws (also normal: [mean, std])

Parameter names: launch.<launch argument>, model.<xacro argument of the vehicle model: wind,
sensor noise, ...>, controller.<key of the controller's gains or vehicle yaml, dots between
levels>, estimator.<key of msf_simulator.yaml>.
"""

import hashlib
import itertools
import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from rotors_evaluation.options import TUNABLE

EVALUATIONS = ("hovering", "waypoints", "disturbance", "estimator")
EVAL_OPTIONS = TUNABLE  # the evaluation scripts' numeric options (options.EvalOptions)
KINDS = ("launch", "model", "controller", "estimator")
TOP_LEVEL = (
    "name",
    "launch",
    "sim_time_s",
    "wall_limit_s",
    "real_time_factor",
    "repetitions",
    "seed",
    "evaluation",
    "eval_options",
    "keep_bags",
    "fixed",
    "vary",
    "inject_failure",
    "engine",
)
# world: each flight a roslaunch in the full world (bag, evaluation); batch: the flights that share a
# vehicle in one rotors_sim.FlightBatch (no ROS, no rendering; see sweep_batch.py for what it flies)
ENGINES = ("world", "batch")
# what every flight of a sweep sets (when the launch file declares it)
FORCED_ARGS = {"lockstep": "true", "real_time_factor": "0", "gui": "false", "enable_logging": "true"}
# the launch argument each parameter kind travels through
CARRIER = {"model": "xacro_args", "controller": "extra_controller_params", "estimator": "extra_msf_params"}
RANGE_HELP = "use a list, {linspace: [start, stop, count]}, {uniform: [low, high], draws: n} or " "{normal: [mean, std], draws: n}"


class SweepError(Exception):
    """A sweep file that cannot run; the message is one line naming the entry."""


@dataclass
class Flight:
    """One flight of a sweep: a value for every varied parameter, and a repetition with its seed."""

    index: int
    params: dict[str, Any]
    repetition: int
    seed: int
    id: str = ""


@dataclass
class SweepSpec:
    name: str
    source: Path
    launch_package: str
    launch_file: Path
    launch_args: dict[str, str]  # declared arguments and their defaults (None: no default)
    sim_time_s: float
    wall_limit_s: float
    repetitions: int
    seed: int
    evaluations: list[str]
    eval_options: dict[str, float]
    keep_bags: bool
    fixed: dict[str, Any]
    vary: dict[str, list[Any]]  # expanded values, in the file's order
    inject_failure: dict[str, float] | None = None
    real_time_factor: float = 0.0
    flights: list[Flight] = field(default_factory=list)
    engine: str = "world"

    @property
    def mav_name(self) -> str:
        return str(self.fixed.get("launch.mav_name", self.launch_args.get("mav_name") or "firefly"))

    def to_json(self) -> dict[str, Any]:
        """What a flight needs of the sweep (sent to Ray workers; plain types only)."""
        return {
            "name": self.name,
            "launch_package": self.launch_package,
            "launch_file": str(self.launch_file),
            "launch_args": self.launch_args,
            "sim_time_s": self.sim_time_s,
            "wall_limit_s": self.wall_limit_s,
            "evaluations": self.evaluations,
            "eval_options": self.eval_options,
            "keep_bags": self.keep_bags,
            "fixed": self.fixed,
            "mav_name": self.mav_name,
            "inject_failure": self.inject_failure,
            "real_time_factor": self.real_time_factor,
            "engine": self.engine,
        }


def _fail(source: Path, message: str) -> SweepError:
    return SweepError(f"{source.name}: {message}")


def declared_launch_args(path: Path) -> dict[str, str | None]:
    """The <arg> elements a launch file declares (name -> default; None when it has none)."""
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    return {a.get("name"): a.get("default", a.get("value")) for a in root.findall("arg")}


def declared_xacro_args(description_dir: Path) -> list[str]:
    """Every <xacro:arg name="..."> of the shipped vehicle descriptions."""
    names = set()
    for f in list(description_dir.glob("urdf/*.xacro")) + list(description_dir.glob("urdf/*.gazebo")):
        names.update(re.findall(r'<xacro:arg\s+name="([^"]+)"', f.read_text()))
    return sorted(names)


def _package_path(package: str) -> Path:
    import rospkg

    try:
        return Path(rospkg.RosPack().get_path(package))
    except rospkg.ResourceNotFound:
        raise SweepError(f"package '{package}' is not found (source scripts/env.bash first)") from None


def _key_exists(tree: Any, path: list[str]) -> bool:
    for key in path:
        if not isinstance(tree, dict):
            return False
        match = [k for k in tree if str(k) == key]
        if not match:
            return False
        tree = tree[match[0]]
    return True


def _yaml(path: Path) -> dict:
    return yaml.safe_load(path.read_text()) or {}


def _expand_range(source: Path, name: str, spec: Any, rng_seed: int) -> list[Any]:
    bad = _fail(source, f"vary entry '{name}': malformed range {spec!r}; {RANGE_HELP}")
    if isinstance(spec, list):
        if not spec:
            raise _fail(source, f"vary entry '{name}': the list is empty")
        return list(spec)
    if not isinstance(spec, dict) or len(spec) not in (1, 2):
        raise bad
    numbers = lambda xs: isinstance(xs, list) and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in xs)
    if "linspace" in spec and len(spec) == 1:
        v = spec["linspace"]
        if not (numbers(v) and len(v) == 3 and float(v[2]).is_integer() and v[2] >= 1):
            raise bad
        return [float(x) for x in np.linspace(v[0], v[1], int(v[2]))]
    for law in ("uniform", "normal"):
        if law in spec:
            v, n = spec[law], spec.get("draws")
            if set(spec) != {law, "draws"} or not numbers(v) or len(v) != 2 or not isinstance(n, int) or n < 1:
                raise bad
            if law == "uniform" and not v[0] <= v[1]:
                raise _fail(source, f"vary entry '{name}': uniform low {v[0]} is above high {v[1]}")
            if law == "normal" and v[1] < 0:
                raise _fail(source, f"vary entry '{name}': normal std {v[1]} is negative")
            # the draws depend on the sweep's seed and the entry's name only
            entry_seed = int(hashlib.sha256(f"{rng_seed}:{name}".encode()).hexdigest()[:8], 16)
            rng = np.random.default_rng(entry_seed)
            draws = rng.uniform(v[0], v[1], n) if law == "uniform" else rng.normal(v[0], v[1], n)
            return [float(f"{x:.6g}") for x in draws]
    raise bad


class _Checker:
    """Checks parameter names against what the launch file, the descriptions and the yaml files
    declare."""

    def __init__(self, source: Path, launch_file: Path, launch_args: dict[str, str | None]):
        self.source, self.launch_file, self.launch_args = source, launch_file, launch_args
        self._xacro: list[str] | None = None
        self._gazebo = _package_path("rotors_gazebo")

    def check(self, entry: str, name: str, mav_name: str) -> None:
        kind, _, key = name.partition(".")
        if kind not in KINDS or not key:
            raise _fail(self.source, f"{entry} '{name}': a parameter is one of {', '.join(k + '.<name>' for k in KINDS)}")
        if kind == "launch":
            if key not in self.launch_args:
                raise _fail(
                    self.source,
                    f"{entry} '{name}': {self.launch_file.name} has no argument '{key}' (it has: "
                    f"{', '.join(sorted(self.launch_args))})",
                )
            if key in FORCED_ARGS or key in CARRIER.values() or key == "random_seed":
                raise _fail(
                    self.source,
                    f"{entry} '{name}': the sweep sets '{key}' itself " f"(lockstep, as fast as possible, logging, seeds, parameter files)",
                )
            return
        carrier = CARRIER[kind]
        if carrier not in self.launch_args:
            raise _fail(
                self.source,
                f"{entry} '{name}': {self.launch_file.name} has no '{carrier}' argument, so " f"{kind} parameters cannot reach the flight",
            )
        if kind == "model":
            if self._xacro is None:
                self._xacro = declared_xacro_args(_package_path("rotors_description"))
            if key not in self._xacro:
                raise _fail(self.source, f"{entry} '{name}': no vehicle description declares the xacro argument " f"'{key}'")
        elif kind == "controller":
            files = [self._gazebo / "resource" / f"lee_controller_{mav_name}.yaml", self._gazebo / "resource" / f"{mav_name}.yaml"]
            if not all(f.exists() for f in files):
                raise _fail(self.source, f"{entry} '{name}': no controller parameters for the vehicle '{mav_name}'")
            if not any(_key_exists(_yaml(f), key.split(".")) for f in files):
                raise _fail(self.source, f"{entry} '{name}': '{key}' is no key of {files[0].name} or {files[1].name}")
        elif kind == "estimator":
            f = self._gazebo / "resource" / "msf_simulator.yaml"
            if not _key_exists(_yaml(f), key.split(".")):
                raise _fail(self.source, f"{entry} '{name}': '{key}' is no key of {f.name}")


def _recorded_topics(spec_fixed: dict[str, Any], launch_args: dict[str, str | None]) -> str:
    return str(spec_fixed.get("launch.log_extra_topics", launch_args.get("log_extra_topics") or ""))


def load(path: Path) -> SweepSpec:
    """Reads and checks a sweep file and lists its flights; raises SweepError (one line)."""
    path = Path(path)
    try:
        raw = yaml.safe_load(path.read_text())
    except FileNotFoundError:
        raise SweepError(f"sweep file '{path}' does not exist") from None
    except yaml.YAMLError as e:
        raise _fail(path, f"is not valid YAML ({str(e).splitlines()[0]})") from None
    if not isinstance(raw, dict):
        raise _fail(path, "is not a mapping of sweep entries")
    unknown = sorted(set(raw) - set(TOP_LEVEL))
    if unknown:
        raise _fail(path, f"unknown entry '{unknown[0]}' (known: {', '.join(TOP_LEVEL)})")
    for required in ("launch", "sim_time_s", "evaluation"):
        if required not in raw:
            raise _fail(path, f"the entry '{required}' is missing")

    launch = str(raw["launch"])
    if Path(launch).is_absolute():
        launch_file, package = Path(launch), ""
    else:
        package, _, file_name = launch.partition("/")
        if not file_name:
            raise _fail(path, f"launch '{launch}': write <package>/<file>.launch or an absolute path")
        launch_file = _package_path(package) / "launch" / file_name
        if not launch_file.exists():
            launch_file = _package_path(package) / file_name
    if not launch_file.exists():
        raise _fail(path, f"launch '{launch}': the file does not exist")
    launch_args = declared_launch_args(launch_file)
    for required in ("lockstep", "enable_logging"):
        if required not in launch_args:
            raise _fail(path, f"launch '{launch}' has no '{required}' argument; sweeps fly in lockstep and record a " f"bag")

    def number(key: str, default: Any, kind=float, minimum: float = 0.0) -> Any:
        value = raw.get(key, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or (kind is int and int(value) != value) or value < minimum:
            raise _fail(path, f"'{key}': {value!r} is not a {'whole ' if kind is int else ''}number >= {minimum}")
        return kind(value)

    sim_time_s = number("sim_time_s", None, minimum=1.0)
    wall_limit_s = number("wall_limit_s", 300.0, minimum=10.0)
    real_time_factor = number("real_time_factor", 0.0)
    repetitions = number("repetitions", 1, int, 1)
    seed = number("seed", 0, int, 0)
    evaluations = raw["evaluation"] if isinstance(raw["evaluation"], list) else [raw["evaluation"]]
    for e in evaluations:
        if e not in EVALUATIONS:
            raise _fail(path, f"evaluation '{e}' is unknown (known: {', '.join(EVALUATIONS)})")
    eval_options = raw.get("eval_options") or {}
    if not isinstance(eval_options, dict):
        raise _fail(path, "eval_options is not a mapping")
    for k, v in eval_options.items():
        if k not in EVAL_OPTIONS:
            raise _fail(path, f"eval_options '{k}' is unknown (known: {', '.join(EVAL_OPTIONS)})")
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise _fail(path, f"eval_options '{k}': {v!r} is not a number")

    fixed = raw.get("fixed") or {}
    vary_raw = raw.get("vary") or {}
    for entry, block in (("fixed", fixed), ("vary", vary_raw)):
        if not isinstance(block, dict):
            raise _fail(path, f"'{entry}' is not a mapping of parameter names")
    both = sorted(set(fixed) & set(vary_raw))
    if both:
        raise _fail(path, f"'{both[0]}' is both fixed and varied")
    mav_name = str(fixed.get("launch.mav_name", launch_args.get("mav_name") or "firefly"))
    checker = _Checker(path, launch_file, launch_args)
    for name in fixed:
        checker.check("fixed entry", str(name), mav_name)
    for name in vary_raw:
        checker.check("vary entry", str(name), mav_name)
    if "launch.mav_name" in vary_raw and any(str(n).startswith("controller.") for n in {**fixed, **vary_raw}):
        raise _fail(
            path, "vary entry 'launch.mav_name': controller parameters are checked against one vehicle; " "sweep one vehicle per file"
        )

    engine = str(raw.get("engine", "world"))
    if engine not in ENGINES:
        raise _fail(path, f"engine '{engine}' is unknown (known: {', '.join(ENGINES)})")
    if engine == "batch":
        from rotors_evaluation.sweep_batch import unsupported

        why = unsupported(launch_file, list(evaluations), [str(n) for n in {**fixed, **vary_raw}])
        if why:
            raise _fail(path, why)
        if raw.get("inject_failure") is not None:
            raise _fail(path, "inject_failure kills a flight's simulator process; engine batch has none (engine: world)")

    # an evaluation needs what it reads to be in the bag
    if "estimator" in evaluations and "msf_core/odometry" not in _recorded_topics(fixed, launch_args):
        raise _fail(
            path,
            f"evaluation 'estimator': {launch_file.name} records no msf_core/odometry (its bag holds "
            f"RotorS' topics and log_extra_topics '{_recorded_topics(fixed, launch_args)}')",
        )

    inject = raw.get("inject_failure")
    if inject is not None:
        if not (isinstance(inject, dict) and set(inject) == {"flight", "at_sim_s"}):
            raise _fail(
                path,
                "inject_failure: write {flight: <index>, at_sim_s: <time>} (the simulator of that "
                "flight is killed at that sim time, to test how a sweep records a crash)",
            )

    vary = {str(n): _expand_range(path, str(n), v, seed) for n, v in vary_raw.items()}
    spec = SweepSpec(
        str(raw.get("name") or path.stem),
        path,
        package,
        launch_file,
        launch_args,
        sim_time_s,
        wall_limit_s,
        repetitions,
        seed,
        list(evaluations),
        {k: float(v) for k, v in eval_options.items()},
        bool(raw.get("keep_bags", False)),
        {str(k): v for k, v in fixed.items()},
        vary,
        inject,
        real_time_factor,
        engine=engine,
    )
    spec.flights = expand(spec)
    if inject is not None and not 0 <= inject["flight"] < len(spec.flights):
        raise _fail(path, f"inject_failure: flight {inject['flight']} does not exist (0 to {len(spec.flights) - 1})")
    return spec


def expand(spec: SweepSpec) -> list[Flight]:
    """The grid of varied values times the repetitions. A flight's id hashes everything that
    defines it (not its place in the grid), so a resumed sweep recognises finished flights and an
    edited one re-flies only what changed."""
    names = list(spec.vary)
    flights = []
    combos: list[tuple] = list(itertools.product(*(spec.vary[n] for n in names))) if names else [()]
    for combo in combos:
        for r in range(spec.repetitions):
            params = dict(zip(names, combo))
            flight = Flight(len(flights), params, r, spec.seed + r)
            identity = json.dumps(
                {
                    "launch": str(spec.launch_file),
                    "fixed": spec.fixed,
                    "params": params,
                    **({"engine": spec.engine} if spec.engine != "world" else {}),
                    "real_time_factor": spec.real_time_factor,
                    "seed": flight.seed,
                    "sim_time_s": spec.sim_time_s,
                    "evaluations": spec.evaluations,
                    "eval_options": spec.eval_options,
                    "inject": spec.inject_failure if spec.inject_failure and spec.inject_failure["flight"] == flight.index else None,
                },
                sort_keys=True,
                default=str,
            )
            flight.id = hashlib.sha256(identity.encode()).hexdigest()[:12]
            if any(f.id == flight.id for f in flights):  # a value listed twice: a flight of its own
                flight.id += f"-{flight.index}"
            flights.append(flight)
    return flights
