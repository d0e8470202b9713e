#!/usr/bin/env bash
# make ros2-setup: PyPI's ROS 2 Jazzy wheels (rclpy with Fast DDS and the message packages the ROS 2
# front end uses, scripts/ros2-requirements.txt) in a venv of their own, build/ros2-venv. Their .pth
# re-executes Python to set the library path, and their message packages share module names with
# ROS 1's, so they stay out of the ROS 1 venv (build/venv). Idempotent: a second run checks the pins.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="$root/build/ros2-venv"
requirements="$root/scripts/ros2-requirements.txt"
if [ -f "$venv/.requirements" ] && cmp -s "$venv/.requirements" "$requirements"; then
  echo "[ros2-setup] ok ($venv)"
  exit 0
fi
python3 -m venv "$venv"
"$venv/bin/pip" install -q -r "$requirements"
"$venv/bin/python" -c "import rclpy, nav_msgs.msg, sensor_msgs.msg, trajectory_msgs.msg, std_srvs.srv, rosgraph_msgs.msg, rosbags.rosbag2"
cp "$requirements" "$venv/.requirements"
echo "[ros2-setup] ok ($venv)"
