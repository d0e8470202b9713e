"""A vehicle's robot description (the URDF that xacro made, as the bag plugin records it on
<ns>/robot_description): where its links are, and the parameters its plugins were given."""

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np


class DescriptionError(ValueError):
    """A robot description that cannot answer the question; the message says what is missing."""


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's fixed-axis rpy: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), math.sin(yaw)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _origin(joint: ET.Element) -> np.ndarray:
    T = np.eye(4)
    origin = joint.find("origin")
    if origin is not None:
        T[:3, 3] = [float(v) for v in origin.get("xyz", "0 0 0").split()]
        T[:3, :3] = _rpy_matrix(*[float(v) for v in origin.get("rpy", "0 0 0").split()])
    return T


@dataclass
class RobotDescription:
    root: ET.Element

    @staticmethod
    def parse(text: str) -> "RobotDescription":
        try:
            return RobotDescription(ET.fromstring(text))
        except ET.ParseError as e:
            raise DescriptionError(f"the robot description is not XML: {e}") from e

    def link_pose(self, link: str) -> np.ndarray:
        """T_RL: link `link` in the root link's frame, through the joints' origins at their zero
        position (the sensor mounts are fixed or zero-range joints)."""
        parent_of = {j.find("child").get("link"): j for j in self.root.iter("joint") if j.find("child") is not None}
        names = {lk.get("name") for lk in self.root.iter("link")}
        if link not in names:
            raise DescriptionError(f"the robot description has no link '{link}'")
        T = np.eye(4)
        while link in parent_of:
            joint = parent_of[link]
            T = _origin(joint) @ T
            link = joint.find("parent").get("link")
        return T

    def transform(self, from_link: str, to_link: str) -> np.ndarray:
        """T_AB: link B (`to_link`) in link A's frame (`from_link`)."""
        return np.linalg.inv(self.link_pose(from_link)) @ self.link_pose(to_link)

    def plugin_params(self, filename: str, **match: str) -> dict[str, str]:
        """The children of the <plugin filename=...> whose children named in `match` have those
        texts (e.g. robotNamespace="firefly/vi_sensor", imuTopic="imu")."""
        found = []
        for plugin in self.root.iter("plugin"):
            if plugin.get("filename") != filename:
                continue
            params = {child.tag: (child.text or "").strip() for child in plugin}
            if all(params.get(k) == v for k, v in match.items()):
                found.append(params)
        if len(found) != 1:
            wanted = ", ".join(f"{k}={v}" for k, v in match.items())
            raise DescriptionError(f"the robot description has {len(found)} {filename} plugins with {wanted}; one expected")
        return found[0]
