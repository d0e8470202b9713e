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


def _draw(entry: tuple, rng: np.random.Generator, size: int) -> np.ndarray:
    kind = entry[0]
    if kind == "uniform":
        return rng.uniform(entry[1], entry[2], size)
    if kind == "normal":
        return rng.normal(entry[1], entry[2], size)
    return np.full(size, entry[1])


def draw_airframe(spec: Mapping[str, tuple], nominal: Mapping[str, Any], rng: np.random.Generator) -> dict[str, Any]:
    """One airframe from `spec` (check_spec's form) around `nominal` (FlightBatch.nominal_airframe),
    drawn from `rng` in PARAMETERS' order (each parameter of the spec draws, the others do not)."""
    out: dict[str, Any] = {}
    for name in PARAMETERS:
        if name not in spec:
            continue
        if name == "mass":
            factor = float(_draw(spec[name], rng, 1)[0])
            if not factor > 0.0:
                raise SimError(f"randomization drew a mass factor of {factor:.4g}; the mass must stay > 0 (narrow its range)")
            out["mass"] = nominal["mass"] * factor
        elif name == "inertia":
            factors = _draw(spec[name], rng, 3)
            if not np.all(factors > 0.0):
                raise SimError(f"randomization drew inertia factors {np.round(factors, 4).tolist()}; each must be > 0")
            s = np.diag(np.sqrt(factors))
            out["inertia"] = s @ np.asarray(nominal["inertia"]) @ s
        elif name == "cog":
            out["cog"] = np.asarray(nominal["cog"]) + _draw(spec[name], rng, 3)
        elif name in WIND_PARAMETERS:
            value = float(_draw(spec[name], rng, 1)[0])
            if (name.endswith("Variance") or name == "windGustDuration") and value < 0.0:
                raise SimError(f"randomization drew {name} = {value:.4g}; it must be >= 0 (narrow its range)")
            out[name] = value
        elif name in IMU_NOISE_PARAMETERS:
            factor = float(_draw(spec[name], rng, 1)[0])
            positive = name.endswith("CorrelationTime")
            if not (factor > 0.0 if positive else factor >= 0.0):
                raise SimError(
                    f"randomization drew a {name} factor of {factor:.4g}; it must be {'> 0' if positive else '>= 0'} (narrow its range)"
                )
            out[name] = float(nominal[name]) * factor
        elif name in ODOMETRY_NOISE_PARAMETERS:
            values = _draw(spec[name], rng, 3)
            if not np.all(values >= 0.0):
                raise SimError(f"randomization drew {name} = {np.round(values, 6).tolist()}; each must be >= 0 (narrow its range)")
            out[name] = values
        elif name == "actuatorDelay":
            entry = spec[name]
            if entry[0] == "uniform":
                out[name] = int(rng.integers(int(np.ceil(entry[1])), int(np.floor(entry[2])) + 1))
            else:
                out[name] = max(0, int(round(float(_draw(entry, rng, 1)[0]))))
        else:
            value = np.asarray(nominal[name], dtype=float)
            factors = _draw(spec[name], rng, len(value))
            must_be_positive = name in ("motorConstant", "timeConstantUp", "timeConstantDown")  # maxRotVelocity 0: failed
            if (must_be_positive and not np.all(factors > 0.0)) or not np.all(factors >= 0.0):
                raise SimError(
                    f"randomization drew {name} factors {np.round(factors, 4).tolist()}; "
                    f"each must be {'> 0' if must_be_positive else '>= 0'} (narrow its range)"
                )
            out[name] = value * factors
    return out
