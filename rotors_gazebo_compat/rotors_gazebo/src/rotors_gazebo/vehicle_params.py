"""Controller parameters of a vehicle computed from its URDF, so that a new vehicle hovers first time.

The simulated vehicle is the URDF that spawn_mav.launch spawns: the body, the rotors, the IMU and
odometry sensor links. Its total mass, its centre of mass and its inertia about the centre of mass
(parallel-axis theorem, every link at zero joint angles) are what the Lee controller needs in
`<mav>.yaml`; the rotor geometry and constants come from the motor plugins' blocks. Gains are those of
the most similar shipped vehicle (rotor count, mass, inertia), scaled to the new vehicle: the Lee law divides the position
and velocity terms by the mass (a = (k_p e_p + k_v e_v) / m) and normalises the attitude gains by
the inertia (k_R J^-1, k_omega J^-1), so k_p, k_v scale with m and k_R, k_omega with J per axis.
"""

import math
import re
import subprocess
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml


class VehicleParamsError(Exception):
    """A problem worded for the user (one line)."""


@dataclass
class Rotor:
    number: int
    position_B: np.ndarray  # [m] rotor hub in the body frame, relative to the centre of mass
    direction: int  # 1 ccw, -1 cw (seen from above)
    force_constant: float  # [N/(rad/s)^2]
    moment_constant: float  # [m]
    max_rot_velocity: float  # [rad/s]


@dataclass
class RigidBody:
    mass_kg: float
    com_B: np.ndarray  # [m] centre of mass in the body (base_link) frame
    inertia_kg_m2: np.ndarray  # (3, 3) about the centre of mass, body axes
    rotors: list[Rotor] = field(default_factory=list)


def _rpy_matrix(rpy: tuple[float, float, float]) -> np.ndarray:
    """URDF fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _origin(elem: ET.Element | None) -> tuple[np.ndarray, np.ndarray]:
    if elem is None:
        return np.zeros(3), np.eye(3)
    xyz = np.array([float(v) for v in elem.get("xyz", "0 0 0").split()])
    rpy = tuple(float(v) for v in elem.get("rpy", "0 0 0").split())
    return xyz, _rpy_matrix(rpy)


def _link_poses(robot: ET.Element, root: str) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Pose (p, R) of every link in the root link's frame, joints at zero."""
    children: dict[str, list[ET.Element]] = {}
    for joint in robot.findall("joint"):
        children.setdefault(joint.find("parent").get("link"), []).append(joint)
    poses = {root: (np.zeros(3), np.eye(3))}
    stack = [root]
    while stack:
        parent = stack.pop()
        p_parent, R_parent = poses[parent]
        for joint in children.get(parent, []):
            p_j, R_j = _origin(joint.find("origin"))
            child = joint.find("child").get("link")
            poses[child] = (p_parent + R_parent @ p_j, R_parent @ R_j)
            stack.append(child)
    return poses


def rigid_body_from_urdf(urdf: str, base_link: str) -> RigidBody:
    robot = ET.fromstring(urdf)
    names = {link.get("name") for link in robot.findall("link")}
    if base_link not in names:
        raise VehicleParamsError(f"the URDF has no link '{base_link}' (links: {', '.join(sorted(names))})")
    poses = _link_poses(robot, base_link)
    masses, coms, inertias = [], [], []
    for link in robot.findall("link"):
        inertial = link.find("inertial")
        if inertial is None or link.get("name") not in poses:
            continue
        p_L, R_L = poses[link.get("name")]
        p_I, R_I = _origin(inertial.find("origin"))
        i = inertial.find("inertia")
        I_I = np.array(
            [
                [float(i.get("ixx")), float(i.get("ixy")), float(i.get("ixz"))],
                [float(i.get("ixy")), float(i.get("iyy")), float(i.get("iyz"))],
                [float(i.get("ixz")), float(i.get("iyz")), float(i.get("izz"))],
            ]
        )
        R = R_L @ R_I
        masses.append(float(inertial.find("mass").get("value")))
        coms.append(p_L + R_L @ p_I)
        inertias.append(R @ I_I @ R.T)
    m = float(sum(masses))
    com = sum(mi * ci for mi, ci in zip(masses, coms)) / m
    # parallel-axis theorem: J = sum R_i J_i R_i^T + m_i (|d|^2 1 - d d^T), d = c_i - c
    J = sum(Ji + mi * (np.dot(ci - com, ci - com) * np.eye(3) - np.outer(ci - com, ci - com)) for mi, ci, Ji in zip(masses, coms, inertias))
    body = RigidBody(m, com, J)
    for plugin in robot.iter("plugin"):
        if "motor_model" not in plugin.get("filename", ""):
            continue
        text = {child.tag: (child.text or "").strip() for child in plugin}
        if text.get("motorType") == "position":  # a servo (the omav's tilt units), not a rotor
            continue
        link = text.get("linkName", "")
        if link not in poses:
            raise VehicleParamsError(f"motor plugin '{plugin.get('name')}': linkName '{link}' is not a link of the URDF")
        for key in ("motorNumber", "turningDirection", "motorConstant", "momentConstant", "maxRotVelocity"):
            if key not in text:
                raise VehicleParamsError(f"motor plugin '{plugin.get('name')}' has no <{key}>")
        body.rotors.append(
            Rotor(
                int(text["motorNumber"]),
                poses[link][0] - com,
                1 if text["turningDirection"] == "ccw" else -1,
                float(text["motorConstant"]),
                float(text["momentConstant"]),
                float(text["maxRotVelocity"]),
            )
        )
    body.rotors.sort(key=lambda r: r.number)
    if [r.number for r in body.rotors] != list(range(len(body.rotors))) or not body.rotors:
        raise VehicleParamsError(f"motor numbers {[r.number for r in body.rotors]} are not 0..N-1")
    return body


