"""RotorS' message packages (mav_msgs, mav_planning_msgs, rotors_comm, dvs_msgs, octomap_msgs) as ROS 2
interface packages (rotors_gazebo_compat/rotors_ros2/interfaces, built by make setup with PyPI's
Jazzy rosidl wheels): every message of each ROS 1 package is there with the same fields in the same
order and the same constants, in ROS 2's form (std_msgs/Header, builtin_interfaces/Time and Duration;
field names in lower case, as rosidl requires: GpsWaypoint's maxSpeed, maxAcc become max_speed,
max_acc). Read from the generated Python classes in build/ros2-venv, against the ROS 1 .msg files."""

import json
import re
import subprocess

import pytest

from support import REPO

pytestmark = pytest.mark.ros2

# ROS 1 builtin -> the rosidl type string of get_fields_and_field_types()
BUILTIN = {
    "float64": "double",
    "float32": "float",
    "int32": "int32",
    "uint32": "uint32",
    "uint64": "uint64",
    "uint8": "uint8",
    "uint16": "uint16",
    "int8": "int8",
    "bool": "boolean",
    "string": "string",
}


def ros2_form(ros1_type: str, package: str) -> str:
    base, array = (ros1_type[:-2], True) if ros1_type.endswith("[]") else (ros1_type, False)
    named = {"Header": "std_msgs/Header", "time": "builtin_interfaces/Time", "duration": "builtin_interfaces/Duration"}
    base = named.get(base, BUILTIN.get(base, base))
    if base[0].isupper():  # a message of the same package
        base = f"{package}/{base}"
    return f"sequence<{base}>" if array else base


def ros1_definition(path, package: str) -> tuple[list, dict]:
    fields, constants = [], {}
    for line in path.read_text().splitlines():
        code = line.split("#", 1)[0].strip()
        if not code:
            continue
        if "=" in code:
            name, value = code.split(None, 1)[1].split("=", 1)
            constants[name.strip()] = value.strip()
        else:
            typ, name = code.split()
            fields.append([re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower(), ros2_form(typ, package)])
    return fields, constants


@pytest.mark.parametrize("package", ["mav_msgs", "mav_planning_msgs", "rotors_comm", "dvs_msgs", "octomap_msgs"])
def test_the_ros2_interface_packages_have_the_ros1_fields_and_constants(package: str):
    python = REPO / "build" / "ros2-venv" / "bin" / "python"
    assert python.exists(), "no build/ros2-venv: run make ros2-setup"
    ros1 = REPO / "rotors_msgs" / package / "msg"
    names = sorted(p.stem for p in ros1.glob("*.msg"))
    probe = (
        f"import json, {package}.msg as m\n"
        f"out = {{}}\nfor n in {names!r}:\n"
        "    c = getattr(m, n)\n"
        "    consts = {k: getattr(c, k) for k in dir(c) if k.isupper() and isinstance(getattr(c, k), (str, int, float))}\n"
        "    out[n] = [list(map(list, c.get_fields_and_field_types().items())), consts]\n"
        "print(json.dumps(out))"
    )
    # in ROS 2's environment: ROS 1's mav_msgs (the devel space on PYTHONPATH) has the same module name
    res = subprocess.run(
        ["bash", "-c", f'source {REPO}/scripts/ros2_env.bash; exec python -c "$0"', probe], capture_output=True, text=True, timeout=60
    )
    assert res.returncode == 0, res.stderr[-2000:]
    ros2 = json.loads(res.stdout.strip().splitlines()[-1])
    for name in names:
        fields, constants = ros1_definition(ros1 / f"{name}.msg", package)
        assert ros2[name][0] == fields, name
        assert ros2[name][1] == {k: int(v) if v.isdigit() else v.strip('"') for k, v in constants.items()}, name
    print(f"{package}: {len(names)} messages: {', '.join(names)}; {sum(len(c) for _, c in ros2.values())} constants")
