"""Domain randomisation of FlightBatch's airframes: a spec names, per airframe parameter (as the SDF
and xacro name it), the distribution of a factor on the vehicle's own value (or, for the CoG, of
an offset in metres), and every vehicle draws its airframe from it at every reset, from its
episode's generator (so one seed gives one airframe, and the next episode another).

    spec = {"mass": ("uniform", 0.8, 1.2), "motorConstant": ("normal", 1.0, 0.05),
            "timeConstantUp": ("uniform", 0.8, 1.5), "cog": ("uniform", -0.01, 0.01)}
    envs = FlightBatchEnv("hover", 64, randomization=spec)

Per-rotor parameters draw one factor per rotor; "inertia" one per body axis (the tensor scaled as
S I S with S = diag(sqrt(s_x), sqrt(s_y), sqrt(s_z)), so its diagonal is s I_ii and it stays
positive definite); "cog" one offset per axis; "actuatorDelay" a whole number of physics steps
(uniform: each of low..high alike; normal: rounded, at least 0); the wind plugin's parameters
("windForceMean" [N], "windGustStart" [s], ...) one value each, in the SDF's units (a vehicle
spawned with a wind plugin, e.g. model=mav_with_wind_gust.gazebo); the IMU plugin's noise
("gyroscopeNoiseDensity", "accelerometerTurnOnBiasSigma", ...) a factor on the vehicle's value; the
odometry plugin's noise ("noiseNormalPosition" [m], "noiseNormalQuaternion" [rad], ...) one value per
axis in the SDF's units (the shipped odometry sensors have none, so a factor would leave it 0). A
draw that leaves a value out of its plugin's range (a factor <= 0 where the parameter must be > 0, a
negative sigma) is an error naming the parameter.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from rotors_sim._engine import SimError

ROTOR_PARAMETERS = (
    "motorConstant",
    "momentConstant",
    "rotorDragCoefficient",
    "rollingMomentCoefficient",
    "timeConstantUp",
    "timeConstantDown",
    "maxRotVelocity",
)
# the wind plugin's (a vehicle spawned with one): drawn as values in the SDF's units, not factors
WIND_PARAMETERS = (
    "windSpeedMean",
    "windSpeedVariance",
    "windForceMean",
    "windForceVariance",
    "windGustStart",
    "windGustDuration",
    "windGustForceMean",
    "windGustForceVariance",
)
# the IMU plugin's noise: factors on the vehicle's own values
IMU_NOISE_PARAMETERS = (
    "gyroscopeNoiseDensity",
    "gyroscopeRandomWalk",
    "gyroscopeBiasCorrelationTime",
    "gyroscopeTurnOnBiasSigma",
    "accelerometerNoiseDensity",
    "accelerometerRandomWalk",
    "accelerometerBiasCorrelationTime",
    "accelerometerTurnOnBiasSigma",
)
# the odometry plugin's noise: one value per axis, in the SDF's units
ODOMETRY_NOISE_PARAMETERS = (
    "noiseNormalPosition",
    "noiseNormalQuaternion",
    "noiseNormalLinearVelocity",
    "noiseNormalAngularVelocity",
    "noiseUniformPosition",
    "noiseUniformQuaternion",
    "noiseUniformLinearVelocity",
    "noiseUniformAngularVelocity",
)
PARAMETERS = (
    "mass",
    "inertia",
    "cog",
    "actuatorDelay",
    *ROTOR_PARAMETERS,
    *WIND_PARAMETERS,
    *IMU_NOISE_PARAMETERS,
    *ODOMETRY_NOISE_PARAMETERS,
)
DISTRIBUTIONS = ("uniform", "normal", "fixed")


def check_spec(spec: Mapping[str, Any] | None) -> dict[str, tuple]:
    """The spec as {name: (distribution, a, b)}; SimError naming an unknown parameter, an unknown
    distribution or bad bounds."""
    if spec is None:
        return {}
    if not isinstance(spec, Mapping):
        raise SimError(f"randomization must be a dict of parameter: (distribution, a, b), got {spec!r}")
    out = {}
    for name, entry in spec.items():
        if name not in PARAMETERS:
            raise SimError(f"randomization: '{name}' is not an airframe parameter; use one of: {', '.join(PARAMETERS)}")
        entry = (entry,) if isinstance(entry, str) else tuple(entry)
        kind = entry[0] if entry else None
        if kind not in DISTRIBUTIONS:
            raise SimError(f"randomization['{name}']: distribution {kind!r} is not known; use uniform, normal or fixed")
        wanted = {"uniform": 3, "normal": 3, "fixed": 2}[kind]
        if len(entry) != wanted or not all(np.isfinite(float(x)) for x in entry[1:]):
            form = {"uniform": "('uniform', low, high)", "normal": "('normal', mean, sigma)", "fixed": "('fixed', value)"}[kind]
            raise SimError(f"randomization['{name}'] = {entry!r}: give {form} with finite numbers")
        if kind == "uniform" and float(entry[1]) > float(entry[2]):
            raise SimError(f"randomization['{name}']: low {entry[1]} > high {entry[2]}")
        if kind == "normal" and float(entry[2]) < 0.0:
            raise SimError(f"randomization['{name}']: sigma {entry[2]} must be >= 0")
        out[name] = (kind, *(float(x) for x in entry[1:]))
    return out


def _sizes(spec: Mapping[str, tuple], nominal: Mapping[str, Any]) -> list[tuple[str, int]]:
    """The spec's parameters in PARAMETERS' order, each with the number of values it draws."""
    sizes = []
    for name in PARAMETERS:
        if name not in spec:
            continue
        if name in ("inertia", "cog") or name in ODOMETRY_NOISE_PARAMETERS:
            sizes.append((name, 3))
        elif name in ROTOR_PARAMETERS:
            sizes.append((name, len(nominal[name])))
        else:
            sizes.append((name, 1))
    return sizes


def _draws(spec: Mapping[str, tuple], sizes: list[tuple[str, int]], rngs: list[np.random.Generator]) -> dict[str, np.ndarray]:
    """Each vehicle's draws (one row per generator), each generator called once for all of its
    uniform values and once for all of its normal ones: {name: len(rngs) x size}."""
    uniform = [(name, n) for name, n in sizes if spec[name][0] == "uniform"]
    normal = [(name, n) for name, n in sizes if spec[name][0] == "normal"]
    u_count, z_count = sum(n for _, n in uniform), sum(n for _, n in normal)
    u = np.array([rng.random(u_count) for rng in rngs]).reshape(len(rngs), u_count)
    z = np.array([rng.standard_normal(z_count) for rng in rngs]).reshape(len(rngs), z_count)
    out: dict[str, np.ndarray] = {}
    at = 0
    for name, n in uniform:
        low, high = spec[name][1], spec[name][2]
        if name == "actuatorDelay":  # a whole number of steps, each of ceil(low)..floor(high) alike
            first, last = int(np.ceil(low)), int(np.floor(high))
            if last < first:
                raise SimError(f"randomization['actuatorDelay'] = ('uniform', {low}, {high}) holds no whole number of steps")
            out[name] = np.minimum(first + np.floor(u[:, at : at + n] * (last - first + 1)), last)
        else:
            out[name] = low + (high - low) * u[:, at : at + n]
        at += n
    at = 0
    for name, n in normal:
        out[name] = spec[name][1] + spec[name][2] * z[:, at : at + n]
        if name == "actuatorDelay":
            out[name] = np.maximum(0.0, np.round(out[name]))
        at += n
    for name, n in sizes:
        if spec[name][0] == "fixed":
            out[name] = np.full((len(rngs), n), spec[name][1])
    return out


def _first_bad(values: np.ndarray, ok: np.ndarray) -> np.ndarray | None:
    """The first row of `values` (one vehicle's draw) where `ok` is False anywhere, or None."""
    if ok.all():  # the common case, in one reduction
        return None
    return values[np.flatnonzero(~ok.all(axis=1))[0]]


def draw_airframe_rows(spec: Mapping[str, tuple], nominal: Mapping[str, Any], rngs: list[np.random.Generator]) -> dict[str, np.ndarray]:
    """One airframe per generator from `spec` (check_spec's form) around `nominal`
    (FlightBatch.nominal_airframe), as FlightBatch.set_airframes takes them: {name: one row per
    generator}. Each generator draws its uniform values in one call and its normal ones in another,
    in PARAMETERS' order (the parameters of the spec draw, the others do not), and the values are
    checked as the plugins check theirs (SimError naming the first bad one)."""
    draws = _draws(spec, _sizes(spec, nominal), rngs)
    values: dict[str, np.ndarray] = {}
    for name, d in draws.items():
        if name == "mass":
            bad = _first_bad(d, d > 0.0)
            if bad is not None:
                raise SimError(f"randomization drew a mass factor of {bad[0]:.4g}; the mass must stay > 0 (narrow its range)")
            values[name] = nominal["mass"] * d[:, 0]
        elif name == "inertia":
            bad = _first_bad(d, d > 0.0)
            if bad is not None:
                raise SimError(f"randomization drew inertia factors {np.round(bad, 4).tolist()}; each must be > 0")
            s = np.sqrt(d)  # S I S with S = diag(sqrt(s)): element (j, k) scaled by sqrt(s_j s_k)
            values[name] = s[:, :, None] * np.asarray(nominal["inertia"])[None, :, :] * s[:, None, :]
        elif name == "cog":
            values[name] = np.asarray(nominal["cog"])[None, :] + d
        elif name in WIND_PARAMETERS:
            if name.endswith("Variance") or name == "windGustDuration":
                bad = _first_bad(d, d >= 0.0)
                if bad is not None:
                    raise SimError(f"randomization drew {name} = {bad[0]:.4g}; it must be >= 0 (narrow its range)")
            values[name] = d[:, 0]
        elif name in IMU_NOISE_PARAMETERS:
            positive = name.endswith("CorrelationTime")
            bad = _first_bad(d, d > 0.0 if positive else d >= 0.0)
            if bad is not None:
                raise SimError(
                    f"randomization drew a {name} factor of {bad[0]:.4g}; it must be {'> 0' if positive else '>= 0'} (narrow its range)"
                )
            values[name] = float(nominal[name]) * d[:, 0]
        elif name in ODOMETRY_NOISE_PARAMETERS:
            bad = _first_bad(d, d >= 0.0)
            if bad is not None:
                raise SimError(f"randomization drew {name} = {np.round(bad, 6).tolist()}; each must be >= 0 (narrow its range)")
            values[name] = d
        elif name == "actuatorDelay":
            values[name] = d[:, 0].astype(np.int64)
        else:
            must_be_positive = name in ("motorConstant", "timeConstantUp", "timeConstantDown")  # maxRotVelocity 0: failed
            bad = _first_bad(d, (d > 0.0) if must_be_positive else (d >= 0.0))
            if bad is not None:
                raise SimError(
                    f"randomization drew {name} factors {np.round(bad, 4).tolist()}; "
                    f"each must be {'> 0' if must_be_positive else '>= 0'} (narrow its range)"
                )
            values[name] = np.asarray(nominal[name], dtype=float)[None, :] * d
    return values


def draw_airframes(spec: Mapping[str, tuple], nominal: Mapping[str, Any], rngs: list[np.random.Generator]) -> list[dict[str, Any]]:
    """draw_airframe_rows' airframes, one dict per generator (FlightBatch.set_airframe's keywords)."""
    rows = draw_airframe_rows(spec, nominal, rngs)
    scalars = {"mass", "actuatorDelay", *WIND_PARAMETERS, *IMU_NOISE_PARAMETERS}
    return [{name: (v[i].item() if name in scalars else v[i]) for name, v in rows.items()} for i in range(len(rngs))]


def draw_airframe(spec: Mapping[str, tuple], nominal: Mapping[str, Any], rng: np.random.Generator) -> dict[str, Any]:
    """One airframe from `spec` around `nominal`, drawn from `rng` (draw_airframes for one)."""
    return draw_airframes(spec, nominal, [rng])[0]