def world_gravity(world_file: Path) -> float:
    """|g| [m/s^2] of a .world file (SDF <gravity>), 9.8 when it names none (Gazebo's default)."""
    match = re.search(r"<gravity>\s*([-\d.eE+]+)\s+([-\d.eE+]+)\s+([-\d.eE+]+)\s*</gravity>", world_file.read_text())
    return float(np.linalg.norm([float(v) for v in match.groups()])) if match else 9.8


def vehicle_yaml(body: RigidBody, gravity: float) -> dict:
    J = body.inertia_kg_m2
    rotors = {}
    for r in body.rotors:
        rotors[str(r.number)] = {
            "angle": float(math.atan2(r.position_B[1], r.position_B[0])),
            "arm_length": float(math.hypot(r.position_B[0], r.position_B[1])),
            "rotor_force_constant": r.force_constant,
            "rotor_moment_constant": r.moment_constant,
            "direction": r.direction,
            "max_rot_velocity": r.max_rot_velocity,
        }
    return {
        "mass": round(float(body.mass_kg), 6),
        "inertia": {
            k: round(float(v), 8)
            for k, v in zip(("xx", "xy", "xz", "yy", "yz", "zz"), (J[0, 0], J[0, 1], J[0, 2], J[1, 1], J[1, 2], J[2, 2]))
        },
        "gravity": gravity,
        "rotor_configuration": rotors,
    }


def scaled_gains(reference_gains: dict, reference_vehicle: dict, body: RigidBody) -> dict:
    ratio_m = body.mass_kg / reference_vehicle["mass"]
    ref_J = reference_vehicle["inertia"]
    ratio_J = {
        "x": body.inertia_kg_m2[0, 0] / ref_J["xx"],
        "y": body.inertia_kg_m2[1, 1] / ref_J["yy"],
        "z": body.inertia_kg_m2[2, 2] / ref_J["zz"],
    }
    out = {}
    for key in ("position_gain", "velocity_gain"):
        out[key] = {a: round(float(v) * float(ratio_m), 4) for a, v in reference_gains[key].items()}
    for key in ("attitude_gain", "angular_rate_gain"):
        out[key] = {a: round(float(v) * float(ratio_J[a]), 4) for a, v in reference_gains[key].items()}
    if "max_tilt_angle" in reference_gains:  # a limit of the motion, not of the vehicle's size
        out["max_tilt_angle"] = reference_gains["max_tilt_angle"]
    return out


def closest_shipped(resource: Path, body: RigidBody, exclude: str) -> str:
    """The shipped vehicle most like `body`: the same number of rotors if there is one, then the
    smallest sum of |log ratio| of mass and principal inertias."""
    J = np.diag(body.inertia_kg_m2)
    candidates = []
    for path in sorted(resource.glob("lee_controller_*.yaml")):
        name = path.stem[len("lee_controller_") :]
        vehicle = resource / f"{name}.yaml"
        if name == exclude or not vehicle.is_file():
            continue
        v = yaml.safe_load(vehicle.read_text())
        J_ref = np.array([v["inertia"]["xx"], v["inertia"]["yy"], v["inertia"]["zz"]])
        distance = abs(math.log(body.mass_kg / v["mass"])) + float(np.abs(np.log(J / J_ref)).sum())
        candidates.append((len(v["rotor_configuration"]) != len(body.rotors), distance, name))
    if not candidates:
        raise VehicleParamsError(f"no shipped vehicle with gains in {resource}")
    return min(candidates)[2]


def run_xacro(xacro_cmd: Path, model: Path, mav_name: str) -> str:
    res = subprocess.run([str(xacro_cmd), str(model), f"mav_name:={mav_name}", f"namespace:={mav_name}"], capture_output=True, text=True)
    if res.returncode != 0:
        lines = (res.stderr or res.stdout).strip().splitlines()
        raise VehicleParamsError(f"xacro failed on {model}: {lines[-1] if lines else 'exit ' + str(res.returncode)}")
    return res.stdout


