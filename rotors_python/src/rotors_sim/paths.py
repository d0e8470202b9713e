"""Where the packages' files are (ROS_PACKAGE_PATH through rospkg: no ROS master needed)."""

from __future__ import annotations

import functools
from pathlib import Path

import rospkg

from rotors_sim._engine import SimError


@functools.cache
def package_path(name: str) -> Path:
    try:
        return Path(rospkg.RosPack().get_path(name))
    except rospkg.ResourceNotFound:
        raise SimError(f"package '{name}' not found on ROS_PACKAGE_PATH (source scripts/env.bash)") from None


def world_file(name: str) -> Path:
    """A world by name (rotors_gazebo/worlds/<name>.world) or by path."""
    path = Path(name)
    if path.suffix in (".world", ".sdf") or path.exists():
        if not path.exists():
            raise SimError(f"world file '{name}' does not exist")
        return path
    path = package_path("rotors_gazebo") / "worlds" / f"{name}.world"
    if not path.exists():
        known = sorted(p.stem for p in path.parent.glob("*.world"))
        raise SimError(f"unknown world '{name}' (known: {' '.join(known)})")
    return path


def resource(name: str) -> Path:
    return package_path("rotors_gazebo") / "resource" / name
