"""The "own catkin workspace" recipe of docs/rotors_compatibility.md, as a new user runs it: the package folder linked into a
fresh workspace's src, `catkin_make -DPYTHON_EXECUTABLE=<venv python>`, and the evaluation started
with `rosrun` from that workspace's devel space. (The recipe links every package; this links
rotors_evaluation, whose wrappers are what the recipe's PYTHON_EXECUTABLE is for, so that the test
builds in seconds. The venv is the project's build/venv, made as the recipe makes one.)"""

import os
import subprocess
import sys
from pathlib import Path

from synthetic_bags import write_flight

PACKAGE = Path(__file__).resolve().parents[1]


def test_readme_recipe_workspace_rosrun_evaluates_a_bag(tmp_path: Path):
    venv_python = Path(sys.executable)  # build/venv/bin/python: --system-site-packages, requirements.txt
    ws = tmp_path / "catkin_ws"
    (ws / "src").mkdir(parents=True)
    (ws / "src" / PACKAGE.name).symlink_to(PACKAGE)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH"))}
    env["CMAKE_PREFIX_PATH"] = "/usr"  # a user's plain ROS environment: Debian's ROS only
    env["PATH"] = "/usr/bin:/bin"  # no venv on PATH: the -D alone must pick the interpreter
    env["PWD"] = str(ws)  # catkin_make takes the workspace from PWD, as after `cd ..`
    built = subprocess.run(
        ["catkin_make", f"-DPYTHON_EXECUTABLE={venv_python}"], cwd=ws, env=env, capture_output=True, text=True, timeout=600
    )
    assert built.returncode == 0, built.stdout[-3000:] + built.stderr[-3000:]
    wrapper = ws / "devel" / "lib" / "rotors_evaluation" / "hovering_eval.py"
    shebang = wrapper.read_text().splitlines()[0]
    print(f"{wrapper.relative_to(ws)} starts with {shebang}")
    assert shebang == f"#!{venv_python}"

    # set point (0, 0, 1) at 5 s, an offset of (0.04, 0, 0.03) from 10 s on: RMS 0.05 m
    bag = write_flight(
        tmp_path / "hover.bag",
        lambda t: (0.04, 0.0, 1.03) if t > 10.0 else (0.0, 0.0, 0.5),
        lambda t: (0.0, 0.0, 0.0),
        [(5.0, (0.0, 0.0, 1.0))],
    )
    res = subprocess.run(
        [
            "bash",
            "-c",
            f"source {ws}/devel/setup.bash && rosrun rotors_evaluation hovering_eval.py " f"-b {bag} --mav_name firefly --plot False",
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    print(res.stdout[-600:], res.stderr[-600:])
    assert res.returncode == 0 and "Position RMS error: 0.050 m" in res.stdout, res.stderr