# ---- checking a controller yaml against the URDF (one source of truth) ------------------------
RELATIVE_TOLERANCE = 1e-3  # masses, inertias, rotor constants, gravity
ROTOR_POSITION_TOLERANCE_M = 5e-3  # rotor hub in the xy plane (a centre of mass a few mm off is fine)
ROTOR_SPEED_TOLERANCE = 1e-6  # max_rot_velocity [rad/s]
DEFAULT_CONTROLLER_GRAVITY = 9.81  # what the controller nodes assume when the yaml gives none


def _differs(a: float, b: float, rel: float = RELATIVE_TOLERANCE) -> bool:
    return abs(a - b) > rel * max(abs(a), abs(b), 1e-12)


def compare_with_urdf(
    mav: str, vehicle: dict, body: RigidBody, world_gravity_m_s2: float, overrides: dict[str, str], yaml_name: str = ""
) -> list[str]:
    """The parameters where the controller yaml `vehicle` (the layout of resource/<mav>.yaml) and the
    parsed URDF disagree, one line each naming the vehicle and the parameter; `overrides` maps the
    names that may differ (mass, inertia, gravity, rotor_configuration/<i>/<field>) to the reason.
    A named override whose values agree is reported too, so the list stays honest. `yaml_name` is how
    the lines name the yaml (default <mav>.yaml)."""
    yaml_name = yaml_name or f"{mav}.yaml"
    urdf = vehicle_yaml(body, world_gravity_m_s2)
    found: list[tuple[str, str]] = []  # (parameter, description)

    def check(name: str, yaml_value: float, urdf_value: float, differs: bool) -> None:
        if differs:
            found.append((name, f"{yaml_value:g} in {yaml_name}, {urdf_value:g} in the URDF"))
        elif name in overrides:
            found.append((name, f"named override, but both give {urdf_value:g}: remove it"))

    check("mass", float(vehicle["mass"]), urdf["mass"], _differs(float(vehicle["mass"]), urdf["mass"]))
    J_yaml, J_urdf = vehicle["inertia"], urdf["inertia"]
    scale = max(abs(J_urdf[k]) for k in ("xx", "yy", "zz"))
    inertia_differs = [
        k
        for k in J_urdf
        if abs(float(J_yaml.get(k, 0.0)) - J_urdf[k]) > RELATIVE_TOLERANCE * scale
        and (k in ("xy", "xz", "yz") or _differs(float(J_yaml.get(k, 0.0)), J_urdf[k]))
    ]
    if inertia_differs or "inertia" in overrides:
        k = inertia_differs[0] if inertia_differs else "xx"
        check("inertia", float(J_yaml.get(k, 0.0)), J_urdf[k], bool(inertia_differs))
    g_yaml = float(vehicle.get("gravity", DEFAULT_CONTROLLER_GRAVITY))
    check("gravity", g_yaml, world_gravity_m_s2, _differs(g_yaml, world_gravity_m_s2))

    rotors_yaml = {str(k): v for k, v in vehicle["rotor_configuration"].items()}
    if sorted(rotors_yaml) != sorted(urdf["rotor_configuration"]):
        found.append(
            ("rotor_configuration", f"rotors {sorted(rotors_yaml)} in {yaml_name}, " f"{sorted(urdf['rotor_configuration'])} in the URDF")
        )
    for i, u in urdf["rotor_configuration"].items():
        r = rotors_yaml.get(i)
        if r is None:
            continue
        base = f"rotor_configuration/{i}/"
        p_yaml = float(r["arm_length"]) * np.array([math.cos(float(r["angle"])), math.sin(float(r["angle"]))])
        p_urdf = u["arm_length"] * np.array([math.cos(u["angle"]), math.sin(u["angle"])])
        distance = float(np.linalg.norm(p_yaml - p_urdf))
        if distance > ROTOR_POSITION_TOLERANCE_M:
            found.append(
                (
                    base + "position",
                    f"angle {float(r['angle']):.4f} rad, arm {float(r['arm_length']):.4f} m "
                    f"in {yaml_name}, {u['angle']:.4f} rad, {u['arm_length']:.4f} m in the URDF "
                    f"({distance * 1000:.1f} mm apart)",
                )
            )
        elif base + "position" in overrides:
            found.append((base + "position", "named override, but the positions agree: remove it"))
        for field_name in ("rotor_force_constant", "rotor_moment_constant"):
            check(base + field_name, float(r[field_name]), u[field_name], _differs(float(r[field_name]), u[field_name]))
        check(base + "direction", int(r["direction"]), u["direction"], int(r["direction"]) != u["direction"])
        if "max_rot_velocity" in r:
            check(
                base + "max_rot_velocity",
                float(r["max_rot_velocity"]),
                u["max_rot_velocity"],
                abs(float(r["max_rot_velocity"]) - u["max_rot_velocity"]) > ROTOR_SPEED_TOLERANCE,
            )
    lines = []
    for name, text in found:
        if name in overrides and not text.startswith("named override"):
            continue
        hint = "" if text.startswith("named override") else " (not a named override)"
        lines.append(f"{mav}: {name}: {text}{hint}")
    return lines
